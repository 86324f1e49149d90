#pragma once
// Bricks: full, single-level boxes of leaf cells (exabrick-reference.md 2.1). Every leaf cell is
// in exactly one brick; values are stored in brick order (x fastest inside a brick). Made by the
// brick build (accel/brick_build.h) or read from a .bricks file (accel/bricks_file.h).
#include <glm/glm.hpp>

#include <cstdint>
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

// Values of `field` in brick order (NaN for empty slots); a copy of the field after buildBricks.
std::vector<float> brickOrderValues(const BrickSet& bricks, const amr::Field& field);

struct BrickStats {
    uint64_t brickCount = 0, singleCellBricks = 0;
    double averageCellsPerBrick = 0;
    uint64_t largestBrickCells = 0;
};
BrickStats computeBrickStats(const BrickSet& bricks);

}  // namespace amrvk::accel
