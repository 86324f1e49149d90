// The brick build's split choice on statistics alone (accel/brick_split.h): the plane where the
// level set changes, the brick test, and slabs read from a cube grid equal to those of the cells,
// which is what lets a plan on the grid choose what a split over the cells chooses.
#include <gtest/gtest.h>

#include <functional>
#include <random>
#include <vector>

#include "accel/brick_split.h"

using namespace amrvk;
using namespace amrvk::accel;

namespace {

CellStats statsOf(const std::vector<amr::Cell>& cells) {
    CellStats s;
    for (const amr::Cell& c : cells) s.add(c);
    return s;
}

// Slab statistics straight from the cells, as the build gathers them where it has no cube grid.
Slabs slabsOfCells(const std::vector<amr::Cell>& cells, const SplitFrame& f) {
    Slabs s;
    for (int a = 0; a < 3; ++a) s[size_t(a)].assign(size_t(f.used[a]), CellStats{});
    for (const amr::Cell& c : cells)
        for (int a = 0; a < 3; ++a)
            if (f.used[a] > 0) s[size_t(a)][size_t((int64_t(c.lower[a]) - f.lo[a]) / f.cw)].add(c);
    return s;
}

// Every cell of `level` in the box [lo, lo + size) (voxel space, aligned to the level's width).
void fill(std::vector<amr::Cell>& cells, glm::ivec3 lo, glm::ivec3 size, int32_t level) {
    const int32_t w = int32_t{1} << level;
    for (int32_t z = lo.z; z < lo.z + size.z; z += w)
        for (int32_t y = lo.y; y < lo.y + size.y; y += w)
            for (int32_t x = lo.x; x < lo.x + size.x; x += w) cells.push_back({{x, y, z}, level});
}

void expectSameStats(const CellStats& a, const CellStats& b, const char* what) {
    EXPECT_EQ(a.levelMask, b.levelMask) << what;
    EXPECT_EQ(a.count, b.count) << what;
    EXPECT_EQ(a.volume, b.volume) << what;  // sums of powers of 8: exact in any order
    if (a.count > 0) {
        EXPECT_EQ(a.lo, b.lo) << what;
        EXPECT_EQ(a.hi, b.hi) << what;
    }
}

}  // namespace

TEST(BrickSplit, CutsWhereTheLevelSetChangesAndItsSidesAreBricks) {
    // x in [0, 4): 8 cells of level 1; x in [4, 8): 64 of level 0; each slab along y or z holds both.
    std::vector<amr::Cell> cells;
    fill(cells, {0, 0, 0}, {4, 4, 4}, 1);
    fill(cells, {4, 0, 0}, {4, 4, 4}, 0);
    const CellStats in = statsOf(cells);
    glm::i64vec3 dims;
    EXPECT_FALSE(brickShaped(in, dims));  // two levels
    const SplitFrame f = frameOf(in);
    EXPECT_EQ(f.cw, 2);
    EXPECT_EQ(f.slabs, glm::i64vec3(4, 2, 2));
    const SplitChoice c = chooseSplit(f, slabsOfCells(cells, f));
    ASSERT_EQ(c.axis, 0);
    EXPECT_EQ(c.plane, 4);
    ASSERT_TRUE(c.sidesFromSlabs);
    EXPECT_EQ(c.left.count, 8u);
    EXPECT_EQ(c.right.count, 64u);
    ASSERT_TRUE(brickShaped(c.left, dims));
    EXPECT_EQ(dims, glm::i64vec3(2, 2, 2));
    ASSERT_TRUE(brickShaped(c.right, dims));
    EXPECT_EQ(dims, glm::i64vec3(4, 4, 4));
    // A hole is not a brick: the node is then not completely filled.
    cells.pop_back();
    EXPECT_FALSE(brickShaped(statsOf(std::vector<amr::Cell>(cells.begin() + 8, cells.end())), dims));
}

TEST(BrickSplit, SlabsFromACubeGridAreTheSlabsOfItsCells) {
    // A random refinement of a 4^3 block of level-3 cells down to level 0, away from the grid's origin.
    std::mt19937 rng(54);
    std::vector<amr::Cell> cells;
    const std::function<void(glm::ivec3, int32_t)> refine = [&](glm::ivec3 lo, int32_t level) {
        if (level == 0 || rng() % 2 == 0) {
            cells.push_back({lo, level});
            return;
        }
        const int32_t h = int32_t{1} << (level - 1);
        for (int k = 0; k < 8; ++k) refine(lo + h * glm::ivec3(k & 1, (k >> 1) & 1, k >> 2), level - 1);
    };
    const glm::ivec3 offset(8, 16, 24);
    for (int k = 0; k < 64; ++k) refine(offset + 8 * glm::ivec3(k % 4, k / 4 % 4, k / 16), 3);
    const CellStats in = statsOf(cells);
    const SplitFrame f = frameOf(in);
    ASSERT_EQ(f.cw, 8);
    for (int64_t cw : {8, 2, 1}) {  // cubes of the frame's width and finer
        CubeGrid g{glm::i64vec3(0), glm::i64vec3(64 / cw), cw, {}};
        g.cubes.assign(size_t(g.dims.x * g.dims.y * g.dims.z), CellStats{});
        for (const amr::Cell& c : cells) {
            const glm::i64vec3 q = (glm::i64vec3(c.lower) - g.lo) / cw;
            g.cubes[size_t((q.z * g.dims.y + q.y) * g.dims.x + q.x)].add(c);
        }
        const Slabs fromCubes = slabsFromCubes(g, f), fromCells = slabsOfCells(cells, f);
        for (size_t a = 0; a < 3; ++a) {
            ASSERT_EQ(fromCubes[a].size(), fromCells[a].size());
            for (size_t k = 0; k < fromCells[a].size(); ++k) expectSameStats(fromCubes[a][k], fromCells[a][k], "slab");
        }
        const SplitChoice a = chooseSplit(f, fromCubes), b = chooseSplit(f, fromCells);
        EXPECT_EQ(a.axis, b.axis);
        EXPECT_EQ(a.plane, b.plane);
        expectSameStats(a.left, b.left, "left side");
        expectSameStats(a.right, b.right, "right side");
    }
}
