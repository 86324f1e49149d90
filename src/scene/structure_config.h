#pragma once
// Which structures a render uses: majorant traversal x sample reconstruction x back-end
// (paper Section 5; exabrick-reference.md 3-4). Every combination is valid at run time.
#include <cstdint>
#include <string>
#include <vector>

#include "shared/kinds.h"

namespace amrvk::scene {

// The kinds are defined once for C++ and GLSL in shaders/shared/kinds.h; their values are the
// shaders' specialization constants. Dense: the field resampled to a uniform finest-level grid
// (clamped trilinear), the cost floor of sampling; it needs a grid traversal (its majorants come
// from the dense samples). Backend Sw: software BVHs in GLSL; Rq: VK_KHR_ray_query over AABB
// BLASes; Auto: Rq where the device has it (resolved before a scene is configured).
using shared::Backend;
using shared::SamplerKind;
using shared::TraversalKind;

SamplerKind parseSampler(const std::string& name);
const char* samplerName(SamplerKind kind);
TraversalKind parseTraversal(const std::string& name);
const char* traversalName(TraversalKind kind);
Backend parseBackend(const std::string& name);
const char* backendName(Backend backend);
std::vector<TraversalKind> allTraversals();
std::vector<SamplerKind> allSamplers();  // the AMR samplers: the paper's two and grid (not dense)

struct StructureConfig {
    SamplerKind sampler = SamplerKind::Grid;  // the fastest exact lookup (issue 12)
    TraversalKind traversal = TraversalKind::GridDda;
    Backend backend = Backend::Sw;  // resolved (Sw or Rq) before a scene is configured
    std::string grid = "auto";      // macrocells (grid-dda, grid-bvh, grid sampler): auto | N | NxMxK
    uint32_t kdLeaves = 4096;       // kdtree leaves
    uint64_t denseMaxBytes = uint64_t(2) << 30;  // dense sampler: refuse larger grids
    // Whether the combination uses a BVH (sampler always; traversal unless grid-dda).
    bool traversalUsesBoxes() const { return traversal != TraversalKind::GridDda; }
    bool usesGrid() const { return traversal == TraversalKind::GridDda || traversal == TraversalKind::GridBvh; }
    bool usesAbrs() const { return sampler == SamplerKind::Abr || traversal == TraversalKind::Abr; }
    bool usesBrickGrid() const { return sampler == SamplerKind::Grid; }
    bool usesBricks() const { return sampler != SamplerKind::Dense; }  // on the GPU
    // Throws a one-line error for a combination that cannot run (dense without a grid traversal).
    void validate() const;
    std::string label() const;          // e.g. "grid-dda/ext-brick/sw"
    std::string labelWithGrid() const;  // and " grid <grid>" where a grid is used: "grid-dda/grid/sw grid 64"
};

// Which traversal fits the data when none is asked for: grid-dda (the paper's default) where the
// leaf cells fill at least kGridMinCoverage of their bounding box, else abr. Over sparse data a
// uniform macrocell grid is mostly empty space whose majorant is set by the few cells inside:
// 20,000 cells scattered over a 2^30-wide box give macrocells 2^23 cells wide and millions of
// null collisions per crossing, while ABRs hug the cells. `why` gets one line for the log.
constexpr double kGridMinCoverage = 1e-3;
TraversalKind fittingTraversal(double leafVolume, double boundsVolume, std::string* why = nullptr);

// Resolves Backend::Auto: Rq when the device supports ray queries, else Sw; a requested Rq on a
// device without ray queries is an error naming the device.
Backend resolveBackend(Backend requested, bool deviceHasRayQuery, const std::string& deviceName);

}  // namespace amrvk::scene
