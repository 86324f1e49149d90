// Everything a render or majorant pass reads, in one buffer addressed by device address, split
// into blocks by the component that writes them, so each kind of change rewrites only its block:
//   ViewGpu      camera and image          (Renderer: camera, size, seed)
//   ShadingGpu   medium scale and lights   (Renderer: lighting, density, phase, dvr)
//   SceneGpu     TF-independent structures (DeviceScene: one structure combination)
//   MajorantsGpu TF and TF-dependent data  (MajorantPass: majorants, culled hierarchy, kd-tree)
//   CutAwayGpu   crop box and clip planes  (Renderer: with the medium, cut_away_gpu.h)
// Spaces: local voxel space (voxel - local origin). Distances along rays are in voxel units;
// extinction sigma_t = alpha(TF(v)) * densityScale * invFinestCellWidth per voxel unit, i.e.
// alpha * densityScale per finest cell width (architecture.md, "Units and semantics").
// Layout: scalar block layout; every vec3 starts at a multiple of 16 and is followed by a 4-byte
// scalar; offsets are asserted below and checked on the GPU (tests/gpu/layout_test.cpp).
#ifndef AMRVK_RENDER_PARAMS_H
#define AMRVK_RENDER_PARAMS_H
#include "cut_away_gpu.h"
#include "interop.h"
#include "kinds.h"

AMRVK_NAMESPACE_BEGIN

AMRVK_CONST uint kMaxLights = 8u;

// Per-frame counters (uint32 each, reset per dispatch, summed on the host in 64 bits).
AMRVK_CONST uint kCounterDensityLookups = 0u;
AMRVK_CONST uint kCounterRealCollisions = 1u;
AMRVK_CONST uint kCounterNullCollisions = 2u;
AMRVK_CONST uint kCounterTraversalSteps = 3u;      // DDA steps plus box queries, one each
AMRVK_CONST uint kCounterMajorantViolations = 4u;  // sigma > majorant (1 + 1e-6)
AMRVK_CONST uint kCounterBounceLimitHits = 5u;     // ms paths stopped at kMaxBounces
AMRVK_CONST uint kCounterNanSamples = 6u;          // NaN/Inf radiance samples (zeroed)
AMRVK_CONST uint kCounterTrackingCapHits = 7u;     // tracking stopped at the step cap or stalled in float (biased)
// Lookup slots of the subgroups: per subgroup, its size x the most lookups one invocation made.
// densityLookups / this = the SIMD lanes' share of useful lookup work (1: no divergence).
AMRVK_CONST uint kCounterLookupLaneSlots = 8u;
AMRVK_CONST uint kCounterShadowLookups = 9u;  // of densityLookups, those of shadow rays (transmittance)
AMRVK_CONST uint kCounterSubMajorantSkips = 10u;  // collisions a sub-majorant decided without a lookup
AMRVK_CONST uint kCounterCount = 11u;

// Per-path statistics (single-process passes; RenderParams::pathStats, reset per dispatch): for
// each quantity counted per path (a sample: camera ray, bounces, shadow rays), the largest count
// of one path (uint[kPathQuantities] at kPathStatsMax) and a histogram over kPathBins bins, 4 per
// octave: bin(n) = n for n < 8, else 4 (e - 1) + ((n >> (e - 2)) & 3) with e = the highest set bit
// of n (uint[kPathQuantities][kPathBins] at kPathStatsBins; scene/render_output.h turns bins into
// percentiles). Every path enters the lookup histogram; the others count only paths with a count
// above 0 (their bin 0 is the rest, filled in on the host).
AMRVK_CONST uint kPathBins = 128u;
AMRVK_CONST uint kPathLookups = 0u;  // density lookups
AMRVK_CONST uint kPathNulls = 1u;    // null collisions
AMRVK_CONST uint kPathReal = 2u;     // real collisions
AMRVK_CONST uint kPathSteps = 3u;    // traversal steps (DDA steps plus box queries)
AMRVK_CONST uint kPathQuantities = 4u;
AMRVK_CONST uint kPathStatsMax = 0u;
AMRVK_CONST uint kPathStatsBins = kPathQuantities;
AMRVK_CONST uint kPathStatsCount = kPathQuantities * (1u + kPathBins);

AMRVK_CONST uint kMaxBounces = 65536u;  // ms path length cap; paths reaching it are counted

struct LightGpu {
    vec3 posOrDir;  // point: position (local voxel); directional: unit direction *towards* the light
    uint type;      // LightType
    vec3 radiance;  // directional: radiance; point: intensity (falls off as 1/d^2, d in voxel units)
    float pad;
};
AMRVK_STATIC_ASSERT(sizeof(LightGpu) == 32);

