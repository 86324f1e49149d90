#version 460
// pc.samples samples per pixel per dispatch (numbered pc.frameIndex.., each seeded by its number,
// so the image does not depend on how samples are grouped): camera ray -> the estimator of the
// chosen mode (lib/estimator.glsl, shared with path_trace_dp.comp; dvr: lib/ray_march.glsl) ->
// radiance and its square summed in registers, added to the accumulation once. Both
// sums are double-floats (lib/double_float.glsl; layout: AccumPixelGpu), so they do not drift.
// Specialization: kMode (ae | ss | ms | dvr), kSampler (ext-brick | abr | dense | grid),
// kTraversal (grid-dda | grid-bvh | abr | brick | ext-brick | kdtree), kBackend (sw | rq).
// Built twice: path_trace (software BVHs only, runs everywhere) and path_trace_rq
// (-DAMRVK_RAY_QUERY: also the VK_KHR_ray_query back-end; needs the rayQuery feature).
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
#ifdef AMRVK_RAY_QUERY
#extension GL_EXT_ray_query : require
#endif
#include "lib/common.glsl"
layout(push_constant, scalar) uniform Push { PushConstants pc; };
#include "lib/rng.glsl"
#include "lib/tf.glsl"
#include "lib/amr_sample.glsl"
#include "lib/majorant_dda.glsl"
#include "lib/domain_traversal.glsl"
#include "lib/traversal.glsl"
#include "lib/tracking.glsl"
#include "lib/phase.glsl"
#include "lib/ray_march.glsl"
#include "lib/double_float.glsl"
#include "shared/path_state_gpu.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const uint kMode = kModeMs;            // Mode
layout(constant_id = 1) const uint kSampler = kSamplerExtBrick;  // SamplerKind
layout(constant_id = 2) const uint kTraversal = kTraversalGridDda;  // TraversalKind
layout(constant_id = 3) const uint kBackend = kBackendSw;      // Backend
#include "lib/estimator.glsl"

StructureConfig cfg() { return StructureConfig(kSampler, kTraversal, kBackend); }

// One sample of the chosen mode along the path's camera ray: the estimator's events
// (lib/estimator.glsl) in one loop, tracking and shadow rays drawing from the path's own random
// state.
vec3 radiance(inout PathStateGpu p, inout Counters c) {
    if (kMode == kModeDvr) return rayMarch(p.o, p.d, cfg(), p.rng, c);
    while ((p.flags & kPathLive) != 0u) {
        float tHit;
        vec4 tf;
        bool hit = deltaTrack(p.o, p.d, kInf, cfg(), p.rng, c, tHit, tf);
        if (shadeCollision(p, hit, tHit, tf.rgb)) atomicAdd(UintRW(P.counters).v[kCounterBounceLimitHits], 1u);
        if ((p.flags & kPathShadow) != 0u)
            resolveShadow(p, ratioTrack(p.o, p.shadowDir, p.shadowDist, cfg(), p.rng, c));
        scatterPath(p);
    }
    return p.radiance;
}

// Histogram bin of a per-path count (shared/render_params.h, kPathBins).
uint pathBin(uint n) {
    if (n < 8u) return n;
    int e = findMSB(n);
    return min(4u * uint(e - 1) + ((n >> uint(e - 2)) & 3u), kPathBins - 1u);
}

void main() {
    gParams = ParamsRef(pc.params);
    UintRW pathStats = UintRW(P.pathStats);
    uint pathMaxLookups = 0u, pathMaxNulls = 0u;
    uvec2 pix = uvec2(gl_GlobalInvocationID.x, pc.rowOffset + gl_GlobalInvocationID.y * max(pc.rowStride, 1u));
    bool inImage = pix.x < P.view.width && pix.y < min(P.view.height, pc.rowEnd);
    Counters c = newCounters();
    uint nanSamples = 0u;
    if (inImage) {
        uint pixel = pix.y * P.view.width + pix.x;
        vec4 sumHi = vec4(0.0), sumLo = vec4(0.0), sumSqHi = vec4(0.0), sumSqLo = vec4(0.0);
        for (uint k = 0u; k < pc.samples; ++k) {
            PathStateGpu path = startPath(pix, pixel, pc.frameIndex + k);
            uint lookups0 = c.lookups, nulls0 = c.nulls;
            vec3 L = radiance(path, c);
            uint pathLookups = c.lookups - lookups0, pathNulls = c.nulls - nulls0;
            atomicAdd(pathStats.v[kPathStatsLookupBins + pathBin(pathLookups)], 1u);
            atomicAdd(pathStats.v[kPathStatsNullBins + pathBin(pathNulls)], 1u);
            pathMaxLookups = max(pathMaxLookups, pathLookups);
            pathMaxNulls = max(pathMaxNulls, pathNulls);
            if (any(isnan(L)) || any(isinf(L))) {
                L = vec3(0.0);
                ++nanSamples;
            }
            addDoubleFloat(sumHi, sumLo, vec4(L, 1.0));
            addDoubleFloat(sumSqHi, sumSqLo, vec4(L * L, 0.0));
        }
        AccumRW acc = AccumRW(P.accum);
        AccumPixelGpu a = acc.v[pixel];
        addDoubleFloat(a.sumHi, a.sumLo, sumHi, sumLo);
        addDoubleFloat(a.sumSqHi, a.sumSqLo, sumSqHi, sumSqLo);
        acc.v[pixel] = a;
    }
    UintRW counters = UintRW(P.counters);
    uint v0 = subgroupAdd(c.lookups), v1 = subgroupAdd(c.real), v2 = subgroupAdd(c.nulls);
    uint v3 = subgroupAdd(c.steps), v4 = subgroupAdd(c.violations), v5 = subgroupAdd(nanSamples);
    uint v6 = subgroupAdd(c.capped);
    uint v7 = subgroupMax(c.lookups) * gl_SubgroupSize;
    uint m0 = subgroupMax(pathMaxLookups), m1 = subgroupMax(pathMaxNulls);
    if (subgroupElect()) {
        atomicAdd(counters.v[kCounterDensityLookups], v0);
        atomicAdd(counters.v[kCounterRealCollisions], v1);
        atomicAdd(counters.v[kCounterNullCollisions], v2);
        atomicAdd(counters.v[kCounterTraversalSteps], v3);
        atomicAdd(counters.v[kCounterMajorantViolations], v4);
        atomicAdd(counters.v[kCounterNanSamples], v5);
        atomicAdd(counters.v[kCounterTrackingCapHits], v6);
        atomicAdd(counters.v[kCounterLookupLaneSlots], v7);
        atomicMax(pathStats.v[kPathStatsMaxLookups], m0);
        atomicMax(pathStats.v[kPathStatsMaxNulls], m1);
    }
}
