#include "amr/space_partition.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace amrvk::amr {

namespace {

// Pass 1 over one chunk: bounds, levels, count, field range.
void addExtent(CellCensus& c, const Model& chunk) {
    const std::vector<float>& values = chunk.fields.at(0).values;
    for (size_t i = 0; i < chunk.cells.size(); ++i) {
        const Cell& cell = chunk.cells[i];
        const glm::i64vec3 lo(cell.lower), hi = lo + glm::i64vec3(cellWidth(cell.level));
        if (c.cells == 0) {
            c.bounds = {lo, hi};
            c.valueLo = c.valueHi = values[i];
        } else {
            c.bounds.lower = glm::min(c.bounds.lower, lo);
            c.bounds.upper = glm::max(c.bounds.upper, hi);
            c.valueLo = std::min(c.valueLo, values[i]);
            c.valueHi = std::max(c.valueHi, values[i]);
        }
        c.minLevel = std::min(c.minLevel, cell.level);
        c.maxLevel = std::max(c.maxLevel, cell.level);
        ++c.cells;
    }
}

// Bins once the extent is known.
void placeBins(CellCensus& c) {
    AMRVK_CHECK(c.cells > 0, c.head.source, ": no cells");
    const glm::i64vec3 size = c.bounds.size();
    const int64_t extent = std::max({size.x, size.y, size.z});
    c.binWidth = 1;
    while (c.binWidth * CellCensus::kMaxBins < extent + c.binWidth) c.binWidth *= 2;
    for (int a = 0; a < 3; ++a) {
        c.binOrigin[a] = floorDiv(c.bounds.lower[a], c.binWidth) * c.binWidth;
        c.bins[a] = int((c.bounds.upper[a] - c.binOrigin[a] + c.binWidth - 1) / c.binWidth);
    }
    c.counts.assign(size_t(c.bins.x) * size_t(c.bins.y) * size_t(c.bins.z), 0);
}

void addCounts(CellCensus& c, const CellArray& cells) {
    for (const Cell& cell : cells) {
        const glm::i64vec3 b = (glm::i64vec3(cell.lower) - c.binOrigin) / c.binWidth;
        ++c.counts[(size_t(b.z) * size_t(c.bins.y) + size_t(b.y)) * size_t(c.bins.x) + size_t(b.x)];
    }
}

struct BinBox {
    glm::ivec3 lo, hi;  // [lo, hi) in bins
};

// Cells per slab of `box` along `axis`.
std::vector<uint64_t> slabCounts(const CellCensus& c, const BinBox& box, int axis) {
    std::vector<uint64_t> slabs(size_t(box.hi[axis] - box.lo[axis]), 0);
    for (int z = box.lo.z; z < box.hi.z; ++z)
        for (int y = box.lo.y; y < box.hi.y; ++y)
            for (int x = box.lo.x; x < box.hi.x; ++x) {
                const glm::ivec3 b(x, y, z);
                slabs[size_t(b[axis] - box.lo[axis])] +=
                    c.counts[(size_t(z) * size_t(c.bins.y) + size_t(y)) * size_t(c.bins.x) + size_t(x)];
            }
    return slabs;
}

uint64_t occupiedBins(const CellCensus& c, const BinBox& box) {
    uint64_t n = 0;
    for (int z = box.lo.z; z < box.hi.z; ++z)
        for (int y = box.lo.y; y < box.hi.y; ++y)
            for (int x = box.lo.x; x < box.hi.x; ++x)
                n += c.counts[(size_t(z) * size_t(c.bins.y) + size_t(y)) * size_t(c.bins.x) + size_t(x)] > 0;
    return n;
}

void bisect(const CellCensus& c, const BinBox& box, int parts, std::vector<BinBox>& out) {
    if (parts == 1) {
        out.push_back(box);
        return;
    }
    const glm::ivec3 extent = box.hi - box.lo;
    int axes[3] = {0, 1, 2};
    std::stable_sort(axes, axes + 3, [&](int a, int b) { return extent[a] > extent[b]; });
    const int left = parts / 2;
    for (int axis : axes) {
        if (extent[axis] < 2) continue;
        const std::vector<uint64_t> slabs = slabCounts(c, box, axis);
        uint64_t total = 0;
        for (uint64_t s : slabs) total += s;
        const double target = double(total) * double(left) / double(parts);
        // The plane k (cells of slabs [0, k) go left) closest to the target, each side non-empty.
        int best = -1;
        double bestError = 0;
        uint64_t before = 0;
        for (size_t k = 1; k < slabs.size(); ++k) {
            before += slabs[k - 1];
            if (before == 0 || before == total) continue;
            const double error = std::abs(double(before) - target);
            if (best < 0 || error < bestError) {
                best = int(k);
                bestError = error;
            }
        }
        if (best < 0) continue;  // all cells in one slab along this axis
        BinBox lo = box, hi = box;
        lo.hi[axis] = box.lo[axis] + best;
        hi.lo[axis] = box.lo[axis] + best;
        if (occupiedBins(c, lo) < uint64_t(left) || occupiedBins(c, hi) < uint64_t(parts - left)) continue;
        bisect(c, lo, left, out);
        bisect(c, hi, parts - left, out);
        return;
    }
    AMRVK_CHECK(false, c.head.source, ": cannot split ", c.cells, " cells into ", parts, " parts of cells (bins of ",
                c.binWidth, " voxels; use fewer ranks)");
}

}  // namespace

