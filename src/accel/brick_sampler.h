#pragma once
// Reconstruction through bricks (exabrick-reference.md 3.1-3.2): the same tent-weighted sum as
// amr::ReferenceSampler, gathered per brick as clamped trilinear weights over <= 8 cells. Two ways
// to find the bricks at P (the paper's samplers):
//   ExtBrick: a BVH over brick domains; every brick whose domain contains P contributes.
//   Abr:      a BVH over ABR boxes; the one ABR containing P lists the contributing bricks.
// Neither structure is ever culled by a transfer function.
#include <glm/glm.hpp>

#include <cmath>
#include <span>

#include "accel/abrs.h"
#include "accel/bricks.h"
#include "accel/bvh.h"
#include "amr/sampler.h"

namespace amrvk::accel {

// One axis of a brick's clamped trilinear weights at cell-centre coordinate `local` (cell k's centre
// at k): the (at most two) cells inside the brick, [0, size), with their linear weights, lower
// cell first. The tent weight of a cell is the product of its three axes' weights.
struct TentAxis {
    int cell[2];
    double weight[2];
    int count;  // no default, so arrays of them cost nothing to declare
};
TentAxis tentAxis(double local, int32_t size);

// Adds the tent weights phi = x.weight * y.weight * z.weight of brick b's (at most 8) cells given
// by the three axes, and phi * value, to (sumW, sumWV), z slowest and x fastest; cells of zero
// weight and NaN (empty) slots are skipped.
inline void addTentCells(const Brick& b, std::span<const float> brickValues, const TentAxis& x, const TentAxis& y,
                         const TentAxis& z, double& sumW, double& sumWV) {
    for (int cz = 0; cz < z.count; ++cz)
        for (int cy = 0; cy < y.count; ++cy) {
            const size_t row = b.begin + size_t((int64_t(z.cell[cz]) * b.size.y + y.cell[cy]) * b.size.x);
            for (int cx = 0; cx < x.count; ++cx) {
                const double phi = x.weight[cx] * y.weight[cy] * z.weight[cz];
                const float v = brickValues[row + size_t(x.cell[cx])];
                if (phi <= 0 || std::isnan(v)) continue;
                sumW += phi;
                sumWV += phi * double(v);
            }
        }
}

// The tent-weighted value at p over the listed bricks whose domain contains p, summed in list
// order (the grid sampler's lists, the exact range lattice).
amr::Sample sampleBricks(std::span<const uint32_t> ids, const BrickSet& bricks, std::span<const float> brickValues,
                         glm::dvec3 p);

// Voxel-space double boxes of the brick domains / ABRs (BVH inputs).
std::vector<BoxD> brickDomainBoxes(const BrickSet& bricks);
std::vector<BoxD> abrBoxes(const AbrSet& abrs);

class ExtBrickSampler {
public:
    ExtBrickSampler(const BrickSet& bricks, std::span<const float> brickValues);
    amr::Sample sample(glm::dvec3 p) const;

private:
    const BrickSet& mBricks;
    std::span<const float> mValues;
    std::vector<HalfBox> mDomains;
    Bvh mBvh;
};

class AbrSampler {
public:
    AbrSampler(const AbrSet& abrs, const BrickSet& bricks, std::span<const float> brickValues);
    amr::Sample sample(glm::dvec3 p) const;
    // Evaluates with the bricks of a known ABR (no lookup): the ABR-traversal + ABR-sampler path.
    amr::Sample sampleInAbr(const Abr& abr, glm::dvec3 p) const;
    // Index of an ABR whose closed box contains p, or -1.
    int64_t findAbr(glm::dvec3 p) const;

private:
    const AbrSet& mAbrs;
    const BrickSet& mBricks;
    std::span<const float> mValues;
    Bvh mBvh;
};

}  // namespace amrvk::accel
