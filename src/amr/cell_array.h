#pragma once
// The model's leaf cells, 8 bytes each wherever they fit (the 16-byte Cell otherwise).
//  - Compact: one uint64 per cell, bits 0-4 the level, then lower >> level per axis: x in bits
//    5-24, y in 25-44, z in 45-63 (20, 20 and 19 bits). A cell fits when its level is 0..30, its
//    corner is non-negative and a multiple of its width, and lower >> level is below 2^20 (x, y)
//    and 2^19 (z): a finest grid up to 524,288 cells deep on z at every level, which every data
//    set we read has.
//  - Wide: the 16-byte Cell, for everything else (negative or misaligned corners: the validator
//    names them from the same values the file held).
// The array starts compact and turns wide, once and for good, when a cell that does not fit is
// stored; so at 10^9 cells the cells and one field take 12 bytes per cell, not 20.
// Cells are values: operator[] returns a Cell, set() stores one. set() on a compact array from
// several threads at once is safe only for cells that fit (cells taken from the array itself).
#include "core/file_io.h"

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <iterator>
#include <span>
#include <utility>
#include <vector>

namespace amrvk::amr {

// One leaf cell in the ExaBrick convention (amr/model.h), as a .cells record holds it.
struct Cell {
    glm::ivec3 lower;  // lower corner, finest-level integer units
    int32_t level;     // width = 1 << level units; 0 = finest
    friend bool operator==(const Cell&, const Cell&) = default;
};
static_assert(sizeof(Cell) == 16, "Cell must match the 16-byte .cells record");

class CellArray {
public:
    static constexpr int kLevelBits = 5, kXBits = 20, kYBits = 20, kZBits = 19;

    // The 8-byte form of c, with every condition of fits() ORed into `bad` (no branches: the
    // reader packs each chunk in one pass with it); the result means nothing where bad != 0.
    static uint64_t packChecked(const Cell& c, uint32_t& bad) {
        const uint32_t level = uint32_t(c.level), l = level & 31u;
        const uint32_t x = uint32_t(c.lower.x), y = uint32_t(c.lower.y), z = uint32_t(c.lower.z);
        bad |= uint32_t(level > 30u) | ((x | y | z) >> 31) | ((x | y | z) & ((1u << l) - 1u)) |
               ((x >> l) >> kXBits) | ((y >> l) >> kYBits) | ((z >> l) >> kZBits);
        return uint64_t(l) | uint64_t(x >> l) << kLevelBits | uint64_t(y >> l) << (kLevelBits + kXBits) |
               uint64_t(z >> l) << (kLevelBits + kXBits + kYBits);
    }
    // True when `c` is stored in 8 bytes: level 0..30, corner non-negative and aligned, and
    // lower >> level within the bits of its axis.
    static bool fits(const Cell& c) {
        uint32_t bad = 0;
        packChecked(c, bad);
        return bad == 0;
    }
    static uint64_t pack(const Cell& c) {  // fits(c)
        uint32_t bad = 0;
        return packChecked(c, bad);
    }
    // A cell from either storage (visitStorage's elements).
    static Cell decode(uint64_t v) {
        const int level = int(v & 31u);
        const auto axis = [&](int shift, int bits) {
            return int32_t(uint32_t((v >> shift) & ((uint64_t{1} << bits) - 1)) << level);
        };
        return Cell{{axis(kLevelBits, kXBits), axis(kLevelBits + kXBits, kYBits),
                     axis(kLevelBits + kXBits + kYBits, kZBits)},
                    level};
    }
    static const Cell& decode(const Cell& c) { return c; }

    CellArray() = default;
    CellArray(std::initializer_list<Cell> cells);

    size_t size() const { return mWide ? mWideCells.size() : mCompact.size(); }
    bool empty() const { return size() == 0; }
    bool compact() const { return !mWide; }
    size_t bytesPerCell() const { return mWide ? sizeof(Cell) : sizeof(uint64_t); }
    // Bytes allocated (the capacity).
    uint64_t bytes() const {
        return mWide ? mWideCells.capacity() * sizeof(Cell) : mCompact.capacity() * sizeof(uint64_t);
    }

