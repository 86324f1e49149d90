#pragma once
// The "dense" speed-of-light sampler, CPU side: the AMR reconstruction (exabrick-reference.md 3.1,
// the same tent-weighted sum as amr::ReferenceSampler / ExtBrickSampler) resampled once onto a
// uniform grid at the finest cell width, so a GPU pass can read it with one clamped trilinear fetch.
//  - Space: voxel space (finest-level integer units). Sample (i, j, k) sits at the centre
//    origin + (idx + 0.5) * width, width = 1 << level voxel units.
//  - NaN marks a sample whose centre lies in no leaf cell (the leaf cells are rasterised; the
//    reconstruction's weights, which reach half a cell beyond the medium, play no part in that).
//  - sampleDense is the GPU interpolation (clamped indices, NaN samples skipped and the weights
//    renormalised); assignDenseRanges makes every macrocell range bound every value sampleDense can
//    return anywhere inside that macrocell, so empty-space skipping over the ranges stays exact.
#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

#include "accel/bricks.h"
#include "accel/range_grid.h"
#include "amr/model.h"

namespace amrvk::accel {

struct DenseGrid {
    glm::i64vec3 origin{0};     // voxel space: lower corner of the data bounds
    int32_t level = 0;          // sample spacing = 1 << level voxel units (the finest level present)
    glm::ivec3 dims{0};         // samples per axis = ceil(bounds size / width)
    std::vector<float> values;  // x fastest; NaN where the sample centre lies in no leaf cell
    double buildSeconds = 0;
    uint64_t memoryBytes() const { return values.size() * sizeof(float); }
    double width() const { return double(amr::cellWidth(level)); }
    size_t index(glm::ivec3 c) const {
        return size_t(c.x) + size_t(dims.x) * (size_t(c.y) + size_t(dims.y) * size_t(c.z));
    }
    // Voxel-space centre of sample c.
    glm::dvec3 centre(glm::ivec3 c) const { return glm::dvec3(origin) + (glm::dvec3(c) + 0.5) * width(); }
};

// Bytes buildDenseGrid would allocate for these bounds at this level (no allocation); saturates at
// UINT64_MAX when the count does not fit.
uint64_t denseGridBytes(const amr::Box3l& bounds, int32_t level);

// Resamples the field given in brick order (brickOrderValues) over `bounds` (normally
// summarize(model).bounds) at spacing 1 << level. Throws amrvk::Error with one line naming the
// needed and allowed bytes when denseGridBytes > maxBytes or the sample count does not fit.
DenseGrid buildDenseGrid(const amr::Model& model, const BrickSet& bricks, std::span<const float> brickValues,
                         const amr::Box3l& bounds, int32_t level, uint64_t maxBytes);

// Replaces grid.ranges (same dims/origin/cellSize) by the range of the dense samples clamped
// trilinear interpolation can read anywhere inside each macrocell: for a macrocell [a, b], with
// q = (p - origin) / width - 0.5, the indices floor(qa) .. floor(qb) + 1 per axis clamped to
// [0, dims - 1]. The box is first grown by 1e-5 macrocell or the position margin, whichever is
// larger (accel/majorant_bounds.h), so float rounding of GPU sample positions near a face stays
// covered, and the range is padded for the GPU's float sums. NaN samples are ignored; a macrocell
// that reads only NaN samples gets an empty range.
void assignDenseRanges(const DenseGrid& dense, RangeGrid& grid);

// Trilinear interpolation exactly as the GPU does it: q = (p - origin) / width - 0.5, i0 = floor(q),
// f = q - i0; the 8 samples i0 + {0,1}^3 with indices clamped to [0, dims - 1], NaN samples skipped
// and the remaining weights renormalised. inside = the sample of the dense cell containing p
// (floor((p - origin) / width), clamped) is not NaN; value is NaN when no non-NaN sample has weight
// (always the case when all 8 are NaN; never when inside).
struct DenseSample {
    float value;
    bool inside;
};
DenseSample sampleDense(const DenseGrid& dense, glm::dvec3 p);

}  // namespace amrvk::accel
