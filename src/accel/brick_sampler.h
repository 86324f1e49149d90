#pragma once
// Reconstruction through bricks (exabrick-reference.md 3.1-3.2): the same tent-weighted sum as
// amr::ReferenceSampler, gathered per brick as clamped trilinear weights over <= 8 cells. Two ways
// to find the bricks at P (the paper's samplers):
//   ExtBrick: a BVH over brick domains; every brick whose domain contains P contributes.
//   Abr:      a BVH over ABR boxes; the one ABR containing P lists the contributing bricks.
// Neither structure is ever culled by a transfer function.
#include <glm/glm.hpp>

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

// Adds brick b's tent weights at voxel-space p to (sumW, sumWV); p must lie in the brick domain.
// NaN (empty) slots are skipped.
void addBrickContribution(const Brick& b, std::span<const float> brickValues, glm::dvec3 p,
                          double& sumW, double& sumWV);

// The tent-weighted value at p over the listed bricks whose domain contains p, summed in list
// order (the grid sampler's lists, the exact range lattice).
amr::Sample sampleBricks(std::span<const uint32_t> ids, const BrickSet& bricks, std::span<const float> brickValues,
                         glm::dvec3 p);

// Voxel-space double boxes of the brick domains / ABRs (BVH inputs).
std::vector<BoxD> brickDomainBoxes(const BrickSet& bricks);
std::vector<BoxD> abrBoxes(const AbrSet& abrs);

bool halfBoxContains(const HalfBox& box, glm::dvec3 p);

class ExtBrickSampler {
public:
    ExtBrickSampler(const BrickSet& bricks, std::span<const float> brickValues);
    amr::Sample sample(glm::dvec3 p) const;
    const Bvh& bvh() const { return mBvh; }

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
    const Bvh& bvh() const { return mBvh; }

private:
    const AbrSet& mAbrs;
    const BrickSet& mBricks;
    std::span<const float> mValues;
    Bvh mBvh;
};

}  // namespace amrvk::accel
