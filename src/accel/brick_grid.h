#pragma once
// Brick grid: the macrocell grid (MacrocellLayout, as RangeGrid) with, per macrocell, the ascending ids
// of the bricks whose basis domain (closed) meets the macrocell grown by a margin. A point lookup
// is one index computation and a short list: no tree descent (issue 12). Sampling through it
// visits every brick whose domain contains p, in ascending id order, exactly as ExtBrickSampler
// sums them, so the value is the ext-brick value. Twin: sampleGrid in shaders/lib/amr_sample.glsl.
#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

#include "accel/bricks.h"
#include "accel/range_grid.h"
#include "amr/sampler.h"

namespace amrvk::accel {

struct BrickGrid : MacrocellLayout {
    // lists[0 .. cellCount()] are offsets (macrocell i lists ids lists[lists[i] .. lists[i + 1]);
    // offsets count from the start of the array, so one buffer on the GPU), then the brick ids.
    std::vector<uint32_t> lists;
    double buildSeconds = 0;
    uint64_t memoryBytes() const { return lists.size() * sizeof(uint32_t); }
    std::span<const uint32_t> bricksOf(size_t cell) const {
        return {lists.data() + lists[cell], lists.data() + lists[cell + 1]};
    }
};

// Margin (voxel units, per axis) by which a macrocell is grown when its list and its range are
// made: at least 1e-4 macrocell and positionMargin (accel/majorant_bounds.h) of the grid's
// longest extent, far above the float rounding of a local-space sample position and of its
// macrocell index on the GPU.
glm::dvec3 brickGridMargin(const glm::dvec3& cellSize, const glm::ivec3& dims);

// Lists over macrocellLayout(bounds, dims). Throws when the lists would not fit in
// uint32 offsets or in the memory budget.
BrickGrid buildBrickGrid(const BrickSet& bricks, const amr::Box3l& bounds, glm::ivec3 dims);

class GridSampler {
public:
    GridSampler(const BrickGrid& grid, const BrickSet& bricks, std::span<const float> brickValues)
        : mGrid(grid), mBricks(bricks), mValues(brickValues) {}
    // The bricks of the macrocell holding p (cellOf: what sampleGrid computes in float).
    amr::Sample sample(glm::dvec3 p) const;

private:
    const BrickGrid& mGrid;
    const BrickSet& mBricks;
    std::span<const float> mValues;
};

}  // namespace amrvk::accel
