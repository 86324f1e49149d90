#pragma once
// Bricks: full, single-level boxes of leaf cells (exabrick-reference.md 2.1). Every leaf cell is
// in exactly one brick; values are stored in brick order (x fastest inside a brick).
#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <vector>

#include "amr/model.h"

namespace amrvk::accel {

struct Brick {
    glm::ivec3 lower;  // lower corner, voxel space (finest-level units)
    glm::ivec3 size;   // cells per axis, each in [1, kMaxBrickCells]
    int32_t level;     // cell width = 1 << level
    uint32_t begin;    // index of the brick's first cell in brick order
    int64_t cellWidth() const { return int64_t{1} << level; }
    uint64_t cellCount() const { return uint64_t(size.x) * uint64_t(size.y) * uint64_t(size.z); }
    // Strict bounds [lower, lower + size * width), voxel space.
    amr::Box3l bounds() const;
};

using amr::ceilDiv;
using amr::floorDiv;

constexpr int32_t kMaxBrickCells = 127;  // per axis, as exaBuilder's default --max-leaf-width

struct BrickSet {
    std::vector<Brick> bricks;
    // Brick order -> model cell index (kEmptySlot for a hole); empty when the model itself is in
    // brick order (buildBricks), i.e. slot i is cell i.
    std::vector<uint32_t> cellIds;
    static constexpr uint32_t kEmptySlot = UINT32_MAX;
    double buildSeconds = 0;
    uint32_t cellId(uint64_t slot) const { return cellIds.empty() ? uint32_t(slot) : cellIds[slot]; }
    // Brick slots in all (= cells, plus the holes of a .bricks file); bricks are in slot order.
    uint64_t slotCount() const { return bricks.empty() ? 0 : bricks.back().begin + bricks.back().cellCount(); }
    uint64_t memoryBytes() const {
        return bricks.size() * sizeof(Brick) + cellIds.size() * sizeof(uint32_t);
    }
};

// Builds bricks with the exaBuilder SAH-alike kd split: partition at coarse-cell planes where the
// level set or fullness changes, minimising halfArea(L) * volume(L) * levels(L) + same(R); a node
// becomes a brick when it is one level, completely filled, and at most kMaxBrickCells per axis.
// Reorders model.cells and every field, in place, into brick order (x fastest inside a brick), so
// no per-cell copy is made and cellIds stays empty. Finds overlapping cells on the way (cells in
// different bricks lie in disjoint kd regions; within a brick two cells on one slot, or a node
// inside one cell of its own) and throws "SOURCE: overlapping cells: (lower ..) lies inside (..)";
// the model is then some permutation of itself. The order is a function of the set of cells, so
// building again (or from any file order) gives the same model and bricks.
//
// Where a node's cube grid (its cells' statistics per coarsest cell) decides its top levels, the
// build plans them on the grid and moves the cells once (a multi-way partition) instead of once per
// level; the bricks and the order are the same either way.
struct BrickBuildTuning {
    size_t planCells = size_t{1} << 16;  // nodes of at least this many cells are planned; SIZE_MAX: never
};
// `known`: the model's summary where the caller has it (scene::makeVolume), which saves the
// build's first pass over the cells; it must be summarize(model).
BrickSet buildBricks(amr::Model& model, const BrickBuildTuning& tuning = {}, const amr::ModelSummary* known = nullptr);

// Reads a .bricks file of the ExaBrick builders (records: int3 size, int3 lower, int level,
// int cellId[size]) and checks it against the model: every cell id valid and used once, ids -1
// are empty slots, every brick slot at the position of the cell it names.
BrickSet readBricksFile(const std::filesystem::path& path, const amr::Model& model);

// Writes bricks in the same .bricks format (empty slots as -1), atomically.
void writeBricksFile(const std::filesystem::path& path, const BrickSet& bricks);

// Values of `field` in brick order (NaN for empty slots); a copy of the field after buildBricks.
std::vector<float> brickOrderValues(const BrickSet& bricks, const amr::Field& field);

struct BrickStats {
    uint64_t brickCount = 0, singleCellBricks = 0;
    double averageCellsPerBrick = 0;
    uint64_t largestBrickCells = 0;
};
BrickStats computeBrickStats(const BrickSet& bricks);

}  // namespace amrvk::accel