    // const: `cells[i].lower = p` must not compile (it would change a copy); use set().
    const Cell operator[](size_t i) const { return mWide ? mWideCells[i] : decode(mCompact[i]); }
    const Cell front() const { return (*this)[0]; }
    const Cell back() const { return (*this)[size() - 1]; }
    void set(size_t i, const Cell& c) {
        uint32_t bad = 0;
        const uint64_t v = mWide ? 0 : packChecked(c, bad);
        if (bad) widen();
        if (mWide) mWideCells[i] = c;
        else mCompact[i] = v;
    }
    // Exchanges cells i and j (the brick build's partitions): no repacking.
    void swapCells(size_t i, size_t j) {
        if (mWide) std::swap(mWideCells[i], mWideCells[j]);
        else std::swap(mCompact[i], mCompact[j]);
    }
    // Calls fn with the storage as it is, std::span<uint64_t> (compact) or std::span<Cell> (wide),
    // for loops that move many cells without repacking them; decode() reads an element of either.
    // Whatever fn stores must come from the same span.
    template <class Fn>
    decltype(auto) visitStorage(Fn&& fn) {
        return mWide ? fn(std::span<Cell>(mWideCells)) : fn(std::span<uint64_t>(mCompact));
    }
    void push_back(const Cell& c) {
        uint32_t bad = 0;
        const uint64_t v = mWide ? 0 : packChecked(c, bad);
        if (bad) widen();
        if (mWide) mWideCells.push_back(c);
        else mCompact.push_back(v);
    }
    // New cells are uninitialised: set each before it is read.
    void resize(size_t n) { mWide ? mWideCells.resize(n) : mCompact.resize(n); }
    // New cells are `c`.
    void resize(size_t n, const Cell& c) {
        const size_t first = size();
        resize(n);
        for (size_t i = first; i < n; ++i) set(i, c);
    }
    void reserve(size_t n) { mWide ? mWideCells.reserve(n) : mCompact.reserve(n); }
    void clear() { mWide ? mWideCells.clear() : mCompact.clear(); }
    void swap(CellArray& other) noexcept {
        std::swap(mWide, other.mWide);
        mCompact.swap(other.mCompact);
        mWideCells.swap(other.mWideCells);
    }
    // Stores every cell in 16 bytes from now on (also when all fit: tests, and readers whose cells
    // come in parallel and may not fit).
    void widen();

    // Cells [first, first + out.size()) as 16-byte records (writers, a chunk at a time).
    void copyOut(size_t first, std::span<Cell> out) const;
    // Stores records as cells [first, first + in.size()), which must exist; returns false when
    // the array is compact and a record does not fit, and those cells are then unspecified (widen
    // and store them again). Safe from several threads at once for disjoint ranges (it never widens).
    bool tryStore(size_t first, std::span<const Cell> in);
    // Appends records (widening if one does not fit).
    void append(std::span<const Cell> in);

    class const_iterator {
    public:
        using iterator_category = std::random_access_iterator_tag;
        using value_type = Cell;
        using difference_type = std::ptrdiff_t;
        using pointer = void;
        using reference = Cell;
        const_iterator() = default;
        const_iterator(const CellArray* a, size_t i) : mArray(a), mIndex(i) {}
        const Cell operator*() const { return (*mArray)[mIndex]; }
        const Cell operator[](difference_type d) const { return (*mArray)[size_t(difference_type(mIndex) + d)]; }
        const_iterator& operator++() { return ++mIndex, *this; }
        const_iterator operator++(int) { const_iterator t = *this; ++mIndex; return t; }
        const_iterator& operator--() { return --mIndex, *this; }
        const_iterator operator--(int) { const_iterator t = *this; --mIndex; return t; }
        const_iterator& operator+=(difference_type d) { return mIndex = size_t(difference_type(mIndex) + d), *this; }
        const_iterator& operator-=(difference_type d) { return *this += -d; }
        friend const_iterator operator+(const_iterator a, difference_type d) { return a += d; }
        friend const_iterator operator+(difference_type d, const_iterator a) { return a += d; }
        friend const_iterator operator-(const_iterator a, difference_type d) { return a -= d; }
        friend difference_type operator-(const const_iterator& a, const const_iterator& b) {
            return difference_type(a.mIndex) - difference_type(b.mIndex);
        }
        friend bool operator==(const const_iterator& a, const const_iterator& b) { return a.mIndex == b.mIndex; }
        friend auto operator<=>(const const_iterator& a, const const_iterator& b) { return a.mIndex <=> b.mIndex; }

    private:
        const CellArray* mArray = nullptr;
        size_t mIndex = 0;
    };
    const_iterator begin() const { return {this, 0}; }
    const_iterator end() const { return {this, size()}; }

    friend bool operator==(const CellArray& a, const CellArray& b);

private:
    bool mWide = false;
    std::vector<uint64_t, NoInitAllocator<uint64_t>> mCompact;
    std::vector<Cell, NoInitAllocator<Cell>> mWideCells;
};

// Reads `count` 16-byte .cells records at the reader's offset into `out`, compact where they fit:
// 8 MiB chunks on every core, each packed as it arrives, so the 16-byte records are never all held
// at once. Where one does not fit, the records are read again into a wide array.
void readCells(BinaryReader& reader, uint64_t count, CellArray& out);
// Writes the cells as 16-byte records, a chunk at a time.
void writeCells(AtomicFileWriter& writer, const CellArray& cells);

}  // namespace amrvk::amr
