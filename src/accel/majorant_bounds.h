#pragma once
// What a value range must cover so that the majorant the GPU derives from it bounds every sample
// the tracker takes in its box: the one rule every traversal's ranges follow (macrocells, ABRs,
// brick bounds and domains, kd leaves, dense macrocells), checked exhaustively against the
// reconstruction by scene/majorant_check.* (`amrvk info --check-majorants`).
//  - Space: a sample at o + d t is computed in float in local voxel space (ray origins rebased
//    to where they enter the data, lib/traversal.glsl), so it can lie a little outside the box
//    whose segment produced t. A range covers the box grown by positionMargin(bounds) on every
//    side: 2^-18 of the longest extent, 64x the float rounding of a position there.
//  - Values: the GPU reconstructs f = sum(phi v) / sum(phi) in float (lib/amr_sample.glsl), which
//    can leave the exact range by about (2n + 1) u sum(phi |v|) / sum(phi) for n weighted terms
//    (u = 2^-24); a spiky TF turns that into a large relative excess of alpha. A range is widened
//    by kGpuPadUlps float epsilons of a bound on that magnitude (padForGpu); the check asks for
//    kGpuErrorUlps of room on each side.
#include <cstdint>

#include "accel/value_range.h"
#include "amr/model.h"

namespace amrvk::accel {

// Float epsilons (2^-23) of a range's largest magnitude by which a range is widened...
inline constexpr double kGpuPadUlps = 128.0;
// ...and the GPU's float reconstruction error the check requires room for: (2n + 1) u for up to
// n = 64 weighted terms and one division, in epsilons (2u).
inline constexpr double kGpuErrorUlps = 64.0;

// Voxel units by which every traversal box's range must extend beyond the box (per side), for
// data whose longest extent (voxel units) is `longestExtent`, or over `bounds`.
double positionMargin(double longestExtent);
double positionMargin(const amr::Box3l& bounds);

// Half-voxel units by which a closed box on the half-voxel lattice is grown before a
// "support touches the closed box" query so that the range covers `margin` beyond it. Cell
// supports end on the half-voxel lattice, so touching already covers anything closer than half
// a voxel: floor(2 margin) (0 below half a voxel).
int64_t marginHalfUnits(double margin);

// [lo, hi] widened by kGpuPadUlps epsilons of maxAbs, a bound on sum(phi |v|) / sum(phi) in the
// box (the GPU sum's error scales with it; max(|lo|, |hi|) is used when larger), rounded outward
// to float. Empty (lo > hi or NaN) stays empty.
ValueRange padForGpu(double lo, double hi, double maxAbs);
// A range of cell values (its own bounds are the largest magnitudes involved).
ValueRange padForGpu(const ValueRange& r);

}  // namespace amrvk::accel
