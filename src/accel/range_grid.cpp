#include "accel/range_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/checked_size.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/stats.h"

namespace amrvk::accel {

namespace {

// Cells per splat chunk and the most chunks: every chunk splats into its own full grid, so the
// count also bounds the extra memory (at most kMaxSplatChunks - 1 grids besides the result).
constexpr size_t kSplatChunkCells = 250000;
constexpr size_t kMaxSplatChunks = 4;

}  // namespace

glm::ivec3 RangeGrid::cellOf(glm::dvec3 p) const {
    glm::dvec3 c = glm::floor((p - origin) / cellSize);
    return glm::clamp(glm::ivec3(glm::clamp(c, glm::dvec3(-1.0), glm::dvec3(dims))), glm::ivec3(0),
                      dims - 1);
}

glm::ivec3 autoGridDims(const amr::Box3l& bounds, int longest) {
    glm::dvec3 size(bounds.size());
    double maxSize = std::max({size.x, size.y, size.z});
    // Never more macrocells than voxel units along the longest axis.
    longest = int(std::min<double>(longest, std::max(1.0, maxSize)));
    glm::ivec3 dims;
    for (int a = 0; a < 3; ++a)
        dims[a] = std::clamp(int(std::ceil(size[a] * longest / maxSize - 1e-9)), 1, longest);
    return dims;
}

glm::ivec3 parseGridDims(const std::string& text, const amr::Box3l& bounds) {
    if (text == "auto") return autoGridDims(bounds);
    int x = 0, y = 0, z = 0;
    char c1 = 0, c2 = 0, tail = 0;
    glm::ivec3 dims;
    if (std::sscanf(text.c_str(), "%d%c%d%c%d%c", &x, &c1, &y, &c2, &z, &tail) == 5 && c1 == 'x' &&
        c2 == 'x') {
        dims = {x, y, z};
    } else if (std::sscanf(text.c_str(), "%d%c", &x, &tail) == 1) {
        AMRVK_CHECK(x >= 1 && x <= 4096, "--grid ", text, ": macrocells must be in [1, 4096]");
        return autoGridDims(bounds, x);
    } else {
        AMRVK_CHECK(false, "--grid '", text, "': expected auto, N or NxMxK");
    }
    for (int a = 0; a < 3; ++a)
        AMRVK_CHECK(dims[a] >= 1 && dims[a] <= 4096, "--grid ", text,
                    ": macrocells per axis must be in [1, 4096]");
    return dims;
}

RangeGrid rangeGridLayout(const amr::Box3l& bounds, glm::ivec3 dims) {
    AMRVK_CHECK(dims.x >= 1 && dims.y >= 1 && dims.z >= 1, "range grid needs at least one macrocell");
    RangeGrid g;
    g.dims = dims;
    g.origin = glm::dvec3(bounds.lower);
    g.cellSize = glm::dvec3(bounds.size()) / glm::dvec3(dims);
    return g;
}

RangeGrid buildRangeGrid(const amr::Model& model, const amr::Field& field, glm::ivec3 dims) {
    Timer timer;
    RangeGrid g = rangeGridLayout(amr::summarize(model).bounds, dims);
    const size_t total = size_t(dims.x) * size_t(dims.y) * size_t(dims.z);
    const glm::dvec3 eps = 1e-5 * g.cellSize;
    const size_t n = model.cells.size();
    const size_t chunks = std::clamp<size_t>(n / kSplatChunkCells, 1, kMaxSplatChunks);
    // parallelReduce holds one private grid per chunk at once.
    checkAllocation(checkedProduct({total, sizeof(ValueRange), chunks}, "--grid"),
                    strCat("--grid ", dims.x, "x", dims.y, "x", dims.z, ": macrocell value ranges"));

    // Consecutive chunks of cells splat into private grids (in parallel), merged in chunk order.
    auto splat = [&](size_t begin, size_t end) {
        std::vector<ValueRange> ranges(total);
        for (size_t i = begin; i < end; ++i) {
            const amr::Cell& c = model.cells[i];
            const float v = field.values[i];
            if (std::isnan(v)) continue;
            const double w = double(amr::cellWidth(c.level));
            // Support box, grown by 1e-5 macrocell so that float rounding of sample positions on
            // the GPU near a macrocell face cannot step outside the conservative range.
            glm::dvec3 lo = glm::dvec3(c.lower) - 0.5 * w - eps, hi = glm::dvec3(c.lower) + 1.5 * w + eps;
            glm::ivec3 a = g.cellOf(lo), b = g.cellOf(hi);
            for (int z = a.z; z <= b.z; ++z)
                for (int y = a.y; y <= b.y; ++y)
                    for (int x = a.x; x <= b.x; ++x) ranges[g.index({x, y, z})].extend(v);
        }
        return ranges;
    };
    auto merge = [&](std::vector<ValueRange>& acc, std::vector<ValueRange>&& part) {
        parallelFor(0, total, [&](size_t i) { acc[i].extend(part[i]); }, 4096);
    };
    g.ranges = parallelReduce<std::vector<ValueRange>>(0, n, chunks, splat, merge);
    g.buildSeconds = timer.seconds();
    return g;
}

}  // namespace amrvk::accel
