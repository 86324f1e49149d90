// Brick grid (accel/brick_grid.*): its lists against a brute-force overlap test of every brick
// with every macrocell, and its sampler against the brute-force tent sum (amr::ReferenceSampler)
// and the ext-brick BVH sampler, for grids coarser and finer than the cells, at points inside
// cells, on brick domain faces and on macrocell faces.
#include <gtest/gtest.h>

#include <random>

#include "accel/abrs.h"
#include "accel/brick_build.h"
#include "accel/brick_grid.h"
#include "accel/brick_sampler.h"
#include "accel/range_grid.h"
#include "amr/sampler.h"
#include "model_fixtures.h"

using namespace amrvk;
using namespace amrvk::accel;

namespace {

std::vector<glm::dvec3> testPoints(const test::Built& b, const BrickGrid& g, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<size_t> pick(0, b.model.cells.size() - 1);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<glm::dvec3> pts;
    for (int i = 0; i < 20000; ++i) {  // inside cells
        const amr::Cell& c = b.model.cells[pick(rng)];
        pts.push_back(glm::dvec3(c.lower) + double(amr::cellWidth(c.level)) * glm::dvec3(u(rng), u(rng), u(rng)));
    }
    for (const BoxD& d : brickDomainBoxes(b.bricks))  // domain corners, edges and faces
        for (int k = 0; k < 27; ++k) pts.push_back(d.lo + (d.hi - d.lo) * (0.5 * glm::dvec3(k % 3, k / 3 % 3, k / 9)));
    for (int z = 0; z <= g.dims.z; ++z)  // macrocell corners, and points on their faces
        for (int y = 0; y <= g.dims.y; ++y)
            for (int x = 0; x <= g.dims.x; ++x) {
                const glm::dvec3 corner = g.origin + g.cellSize * glm::dvec3(x, y, z);
                pts.push_back(corner);
                pts.push_back(corner + g.cellSize * glm::dvec3(u(rng), u(rng), 0.0));
            }
    return pts;
}

test::Built model(uint32_t seed) {
    amr::Model m = test::makeRefinedModel(seed, {5, 4, 3}, 4, 0.35, seed % 2 ? glm::ivec3(-3, -1, 2) : glm::ivec3(0));
    test::addRandomField(m, "r", seed);
    return test::buildBricks(std::move(m));
}

}  // namespace

TEST(BrickGrid, ListsHoldExactlyTheBricksWhoseDomainMeetsTheMacrocell) {
    test::Built b = model(41);
    const amr::Box3l bounds = amr::summarize(b.model).bounds;
    for (glm::ivec3 dims : {glm::ivec3(1), glm::ivec3(3, 5, 2), glm::ivec3(16), glm::ivec3(bounds.size())}) {
        SCOPED_TRACE(testing::Message() << dims.x << "x" << dims.y << "x" << dims.z);
        const BrickGrid g = buildBrickGrid(b.bricks, bounds, dims);
        ASSERT_EQ(g.lists.size(), g.lists[g.cellCount()]);
        const glm::dvec3 margin = brickGridMargin(g.cellSize, g.dims);
        size_t entries = 0;
        for (int z = 0; z < dims.z; ++z)
            for (int y = 0; y < dims.y; ++y)
                for (int x = 0; x < dims.x; ++x) {
                    const glm::ivec3 c(x, y, z);
                    const size_t cell = g.index(c);
                    // The macrocell grown by the margin; an edge macrocell reaches out to infinity.
                    glm::dvec3 lo = g.origin + g.cellSize * glm::dvec3(c) - margin;
                    glm::dvec3 hi = g.origin + g.cellSize * glm::dvec3(c + 1) + margin;
                    for (int a = 0; a < 3; ++a) {
                        if (c[a] == 0) lo[a] = -1e300;
                        if (c[a] == dims[a] - 1) hi[a] = 1e300;
                    }
                    std::vector<uint32_t> expected;
                    for (uint32_t id = 0; id < b.bricks.bricks.size(); ++id) {
                        const HalfBox d = brickDomain(b.bricks.bricks[id]);
                        const glm::dvec3 dl = d.lower(), dh = d.upper();
                        if (dl.x <= hi.x && dl.y <= hi.y && dl.z <= hi.z && dh.x >= lo.x && dh.y >= lo.y && dh.z >= lo.z)
                            expected.push_back(id);
                    }
                    const auto got = g.bricksOf(cell);
                    ASSERT_EQ(std::vector<uint32_t>(got.begin(), got.end()), expected) << "macrocell " << x << "," << y
                                                                                        << "," << z;
                    entries += expected.size();
                }
        EXPECT_EQ(g.lists.size(), g.cellCount() + 1 + entries);
        EXPECT_GE(entries, b.bricks.bricks.size());
    }
}

