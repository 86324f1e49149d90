#pragma once
// The split choice of the brick build (accel/brick_build.h): statistics of a set of cells, a node's
// candidate planes, exaBuilder's SAH-alike choice among them, and the test for a node that becomes
// a brick. Everything here is a function of cell statistics alone, gathered from the cells or from
// a cube grid, so a plan on the grid (accel/brick_plan.h) chooses what a split over the cells
// chooses. All coordinates are voxel space (finest-level units).
#include <glm/glm.hpp>

#include <array>
#include <bit>
#include <cstdint>
#include <limits>
#include <vector>

#include "amr/model.h"

namespace amrvk::accel {

// Level set, used volume and bounds of a set of cells (voxel space): a node of the kd build, or one
// slab or coarse cube of it. Bounds are int32: validated cells end at or below 2^31-1.
struct CellStats {
    uint32_t levelMask = 0;
    uint32_t count = 0;  // cells (a model has fewer than 2^32)
    double volume = 0;
    glm::ivec3 lo{std::numeric_limits<int32_t>::max()}, hi{std::numeric_limits<int32_t>::min()};
    void add(const amr::Cell& c) {
        levelMask |= 1u << c.level;
        ++count;
        volume += amr::cellVolume(c.level);
        lo = glm::min(lo, c.lower);
        hi = glm::max(hi, c.lower + (int32_t{1} << c.level));
    }
    void merge(const CellStats& o) {
        levelMask |= o.levelMask;
        count += o.count;
        volume += o.volume;
        lo = glm::min(lo, o.lo);
        hi = glm::max(hi, o.hi);
    }
    int32_t minLevel() const { return std::countr_zero(levelMask); }
    int32_t maxLevel() const { return 31 - std::countl_zero(levelMask); }
};

// Cell statistics per cube (cw^3) of a box [lo, lo + dims cw), x fastest; a cell counts in the
// cube of its lower corner. It serves every node inside the box whose coarsest cell width is a
// multiple of cw (a power of two at least cw): such a node's slabs and planes are unions of cubes.
struct CubeGrid {
    glm::i64vec3 lo{0}, dims{0};
    int64_t cw = 1;  // cube width, voxel space
    std::vector<CellStats> cubes;
};

// Per axis, the statistics of a node's coarse slabs (SplitFrame), slab k at index k; an axis
// without slab statistics (SplitFrame::used 0) is empty.
using Slabs = std::array<std::vector<CellStats>, 3>;

// A node's candidate planes: multiples of its coarsest cell width cw inside its bounds rounded out
// to cw (voxel space); `slabs` coarse slabs per axis, `used[a]` = slabs[a] where axis a gets slab
// statistics, else 0 (fewer than 2 slabs, or more than 4 per cell).
struct SplitFrame {
    int64_t cw = 1;
    glm::i64vec3 lo{0}, hi{0}, slabs{0}, used{0};
};
// The frame of a node of statistics `in` (at least one cell).
SplitFrame frameOf(const CellStats& in);

// A node's split plane; axis -1 when no plane exists (the node lies in one coarse cell).
struct SplitChoice {
    int axis = -1;
    int64_t plane = 0;            // voxel space, a multiple of the frame's cw
    bool sidesFromSlabs = false;  // then left and right hold the two sides' statistics
    CellStats left, right;
};

// exaBuilder's SAH-alike cost over the boundary planes between coarse slabs (where the level set or
// fullness changes), else the spatial median of the longest axis. A function of the statistics
// alone, so a plan on a cube grid chooses what a split over the cells chooses.
SplitChoice chooseSplit(const SplitFrame& f, const Slabs& stats);

// A frame's slabs from the cubes of a grid that serves it (g.cw divides f.cw): slab k of axis a
// merges the cubes whose coordinate along a, counted from the frame's lower corner, is k f.cw/g.cw
// up to (k + 1) f.cw/g.cw.
Slabs slabsFromCubes(const CubeGrid& g, const SplitFrame& f);

// A node that becomes a brick: one level, completely filled, at most kMaxBrickCells per axis;
// `dims` its cells per axis (meaningful only where it returns true).
bool brickShaped(const CellStats& in, glm::i64vec3& dims);

}  // namespace amrvk::accel