// Camera ray through pixel (x, y) with jitter j: eye + normalize(dir00 + (x + jx) du + (y + jy) dv).
struct ViewGpu {
    vec3 eye;     // local voxel space
    uint width;   // pixels
    vec3 dir00;   // direction to the corner of pixel (0, 0) (top left)
    uint height;  // pixels
    vec3 du;      // direction step per pixel to the right
    uint seed;    // random seed of the image
    vec3 dv;      // direction step per pixel downwards
    uint pad;
};
AMRVK_STATIC_ASSERT(sizeof(ViewGpu) == 64);

struct ShadingGpu {
    vec3 ambient;          // environment radiance seen by rays that escape (after a bounce)
    float g;               // Henyey-Greenstein asymmetry in [-0.999, 0.999]
    vec3 background;       // radiance seen by primary rays that escape
    float densityScale;    // multiplies extinction
    uint lightCount;       // lights[0, lightCount) are in use
    uint maxTrackingSteps; // per tracking call; reaching it is counted (kCounterTrackingCapHits)
    float dvrStep;         // dvr: step / finest cell width at the sample
    uint dvrShading;       // dvr: 1 = gradient shading
    vec3 dvrLightDir;      // dvr: unit direction towards the shading light (local voxel)
    float dvrAmbient;      // dvr: ambient term of the shading
    float dvrOpacityStop;  // dvr: a ray ends at this opacity (0.99)
    float pad0, pad1, pad2;
    LightGpu lights[kMaxLights];
};
AMRVK_STATIC_ASSERT(sizeof(ShadingGpu) == 80 + 32 * kMaxLights);

struct SceneGpu {
    vec3 boundsHi;              // the union of leaf cells is [0, boundsHi] (local voxel)
    float invFinestCellWidth;   // 1 / (1 << finest level): extinction per voxel unit per unit alpha
    ivec3 gridDims;             // macrocells per axis (grid traversals, dense majorants, grid sampler)
    uint gridBlockShift;        // grid-dda: blocks of 2^shift macrocells per axis, crossed in one step
                                // where all their majorants are 0 (majorant_dda.glsl); 0: no blocks
    vec3 gridOrigin;            // local voxel
    uint gridBvhQueryAfter;     // grid-bvh: culled macrocells in a row stepped by the DDA before one box
                                // query skips the rest of the run (>= 1; traversal.glsl)
    vec3 gridCellSize;          // voxel units per macrocell
    float pad2;
    ivec3 denseDims;            // dense sampler: samples per axis
    int denseLevel;             // dense sampler: level of the spacing (1 << denseLevel)
    vec3 denseOrigin;           // dense sampler: sample (i, j, k) at denseOrigin + (ijk + 0.5) * denseSpacing
    float denseSpacing;         // voxel units
    uint64_t bricks;            // BrickGpu[]
    uint64_t brickValues;       // float[] in brick order (NaN = empty slot)
    uint64_t samplerNodes;      // BvhNodeGpu[] over brick domains (ext-brick) or ABR boxes (abr), sw
    uint64_t samplerPrims;      // uint[] BVH slot -> brick id or ABR id, sw
    uint64_t samplerAccel;      // TLAS over the same boxes (rq back-end), else 0
    uint64_t abrs;              // AbrGpu[]
    uint64_t abrBrickList;      // uint[]
    uint64_t gridRanges;        // ValueRangeGpu[] per macrocell
    uint64_t denseValues;       // float[] dense samples, x fastest (NaN: outside the medium), else 0
    uint64_t gridBrickLists;    // grid sampler: uint[] per-macrocell offsets, then brick ids (accel/brick_grid.h)
};
AMRVK_STATIC_ASSERT(sizeof(SceneGpu) == 176);