TEST(BrickGrid, SamplerEqualsBruteForceAndExtBrickOnEveryGrid) {
    for (uint32_t seed : {31u, 32u}) {
        test::Built b = model(seed);
        const amr::Box3l bounds = amr::summarize(b.model).bounds;
        amr::ReferenceSampler ref(b.model, b.model.fields[0]);
        ExtBrickSampler ext(b.bricks, b.values);
        for (glm::ivec3 dims : {glm::ivec3(1), glm::ivec3(7, 5, 3), glm::ivec3(bounds.size())}) {
            SCOPED_TRACE(testing::Message() << "seed " << seed << " grid " << dims.x << "x" << dims.y << "x" << dims.z);
            const BrickGrid g = buildBrickGrid(b.bricks, bounds, dims);
            GridSampler grid(g, b.bricks, b.values);
            size_t valid = 0, bad = 0;
            for (const glm::dvec3& p : testPoints(b, g, seed)) {
                const amr::Sample r = ref.sample(p), e = ext.sample(p), s = grid.sample(p);
                // Same bricks as ext-brick (only the summation order may differ on the CPU).
                const bool same = std::abs(s.weightSum - e.weightSum) <= 1e-12 && std::abs(s.value - e.value) <= 1e-12 *
                                  std::max(1.0, std::abs(e.value));
                const bool exact = std::abs(s.weightSum - r.weightSum) <= 1e-9 &&
                                   (!r.valid() || std::abs(s.value - r.value) <= 1e-6 * std::max(1.0, std::abs(r.value)));
                valid += r.valid();
                if ((!same || !exact) && ++bad <= 5)
                    ADD_FAILURE() << "at (" << p.x << ", " << p.y << ", " << p.z << "): grid " << s.value << " / "
                                  << s.weightSum << ", ext-brick " << e.value << " / " << e.weightSum << ", brute force "
                                  << r.value << " / " << r.weightSum;
            }
            EXPECT_EQ(bad, 0u);
            EXPECT_GT(valid, 20000u);
        }
    }
}

// The comparison above has power: a grid that drops one brick from one list is caught.
TEST(BrickGrid, ADroppedListEntryIsCaughtByTheBruteForceComparison) {
    test::Built b = model(31);
    const amr::Box3l bounds = amr::summarize(b.model).bounds;
    BrickGrid g = buildBrickGrid(b.bricks, bounds, glm::ivec3(7, 5, 3));
    // A macrocell and a listed brick whose strict bounds overlap it with positive volume: inside
    // the overlap the brick's own cells give it weight at every point.
    size_t cell = 0, pos = 0;
    glm::dvec3 lo(0), hi(0);
    for (size_t c = 0; c < g.cellCount() && hi.x <= lo.x; ++c) {
        const glm::ivec3 ci = g.coordOf(c);
        for (size_t k = g.lists[c]; k < g.lists[c + 1]; ++k) {
            const amr::Box3l bb = b.bricks.bricks[g.lists[k]].bounds();
            lo = glm::max(glm::dvec3(bb.lower), g.origin + g.cellSize * glm::dvec3(ci));
            hi = glm::min(glm::dvec3(bb.upper), g.origin + g.cellSize * glm::dvec3(ci + 1));
            if (hi.x > lo.x && hi.y > lo.y && hi.z > lo.z) {
                cell = c;
                pos = k;
                break;
            }
        }
    }
    ASSERT_TRUE(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z);
    g.lists.erase(g.lists.begin() + ptrdiff_t(pos));  // the offsets after it move down by one
    for (size_t c = cell + 1; c <= g.cellCount(); ++c) --g.lists[c];
    GridSampler grid(g, b.bricks, b.values);
    amr::ReferenceSampler ref(b.model, b.model.fields[0]);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    size_t wrong = 0;
    for (int i = 0; i < 100; ++i) {
        const glm::dvec3 p = lo + (hi - lo) * glm::dvec3(u(rng), u(rng), u(rng));
        ASSERT_EQ(g.index(g.cellOf(p)), cell);
        wrong += std::abs(grid.sample(p).weightSum - ref.sample(p).weightSum) > 1e-9;
    }
    EXPECT_EQ(wrong, 100u);
}
