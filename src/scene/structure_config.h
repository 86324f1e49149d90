#pragma once
// Which structures a render uses: majorant traversal x sample reconstruction x back-end
// (paper Section 5; exabrick-reference.md 3-4). Every combination but dense without a grid
// traversal is valid at run time; what each one builds is decided by scene/structure_plan.h.
#include <cstdint>
#include <string>
#include <vector>

#include "scene/structure_plan.h"

namespace amrvk::scene {

// The kinds are defined once for C++ and GLSL in shaders/shared/kinds.h; their values are the
// shaders' specialization constants. Backend Sw: software BVHs in GLSL; Rq: VK_KHR_ray_query over
// AABB BLASes; Auto: chosen for the device (resolveBackend) before a scene is configured.
SamplerKind parseSampler(const std::string& name);
const char* samplerName(SamplerKind kind);
TraversalKind parseTraversal(const std::string& name);
const char* traversalName(TraversalKind kind);
Backend parseBackend(const std::string& name);
const char* backendName(Backend backend);
std::vector<TraversalKind> allTraversals();
// StructureConfig::subMajorants from its spelling: "off" (0) or 2, 4, 8, 16; errors name `option`.
uint32_t parseSubMajorants(const std::string& text, const char* option = "--sub-majorants");
std::string subMajorantsName(uint32_t subMajorants);  // "off" or the number
std::vector<SamplerKind> allSamplers();  // the AMR samplers: the paper's two and grid (not dense)

struct StructureConfig {
    SamplerKind sampler = SamplerKind::Grid;  // the fastest exact lookup (issue 12)
    TraversalKind traversal = TraversalKind::GridDda;
    Backend backend = Backend::Sw;  // resolved (Sw or Rq) before a scene is configured
    std::string grid = "auto";      // macrocells (grid-dda, grid-bvh, grid sampler): auto | N | NxMxK
    uint32_t kdLeaves = 4096;       // kdtree leaves
    // Grid traversals: split each macrocell that the TF makes loose into at most N^3 sub-boxes with
    // majorants of their own (N = 2, 4, 8 or 16), rebuilt per TF (scene/sub_majorants.h); 0: off.
    // The same picture with fewer lookups where a TF has narrow peaks (1.6-2.5x on spiky,
    // docs/benchmarks.md section 27), nothing built where it has none.
    uint32_t subMajorants = 8;
    uint64_t denseMaxBytes = uint64_t(2) << 30;  // dense sampler: refuse larger grids
    // Every field takes part: two configs are equal when they build the same structures.
    bool operator==(const StructureConfig&) const = default;
    // What this combination builds (backend must be resolved).
    StructurePlan plan() const { return planOf(traversal, sampler, backend, subMajorants > 0); }
    // Whether a macrocell grid (--grid) is part of the combination: grid traversals, grid sampler.
    bool usesGrid() const;
    // Whether the combination has sub-majorants: asked for, a grid traversal, an AMR sampler.
    bool hasSubMajorants() const;
    // Throws a one-line error for a combination that cannot run (dense without a grid traversal).
    void validate() const;
    std::string label() const;          // e.g. "grid-dda/ext-brick/sw"
    std::string labelWithSub() const;   // and " sub N" with sub-majorants: "grid-dda/grid/sw sub 8"
    // and " grid <grid>" where a grid is used, then " sub N": "grid-dda/grid/sw grid 64 sub 8"
    std::string labelWithGrid() const;
};

// Which traversal fits the data when none is asked for: grid-dda (the paper's default) where the
// leaf cells fill at least kGridMinCoverage of their bounding box, else abr. Over sparse data a
// uniform macrocell grid is mostly empty space whose majorant is set by the few cells inside:
// 20,000 cells scattered over a 2^30-wide box give macrocells 2^23 cells wide and millions of
// null collisions per crossing, while ABRs hug the cells. `why` gets one line for the log.
constexpr double kGridMinCoverage = 1e-3;
TraversalKind fittingTraversal(double leafVolume, double boundsVolume, std::string* why = nullptr);

// What the back-end choice depends on, without Vulkan.
struct DeviceTraits {
    std::string name;
    bool cpu = false;       // a CPU implementation (lavapipe, SwiftShader)
    bool rayQuery = false;  // VK_KHR_ray_query available
};
struct BackendChoice {
    Backend backend = Backend::Sw;
    std::string why;  // one line: why auto chose it (empty when the back-end was given)
};
// Resolves Backend::Auto for `config` on `device`: sw where the combination uses no box hierarchy
// (the back-ends are identical there), sw on CPU devices (ray queries measured 3-4x slower than
// the software BVH on lavapipe, docs/benchmarks.md), and sw on GPUs, where ray queries have not
// been measured faster yet (rq stays one option away; --traversal auto measures both). A given Rq
// on a device without ray queries is an error naming the device.
BackendChoice resolveBackend(const StructureConfig& config, const DeviceTraits& device);

}  // namespace amrvk::scene