struct MajorantsGpu {
    uint64_t tfPositions;      // float[tfNodeCount], ascending field values
    uint64_t tfColors;         // vec4[tfNodeCount]: rgb albedo, a = alpha (extinction per finest cell width)
    uint tfNodeCount;
    uint domainCount;          // traversal boxes (grid-bvh: macrocells)
    uint domainAnyActive;      // 1 when some traversal box has majorant > 0
    uint gridBlocks;           // grid-dda: 1 when it crosses empty blocks under this TF (enough are empty)
    uint64_t gridMajorants;    // float[] max alpha per macrocell, then (gridBlockShift > 0) per block the
                               // max of its macrocells' (block_majorants.comp), blocks numbered x fastest
    uint64_t domainBoxes;      // AabbGpu[] traversal boxes (not for grid-bvh: computed from the grid)
    uint64_t domainRanges;     // ValueRangeGpu[] per traversal box (grid-bvh: = gridRanges)
    uint64_t domainMajorants;  // float[] max alpha per traversal box (grid-bvh: = gridMajorants)
    uint64_t domainNodes;      // BvhNodeGpu[] over the boxes with majorant > 0 (sw back-end)
    uint64_t domainPrims;      // uint[] BVH slot -> box id
    uint64_t domainAccel;      // TLAS over the boxes, culled ones collapsed to points (rq back-end)
    uint64_t tfAlphaTree;      // float[2 * L], L = the power of two >= tfNodeCount: max tree of node alphas
                               // (tree[L + i] = alpha_i, padding 0; tree[k] = max(tree[2k], tree[2k + 1]))
    uint64_t subRefinement;    // grid traversals with sub-majorants (scene/sub_majorants.h): uint[] per
                               // macrocell, 0xffffffff (not refined) or (byte offset / 8) << 2 | log2 n - 1
    uint64_t subMajorants;     // their sub-boxes' q (0..255), four bytes to a uint: majorant M q / 255
    uint subMajorantsOn;       // 1 when subRefinement and subMajorants hold a refinement
    uint subMajorantCheck;     // 1: a collision skipped by its sub-majorant is looked up anyway and
                               // counted as a majorant violation where sigma exceeds it (tests)
    uint64_t gridMinorants;    // --control-extinction minorant (grid traversals): float[] per macrocell, the
                               // least TF alpha over its value range less kMinorantMargin times the greatest
                               // (lib/tracking.glsl's control extinction); 0 when off
    uint64_t tfAlphaMinTree;   // with gridMinorants: tfAlphaTree's layout as a min tree (padding +inf)
};
AMRVK_STATIC_ASSERT(sizeof(MajorantsGpu) == 136);

// A minorant is the exact minimum of the TF's alpha over a range less this share of the maximum
// (at least 0), so that the rounding of evalTf's mix (a few ulps of the larger node alpha) never
// puts an extinction below it.
AMRVK_CONST float kMinorantMargin = 1e-6f;

// One pixel of the accumulation buffer (path_trace.comp adds to it; display.comp and
// PathTracePass::read() read it). Each sum is a double-float: value = hi + lo exactly, |lo| <=
// ulp(hi) / 2, about 48 significant bits from float32 arithmetic (no shaderFloat64), so the mean
// of a constant radiance stays exact to float precision at any spp. Readers combine hi + lo in
// double. The count (sumHi.w + sumLo.w) is an exact integer; sumLo.w is 0 below 2^24 samples.
struct AccumPixelGpu {
    vec4 sumHi;    // radiance summed over samples (rgb), w = sample count
    vec4 sumLo;    // its low part (rgb, w)
    vec4 sumSqHi;  // squared radiance summed over samples (rgb), w = 0
    vec4 sumSqLo;  // its low part
};
AMRVK_STATIC_ASSERT(sizeof(AccumPixelGpu) == 64);

struct RenderParams {
    ViewGpu view;
    ShadingGpu shading;
    SceneGpu scene;
    MajorantsGpu majorants;
    uint64_t accum;     // AccumPixelGpu[width * height], pixel (x, y) at y * width + x
    uint64_t counters;  // uint[kCounterCount]
    uint64_t pathStats;  // uint[kPathStatsCount]
    CutAwayGpu cut;
};

struct PushConstants {
    uint64_t params;  // RenderParams address
    uint frameIndex;  // number of the dispatch's first sample
    uint rowOffset;   // first image row of this dispatch (time-budgeted tiles: a band of rows)
    uint rowEnd;      // one past its last row (the image height for a whole sample)
    uint samples;     // samples each invocation takes, numbered frameIndex.. (>= 1)
    // Rows rowOffset, rowOffset + rowStride, ... below rowEnd (0 or 1: every row). A probe of the
    // pace spread over the whole image (core/gpu_deadline.h) takes every rowStride-th row.
    uint rowStride;
    uint unused;      // keeps the size a multiple of 8 in C++ and GLSL alike
};
AMRVK_STATIC_ASSERT(sizeof(PushConstants) == 32);

// majorants.comp: majorants[i] = max TF alpha over ranges[i] for i < count. domain_aabbs.comp:
// aabbs[i] = box i, or the point lo when majorants[i] == 0 (ray-query culling).
struct StructurePush {
    uint64_t params;     // RenderParams address (TF, grid, domain boxes)
    uint64_t source;     // ValueRangeGpu[] (majorants.comp) or float[] majorants (domain_aabbs.comp)
    uint64_t target;     // float[] majorants or AabbGpu[]
    uint count;
    uint traversal;      // domain_aabbs.comp: TraversalKind (grid-bvh computes its boxes)
    uint64_t minorants;  // majorants.comp: 0, or float[] of the minorants of the same ranges
};
AMRVK_STATIC_ASSERT(sizeof(StructurePush) == 40);