CellCensus censusOf(const std::filesystem::path& path, const ReadOptions& options) {
    CellCensus c;
    // The scale and log floor once, for both passes here and every rank's readPart (a given
    // --log-floor kept).
    ReadOptions o = options;
    o.scale = c.scale = resolvedScale(path, options);
    o.logFloor = c.logFloor = logFloorOf(path, o);
    visitCells(
        path, o, [&](const Model& chunk) { addExtent(c, chunk); }, &c.head);
    placeBins(c);
    visitCells(path, o, [&](const Model& chunk) { addCounts(c, chunk.cells); });
    return c;
}

CellCensus censusOf(const Model& model) {
    CellCensus c;
    c.head = model;
    c.head.cells.clear();
    for (Field& f : c.head.fields) f.values.clear();
    c.scale = scaleOf(model);
    addExtent(c, model);
    placeBins(c);
    addCounts(c, model.cells);
    return c;
}

std::vector<Box3l> partitionByCells(const CellCensus& c, int parts) {
    AMRVK_CHECK(parts >= 1, "internal: ", parts, " parts");
    AMRVK_CHECK(occupiedBins(c, {glm::ivec3(0), c.bins}) >= uint64_t(parts), c.head.source, ": cannot split ", c.cells,
                " cells into ", parts, " parts (", occupiedBins(c, {glm::ivec3(0), c.bins}), " occupied bins of ",
                c.binWidth, " voxels; use fewer ranks)");
    std::vector<BinBox> boxes;
    bisect(c, {glm::ivec3(0), c.bins}, parts, boxes);
    std::vector<Box3l> out;
    for (const BinBox& b : boxes) {
        Box3l v{c.binOrigin + glm::i64vec3(b.lo) * c.binWidth, c.binOrigin + glm::i64vec3(b.hi) * c.binWidth};
        v.lower = glm::max(v.lower, c.bounds.lower);  // the outer faces on the data's bounds
        v.upper = glm::min(v.upper, c.bounds.upper);
        out.push_back(v);
    }
    return out;
}

Model readPart(const std::filesystem::path& path, const ReadOptions& options, const Box3l& box) {
    Model out;
    visitCells(
        path, options,
        [&](const Model& chunk) {
            if (out.fields.empty()) {
                out.fields = {Field{chunk.fields.at(0).name, {}}};
            }
            for (size_t i = 0; i < chunk.cells.size(); ++i)
                if (supportMeets(chunk.cells[i], box)) {
                    out.cells.push_back(chunk.cells[i]);
                    out.fields[0].values.push_back(chunk.fields[0].values[i]);
                }
        },
        &out);
    if (options.scale == FieldScale::Log && scaleOf(out) != FieldScale::Log)  // as readModel records it
        out.attributes.emplace_back("scale", "log10");
    return out;
}

}  // namespace amrvk::amr
