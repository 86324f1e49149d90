#include "amr/cell_array.h"

#include "core/parallel.h"

#include <algorithm>
#include <atomic>

namespace amrvk::amr {

namespace {
constexpr size_t kChunkCells = (size_t{8} << 20) / sizeof(Cell);  // 8 MiB of records
}

CellArray::CellArray(std::initializer_list<Cell> cells) { append(std::span<const Cell>(cells.begin(), cells.size())); }

void CellArray::widen() {
    if (mWide) return;
    mWideCells.resize(mCompact.size());
    parallelForRanges(0, mCompact.size(), kChunkCells, [&](size_t lo, size_t hi) {
        for (size_t i = lo; i < hi; ++i) mWideCells[i] = decode(mCompact[i]);
    });
    decltype(mCompact)().swap(mCompact);
    mWide = true;
}

void CellArray::copyOut(size_t first, std::span<Cell> out) const {
    if (mWide) std::copy_n(mWideCells.begin() + std::ptrdiff_t(first), out.size(), out.begin());
    else
        for (size_t i = 0; i < out.size(); ++i) out[i] = decode(mCompact[first + i]);
}

bool CellArray::tryStore(size_t first, std::span<const Cell> in) {
    if (mWide) {
        std::copy(in.begin(), in.end(), mWideCells.begin() + std::ptrdiff_t(first));
        return true;
    }
    uint32_t bad = 0;  // one branch-free pass: fits() and pack() together
    uint64_t* out = mCompact.data() + first;
    for (size_t i = 0; i < in.size(); ++i) out[i] = packChecked(in[i], bad);
    return bad == 0;
}

void CellArray::append(std::span<const Cell> in) {
    const size_t first = size();
    resize(first + in.size());
    if (tryStore(first, in)) return;
    widen();
    tryStore(first, in);
}

bool operator==(const CellArray& a, const CellArray& b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (!(a[i] == b[i])) return false;
    return true;
}

void readCells(BinaryReader& reader, uint64_t count, CellArray& out) {
    reader.requireBytes(count > UINT64_MAX / sizeof(Cell) ? UINT64_MAX : count * sizeof(Cell));
    const uint64_t start = reader.offset();
    const size_t chunks = (size_t(count) + kChunkCells - 1) / kChunkCells;
    const auto fill = [&](CellArray& cells) {
        cells.resize(size_t(count));
        std::atomic<bool> allFit{true};
        parallelFor(0, chunks, [&](size_t k) {
            if (!allFit.load(std::memory_order_relaxed)) return;
            const size_t lo = k * kChunkCells, n = std::min(size_t(count), lo + kChunkCells) - lo;
            std::vector<Cell, NoInitAllocator<Cell>> records(n);
            reader.readAt(start + lo * sizeof(Cell), records.data(), n * sizeof(Cell));
            if (!cells.tryStore(lo, records)) allFit = false;
        });
        return allFit.load();
    };
    CellArray cells;
    if (!fill(cells)) {  // a cell that does not fit: all of them in 16 bytes, as the file has them
        cells = CellArray();
        cells.widen();
        fill(cells);
    }
    reader.seek(start + count * sizeof(Cell));
    out.swap(cells);
}

void writeCells(AtomicFileWriter& writer, const CellArray& cells) {
    std::vector<Cell> records(std::min(cells.size(), kChunkCells));
    for (size_t lo = 0; lo < cells.size(); lo += records.size()) {
        const size_t n = std::min(cells.size() - lo, records.size());
        cells.copyOut(lo, std::span<Cell>(records.data(), n));
        writer.write(records.data(), n * sizeof(Cell));
    }
}

}  // namespace amrvk::amr
