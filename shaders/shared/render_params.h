// Everything a render or majorant pass reads, in one buffer addressed by device address.
// Spaces: local voxel space (voxel - localOrigin). Distances along rays are in voxel units;
// extinction sigma_t = alpha(TF(v)) * densityScale / finestCellWidth per voxel unit, i.e.
// alpha * densityScale per finest cell width (architecture.md, "Units and semantics").
#ifndef AMRVK_RENDER_PARAMS_H
#define AMRVK_RENDER_PARAMS_H
#include "interop.h"

AMRVK_NAMESPACE_BEGIN

AMRVK_CONST uint kMaxLights = 8u;
AMRVK_CONST uint kLightDirectional = 0u;
AMRVK_CONST uint kLightPoint = 1u;

// Render modes (specialization constant kMode).
AMRVK_CONST uint kModeAe = 0u;  // absorption + emission
AMRVK_CONST uint kModeSs = 1u;  // single scattering
AMRVK_CONST uint kModeMs = 2u;  // multiple scattering
AMRVK_CONST uint kModeDvr = 3u; // ray-marching baseline (ExaBrick's DVR): biased by its step

// Samplers (specialization constant kSampler).
AMRVK_CONST uint kSamplerExtBrick = 0u;
AMRVK_CONST uint kSamplerAbr = 1u;
AMRVK_CONST uint kSamplerDense = 2u;  // uniform finest-level resampling, clamped trilinear (cost floor)

// Majorant traversals (specialization constant kTraversal). grid-dda steps through the macrocell
// grid; the others query a set of boxes ("domains", each with a majorant) for the segment that
// starts at the current t: abr = ABR boxes, brick = strict brick bounds, ext-brick = brick basis
// domains (they overlap: the majorant is the maximum over the boxes covering t), grid-bvh =
// non-empty macrocells, kdtree = leaves of the TF-specific kd-tree.
AMRVK_CONST uint kTraversalGridDda = 0u;
AMRVK_CONST uint kTraversalGridBvh = 1u;
AMRVK_CONST uint kTraversalAbr = 2u;
AMRVK_CONST uint kTraversalBrick = 3u;
AMRVK_CONST uint kTraversalExtBrick = 4u;
AMRVK_CONST uint kTraversalKdTree = 5u;

// Back-ends of the box hierarchies (specialization constant kBackend): software BVH in GLSL or
// VK_KHR_ray_query over an AABB BLAS (only in the path_trace_rq shader variant).
AMRVK_CONST uint kBackendSw = 0u;
AMRVK_CONST uint kBackendRq = 1u;

// Per-frame counters (uint32 each, reset per dispatch, summed on the host in 64 bits).
AMRVK_CONST uint kCounterDensityLookups = 0u;
AMRVK_CONST uint kCounterRealCollisions = 1u;
AMRVK_CONST uint kCounterNullCollisions = 2u;
AMRVK_CONST uint kCounterTraversalSteps = 3u;
AMRVK_CONST uint kCounterMajorantViolations = 4u;
AMRVK_CONST uint kCounterBounceLimitHits = 5u;
AMRVK_CONST uint kCounterNanSamples = 6u;
AMRVK_CONST uint kCounterCount = 8u;

AMRVK_CONST uint kMaxBounces = 65536u;  // ms path length cap; paths reaching it are counted

struct LightGpu {
    vec4 posOrDir;  // xyz: point position (local voxel) or direction *towards* the light; w: type
    vec4 radiance;  // rgb: radiance (directional) or intensity (point, falls off as 1/d^2)
};
AMRVK_STATIC_ASSERT(sizeof(LightGpu) == 32);

