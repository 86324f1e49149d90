#include "accel/brick_grid.h"

#include <algorithm>
#include <cmath>

#include "accel/abrs.h"
#include "accel/brick_sampler.h"
#include "accel/majorant_bounds.h"
#include "core/checked_size.h"
#include "core/error.h"
#include "core/stats.h"

namespace amrvk::accel {

glm::dvec3 brickGridMargin(const glm::dvec3& cellSize, const glm::ivec3& dims) {
    const glm::dvec3 extent = cellSize * glm::dvec3(dims);
    const double position = positionMargin(std::max({extent.x, extent.y, extent.z}));
    glm::dvec3 m;
    for (int d = 0; d < 3; ++d) m[d] = std::max(1e-4 * cellSize[d], position);
    return m;
}

BrickGrid buildBrickGrid(const BrickSet& bricks, const amr::Box3l& bounds, glm::ivec3 dims) {
    Timer timer;
    BrickGrid g{macrocellLayout(bounds, dims)};
    const size_t cells = g.cellCount();
    const glm::dvec3 margin = brickGridMargin(g.cellSize, g.dims);
    const std::string what = strCat("--grid ", dims.x, "x", dims.y, "x", dims.z);

    // At least the counts and the offsets, before anything is allocated.
    checkAllocation(checkedProduct({uint64_t(cells) + 1, sizeof(uint64_t) + sizeof(uint32_t)}, what),
                    what + ": brick lists");
    // Pass 1: entries per macrocell (as offsets shifted by one).
    std::vector<uint64_t> counts(cells + 1, 0);
    auto forEachCell = [&](const Brick& b, auto&& visit) {
        // A domain beyond the grid maps to the edge macrocells, which so list what sticks out.
        const HalfBox d = brickDomain(b);
        const glm::ivec3 a = g.cellOf(d.lower() - margin), e = g.cellOf(d.upper() + margin);
        for (int z = a.z; z <= e.z; ++z)
            for (int y = a.y; y <= e.y; ++y)
                for (int x = a.x; x <= e.x; ++x)
                    visit(g.index({x, y, z}));
    };
    for (const Brick& b : bricks.bricks) forEachCell(b, [&](size_t c) { ++counts[c + 1]; });
    uint64_t total = cells + 1;
    for (size_t c = 1; c <= cells; ++c) total = checkedSum(total, counts[c], what);
    AMRVK_CHECK(total <= UINT32_MAX, what, ": ", total, " list entries exceed 2^32 (use a coarser --grid)");
    checkAllocation(checkedProduct({total, sizeof(uint32_t)}, what) + (cells + 1) * sizeof(uint64_t), what + ": brick lists");

    // Pass 2: offsets, then ids in ascending brick order (bricks are visited in id order).
    g.lists.resize(size_t(total));
    uint64_t offset = cells + 1;
    for (size_t c = 0; c < cells; ++c) {
        g.lists[c] = uint32_t(offset);
        offset += counts[c + 1];
    }
    g.lists[cells] = uint32_t(offset);
    std::vector<uint32_t> fill(g.lists.begin(), g.lists.begin() + ptrdiff_t(cells));
    for (uint32_t id = 0; id < bricks.bricks.size(); ++id)
        forEachCell(bricks.bricks[id], [&](size_t c) { g.lists[fill[c]++] = id; });
    g.buildSeconds = timer.seconds();
    return g;
}

amr::Sample GridSampler::sample(glm::dvec3 p) const {
    return sampleBricks(mGrid.bricksOf(mGrid.index(mGrid.cellOf(p))), mBricks, mValues, p);
}

}  // namespace amrvk::accel
