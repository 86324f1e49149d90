#pragma once
// Macrocell value ranges: a uniform grid over the union of leaf-cell bounds (voxel space); each
// macrocell holds a range that bounds the reconstructed value anywhere inside it (grown by the
// brick grid's margin). The reconstruction is the W_b-weighted mean of per-brick clamped-trilinear
// values t_b (W_b = the brick's tent-weight sum), so it lies in the union over bricks b meeting
// the macrocell of the range of t_b over (macrocell and b's domain); t_b is trilinear at the point
// clamped to the brick's cell centres, whose extremes over a box lie on the lattice of the box's
// faces and the centre planes inside it: that union is exact per brick, not the range of every
// cell whose support touches the macrocell (the paper's splat, up to 6x looser). Where a
// macrocell spans at most a few cells, its range is exact for the blend too: f's range over the
// lattice of every brick's breakpoints, shared by neighbouring macrocells (range_grid.cpp).
#include <glm/glm.hpp>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "accel/bricks.h"
#include "accel/value_range.h"
#include "amr/model.h"

namespace amrvk::accel {

// The uniform macrocell grid shared by the value ranges and the brick grid (and the GPU's
// gridDims/gridOrigin/gridCellSize); macrocells are numbered x fastest.
struct MacrocellLayout {
    glm::ivec3 dims{0};      // macrocells per axis
    glm::dvec3 origin{0};    // lower corner, voxel space
    glm::dvec3 cellSize{1};  // macrocell extent per axis, voxel units
    size_t cellCount() const { return size_t(dims.x) * size_t(dims.y) * size_t(dims.z); }
    size_t index(glm::ivec3 c) const { return size_t(c.x) + size_t(dims.x) * (size_t(c.y) + size_t(dims.y) * size_t(c.z)); }
    glm::ivec3 coordOf(size_t index) const {
        return {int(index % size_t(dims.x)), int(index / size_t(dims.x) % size_t(dims.y)),
                int(index / (size_t(dims.x) * size_t(dims.y)))};
    }
    // Macrocell containing voxel-space point p, clamped to the grid.
    glm::ivec3 cellOf(glm::dvec3 p) const;
};

struct RangeGrid : MacrocellLayout {
    std::vector<ValueRange> ranges;  // per macrocell (index())
    double buildSeconds = 0;
    uint64_t memoryBytes() const { return ranges.size() * sizeof(ValueRange); }
};

struct BrickGrid;

// Grid resolution with `longest` macrocells on the longest axis (at most one per voxel unit) and
// near-cubical macrocells elsewhere; with maxMacrocells > 0, `longest` shrinks until the grid has
// at most that many macrocells.
glm::ivec3 autoGridDims(const amr::Box3l& bounds, int longest = 128, uint64_t maxMacrocells = 0);

// What "auto" allows per leaf cell: a finer grid than about one macrocell per cell bounds the
// field no tighter than its cells do, and its ranges cost more to build than a small data set's
// whole picture (Enzo DD0018: 137,502 cells, 128^3 ranges in 1.4 s, 64^3 in 0.3 s, with no
// slower samples; docs/benchmarks.md "Macrocells for small data").
inline constexpr uint64_t kAutoMacrocellsPerCell = 2;

// Parses "auto", "N" (N on the longest axis) or "NxMxK". Throws on anything else or N outside [1, 4096].
// "auto" is autoGridDims(bounds) capped at kAutoMacrocellsPerCell x leafCells (no cap when 0).
glm::ivec3 parseGridDims(const std::string& text, const amr::Box3l& bounds, uint64_t leafCells = 0);
// "" when `text` is auto, N or NxMxK with every count in [1, 4096]; else why not ("expected auto, N or
// NxMxK (got 'x')"), the words --grid, the session's structure.grid and Python's grid= all use.
std::string gridTextError(const std::string& text);

// The grid's dims, origin and macrocell size over `bounds`, with no ranges yet.
MacrocellLayout macrocellLayout(const amr::Box3l& bounds, glm::ivec3 dims);
inline RangeGrid rangeGridLayout(const amr::Box3l& bounds, glm::ivec3 dims) { return {macrocellLayout(bounds, dims)}; }

// Ranges over the layout of `lists` (which it reads: every brick meeting each grown macrocell).
// Empty slots (NaN) make a brick's bound the range of its non-empty cells near the macrocell.
// Bounds are padded for the GPU's float sums (padForGpu, accel/majorant_bounds.h).
RangeGrid buildRangeGrid(const BrickGrid& lists, const BrickSet& bricks, std::span<const float> brickValues);

// Value ranges of the n^3 equal sub-boxes of one macrocell of `lists`' layout, made as
// buildRangeGrid makes a macrocell's: each sub-box grown by the grid's margin (on the grid's outer
// faces it reaches outwards, as an edge macrocell does), exact on the lattice of breakpoints where
// that is small, else the union of the per-brick ranges, padded for the GPU; the bricks are the
// macrocell's list (every brick meeting a grown sub-box meets the grown macrocell). What
// scene/sub_majorants refines a loose macrocell with. Holds what every call needs of the bricks
// (their signs), made once; the three arguments must outlive it.
inline constexpr int kMaxSubdivision = 16;
class SubRangeMaker {
public:
    SubRangeMaker(const BrickGrid& lists, const BrickSet& bricks, std::span<const float> brickValues);
    // Ranges of macrocell `cell`'s sub-boxes (1 <= n <= kMaxSubdivision per axis), x fastest, into
    // `out`. Safe to call from several threads at once.
    void ranges(size_t cell, int n, std::vector<ValueRange>& out) const;

private:
    struct Signs;
    const BrickGrid& mLists;
    const BrickSet& mBricks;
    std::span<const float> mValues;
    std::shared_ptr<const Signs> mSigns;
};

}  // namespace amrvk::accel