#ifdef __cplusplus
AMRVK_STATIC_ASSERT(offsetof(LightGpu, posOrDir) == 0);
AMRVK_STATIC_ASSERT(offsetof(LightGpu, type) == 12);
AMRVK_STATIC_ASSERT(offsetof(LightGpu, radiance) == 16);
AMRVK_STATIC_ASSERT(offsetof(ViewGpu, eye) == 0);
AMRVK_STATIC_ASSERT(offsetof(ViewGpu, width) == 12);
AMRVK_STATIC_ASSERT(offsetof(ViewGpu, dir00) == 16);
AMRVK_STATIC_ASSERT(offsetof(ViewGpu, height) == 28);
AMRVK_STATIC_ASSERT(offsetof(ViewGpu, du) == 32);
AMRVK_STATIC_ASSERT(offsetof(ViewGpu, seed) == 44);
AMRVK_STATIC_ASSERT(offsetof(ViewGpu, dv) == 48);
AMRVK_STATIC_ASSERT(offsetof(ShadingGpu, ambient) == 0);
AMRVK_STATIC_ASSERT(offsetof(ShadingGpu, g) == 12);
AMRVK_STATIC_ASSERT(offsetof(ShadingGpu, background) == 16);
AMRVK_STATIC_ASSERT(offsetof(ShadingGpu, densityScale) == 28);
AMRVK_STATIC_ASSERT(offsetof(ShadingGpu, lightCount) == 32);
AMRVK_STATIC_ASSERT(offsetof(ShadingGpu, maxTrackingSteps) == 36);
AMRVK_STATIC_ASSERT(offsetof(ShadingGpu, dvrStep) == 40);
AMRVK_STATIC_ASSERT(offsetof(ShadingGpu, dvrShading) == 44);
AMRVK_STATIC_ASSERT(offsetof(ShadingGpu, dvrLightDir) == 48);
AMRVK_STATIC_ASSERT(offsetof(ShadingGpu, dvrAmbient) == 60);
AMRVK_STATIC_ASSERT(offsetof(ShadingGpu, dvrOpacityStop) == 64);
AMRVK_STATIC_ASSERT(offsetof(ShadingGpu, lights) == 80);
AMRVK_STATIC_ASSERT(offsetof(SceneGpu, boundsHi) == 0);
AMRVK_STATIC_ASSERT(offsetof(SceneGpu, invFinestCellWidth) == 12);
AMRVK_STATIC_ASSERT(offsetof(SceneGpu, gridDims) == 16);
AMRVK_STATIC_ASSERT(offsetof(SceneGpu, gridBlockShift) == 28);
AMRVK_STATIC_ASSERT(offsetof(SceneGpu, gridOrigin) == 32);
AMRVK_STATIC_ASSERT(offsetof(SceneGpu, gridBvhQueryAfter) == 44);
AMRVK_STATIC_ASSERT(offsetof(SceneGpu, gridCellSize) == 48);
AMRVK_STATIC_ASSERT(offsetof(SceneGpu, denseDims) == 64);
AMRVK_STATIC_ASSERT(offsetof(SceneGpu, denseLevel) == 76);
AMRVK_STATIC_ASSERT(offsetof(SceneGpu, denseOrigin) == 80);
AMRVK_STATIC_ASSERT(offsetof(SceneGpu, denseSpacing) == 92);
AMRVK_STATIC_ASSERT(offsetof(SceneGpu, bricks) == 96);
AMRVK_STATIC_ASSERT(offsetof(SceneGpu, brickValues) == 104);
AMRVK_STATIC_ASSERT(offsetof(SceneGpu, samplerNodes) == 112);
AMRVK_STATIC_ASSERT(offsetof(SceneGpu, samplerPrims) == 120);
AMRVK_STATIC_ASSERT(offsetof(SceneGpu, samplerAccel) == 128);
AMRVK_STATIC_ASSERT(offsetof(SceneGpu, abrs) == 136);
AMRVK_STATIC_ASSERT(offsetof(SceneGpu, abrBrickList) == 144);
AMRVK_STATIC_ASSERT(offsetof(SceneGpu, gridRanges) == 152);
AMRVK_STATIC_ASSERT(offsetof(SceneGpu, denseValues) == 160);
AMRVK_STATIC_ASSERT(offsetof(SceneGpu, gridBrickLists) == 168);
AMRVK_STATIC_ASSERT(offsetof(MajorantsGpu, tfPositions) == 0);
AMRVK_STATIC_ASSERT(offsetof(MajorantsGpu, tfColors) == 8);
AMRVK_STATIC_ASSERT(offsetof(MajorantsGpu, tfNodeCount) == 16);
AMRVK_STATIC_ASSERT(offsetof(MajorantsGpu, domainCount) == 20);
AMRVK_STATIC_ASSERT(offsetof(MajorantsGpu, domainAnyActive) == 24);
AMRVK_STATIC_ASSERT(offsetof(MajorantsGpu, gridBlocks) == 28);
AMRVK_STATIC_ASSERT(offsetof(MajorantsGpu, gridMajorants) == 32);
AMRVK_STATIC_ASSERT(offsetof(MajorantsGpu, domainBoxes) == 40);
AMRVK_STATIC_ASSERT(offsetof(MajorantsGpu, domainRanges) == 48);
AMRVK_STATIC_ASSERT(offsetof(MajorantsGpu, domainMajorants) == 56);
AMRVK_STATIC_ASSERT(offsetof(MajorantsGpu, domainNodes) == 64);
AMRVK_STATIC_ASSERT(offsetof(MajorantsGpu, domainPrims) == 72);
AMRVK_STATIC_ASSERT(offsetof(MajorantsGpu, domainAccel) == 80);
AMRVK_STATIC_ASSERT(offsetof(MajorantsGpu, tfAlphaTree) == 88);
AMRVK_STATIC_ASSERT(offsetof(MajorantsGpu, subRefinement) == 96);
AMRVK_STATIC_ASSERT(offsetof(MajorantsGpu, subMajorants) == 104);
AMRVK_STATIC_ASSERT(offsetof(MajorantsGpu, subMajorantsOn) == 112);
AMRVK_STATIC_ASSERT(offsetof(MajorantsGpu, subMajorantCheck) == 116);
AMRVK_STATIC_ASSERT(offsetof(MajorantsGpu, gridMinorants) == 120);
AMRVK_STATIC_ASSERT(offsetof(MajorantsGpu, tfAlphaMinTree) == 128);
AMRVK_STATIC_ASSERT(offsetof(StructurePush, minorants) == 32);
AMRVK_STATIC_ASSERT(offsetof(AccumPixelGpu, sumHi) == 0);
AMRVK_STATIC_ASSERT(offsetof(AccumPixelGpu, sumLo) == 16);
AMRVK_STATIC_ASSERT(offsetof(AccumPixelGpu, sumSqHi) == 32);
AMRVK_STATIC_ASSERT(offsetof(AccumPixelGpu, sumSqLo) == 48);
AMRVK_STATIC_ASSERT(offsetof(RenderParams, view) == 0);
AMRVK_STATIC_ASSERT(offsetof(RenderParams, shading) == 64);
AMRVK_STATIC_ASSERT(offsetof(RenderParams, scene) == 400);
AMRVK_STATIC_ASSERT(offsetof(RenderParams, majorants) == 576);
AMRVK_STATIC_ASSERT(offsetof(RenderParams, accum) == 712);
AMRVK_STATIC_ASSERT(offsetof(RenderParams, counters) == 720);
AMRVK_STATIC_ASSERT(offsetof(RenderParams, pathStats) == 728);
AMRVK_STATIC_ASSERT(offsetof(RenderParams, cut) == 736);
AMRVK_STATIC_ASSERT(sizeof(RenderParams) == 736 + sizeof(CutAwayGpu));
AMRVK_STATIC_ASSERT(offsetof(PushConstants, params) == 0);
AMRVK_STATIC_ASSERT(offsetof(PushConstants, frameIndex) == 8);
AMRVK_STATIC_ASSERT(offsetof(PushConstants, rowOffset) == 12);
AMRVK_STATIC_ASSERT(offsetof(PushConstants, rowEnd) == 16);
AMRVK_STATIC_ASSERT(offsetof(PushConstants, samples) == 20);
AMRVK_STATIC_ASSERT(offsetof(PushConstants, rowStride) == 24);
AMRVK_STATIC_ASSERT(offsetof(StructurePush, params) == 0);
AMRVK_STATIC_ASSERT(offsetof(StructurePush, source) == 8);
AMRVK_STATIC_ASSERT(offsetof(StructurePush, target) == 16);
AMRVK_STATIC_ASSERT(offsetof(StructurePush, count) == 24);
AMRVK_STATIC_ASSERT(offsetof(StructurePush, traversal) == 28);
#endif

AMRVK_NAMESPACE_END
#endif
