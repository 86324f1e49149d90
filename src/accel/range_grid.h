#pragma once
// Macrocell value ranges: a uniform grid over the union of leaf-cell bounds (voxel space); each
// macrocell holds the range of every cell whose tent support (centre +- one cell width) overlaps
// or touches it, so it bounds the reconstructed value anywhere inside the macrocell.
#include <glm/glm.hpp>

#include <span>
#include <vector>

#include "accel/value_range.h"
#include "amr/model.h"

namespace amrvk::accel {

struct RangeGrid {
    glm::ivec3 dims{0};           // macrocells per axis
    glm::dvec3 origin{0};         // lower corner, voxel space
    glm::dvec3 cellSize{1};       // macrocell extent per axis, voxel units
    std::vector<ValueRange> ranges;  // x fastest: index = x + dims.x * (y + dims.y * z)
    double buildSeconds = 0;
    uint64_t memoryBytes() const { return ranges.size() * sizeof(ValueRange); }
    size_t index(glm::ivec3 c) const { return size_t(c.x) + size_t(dims.x) * (size_t(c.y) + size_t(dims.y) * size_t(c.z)); }
    // Macrocell containing voxel-space point p, clamped to the grid.
    glm::ivec3 cellOf(glm::dvec3 p) const;
};

// Grid resolution with `longest` macrocells on the longest axis (at most one per voxel unit) and
// near-cubical macrocells elsewhere.
glm::ivec3 autoGridDims(const amr::Box3l& bounds, int longest = 128);

// Parses "auto", "N" (N on the longest axis) or "NxMxK". Throws on anything else or N outside [1, 4096].
glm::ivec3 parseGridDims(const std::string& text, const amr::Box3l& bounds);

// The grid's dims, origin and macrocell size over `bounds`, with no ranges yet.
RangeGrid rangeGridLayout(const amr::Box3l& bounds, glm::ivec3 dims);

RangeGrid buildRangeGrid(const amr::Model& model, const amr::Field& field, glm::ivec3 dims);

}  // namespace amrvk::accel