struct RenderParams {
    // Camera (local voxel space): ray(x, y) = eye + normalize(dir00 + u * du + v * dv).
    vec4 eye;
    vec4 dir00;
    vec4 du;
    vec4 dv;
    uvec4 image;         // x: width, y: height, z: seed, w: frame index (sample number)
    // Data
    vec4 boundsLo;       // xyz: union of leaf cells, local voxel; w: 1 / finestCellWidth
    vec4 boundsHi;       // xyz; w: densityScale
    ivec4 gridDims;      // xyz macrocells; w: unused
    vec4 gridOrigin;     // xyz local voxel; w unused
    vec4 gridCellSize;   // xyz voxel units per macrocell
    // Transfer function: nodes at tfPositions[i] (ascending, field values) with tfColors[i].
    vec4 tfInfo;         // x: node count (as float), yzw unused
    // Lighting
    vec4 ambient;        // rgb: environment radiance seen by rays that escape
    vec4 background;     // rgb: radiance seen by primary rays that escape
    vec4 shading;        // x: HG g; y: light count (as float); zw unused
    // dvr: x: step relative to the finest cell width at the sample; y: 1 = gradient shading;
    // z: opacity at which a ray terminates (0.99); w: ambient term of the shading
    vec4 dvr;
    vec4 dvrLight;       // xyz: unit direction towards the shading light (local voxel); w unused
    // dense sampler: sample (i, j, k) at denseOrigin + (ijk + 0.5) * denseOrigin.w
    ivec4 denseDims;     // xyz: samples per axis; w: level of the spacing (1 << w)
    vec4 denseOrigin;    // xyz: local voxel; w: sample spacing (voxel units)
    LightGpu lights[kMaxLights];
    // Buffers (device addresses)
    uint64_t bricks;        // BrickGpu[]
    uint64_t brickValues;   // float[] in brick order (NaN = empty slot)
    uint64_t samplerNodes;  // BvhNodeGpu[] over brick domains (ext-brick) or ABR boxes (abr)
    uint64_t samplerPrims;  // uint[] BVH slot -> brick id or ABR id
    uint64_t abrs;          // AbrGpu[]
    uint64_t abrBrickList;  // uint[]
    uint64_t gridRanges;    // vec2[] value range per macrocell
    uint64_t gridMajorants; // float[] max alpha per macrocell (majorant pass output)
    uint64_t samplerAccel;  // TLAS over sampler boxes (rq back-end), else 0
    uint64_t domainBoxes;   // AabbGpu[] traversal boxes (not for grid-bvh: computed from the grid)
    uint64_t domainRanges;  // vec2[] value range per traversal box (grid-bvh: = gridRanges)
    uint64_t domainMajorants; // float[] max alpha per traversal box (grid-bvh: = gridMajorants)
    uint64_t domainNodes;   // BvhNodeGpu[] over the boxes with majorant > 0 (sw back-end)
    uint64_t domainPrims;   // uint[] BVH slot -> box id
    uint64_t domainAccel;   // TLAS over the boxes, culled ones inactive (rq back-end)
    uvec4 domainInfo;       // x: box count; y: 1 when some box has majorant > 0; zw unused
    uint64_t tfPositions;   // float[]
    uint64_t tfColors;      // vec4[] rgb albedo, a = alpha (extinction per finest cell width)
    uint64_t denseValues;   // float[] dense samples, x fastest (NaN: outside the medium), else 0
    uint64_t accum;         // vec4[2 * pixels]: sum and sum of squares of radiance; w = count
    uint64_t counters;      // uint[kCounterCount]
};

struct PushConstants {
    uint64_t params;  // RenderParams address
    uint frameIndex;  // sample number of this dispatch
    uint pad;
};
AMRVK_STATIC_ASSERT(sizeof(PushConstants) == 16);

// majorants.comp: majorants[i] = max TF alpha over ranges[i] for i < count. domain_aabbs.comp:
// aabbs[i] = box i, or the point lo when majorants[i] == 0 (ray-query culling).
struct StructurePush {
    uint64_t params;     // RenderParams address (TF, grid, domain boxes)
    uint64_t ranges;     // vec2[] (majorants.comp) or float[] majorants (domain_aabbs.comp)
    uint64_t target;     // float[] majorants or AabbGpu[]
    uint count;
    uint kind;           // domain_aabbs.comp: traversal kind (grid-bvh computes boxes)
};
AMRVK_STATIC_ASSERT(sizeof(StructurePush) == 32);

AMRVK_NAMESPACE_END
#endif
