#version 460
// pc.samples samples per pixel per dispatch (numbered pc.frameIndex.., each seeded by its number,
// so the image does not depend on how samples are grouped): camera ray -> the estimator of the
// chosen mode (lib/estimator.glsl, shared with path_trace_dp.comp; dvr: lib/ray_march.glsl) ->
// radiance and its square summed in registers, added to the accumulation once. Both
// sums are double-floats (lib/double_float.glsl; layout: AccumPixelGpu), so they do not drift.
// Specialization: kMode (ae | ss | ms | dvr), kSampler (ext-brick | abr | dense | grid),
// kTraversal (grid-dda | grid-bvh | abr | brick | ext-brick | kdtree), kBackend (sw | rq),
// kPathRegeneration (a workgroup's samples taken from a pool, below).
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
#include "lib/sub_majorants.glsl"
#include "lib/tracking.glsl"
#ifdef AMRVK_UBRM
#include "lib/unbiased_march.glsl"  // --transmittance ubrm (the _ubrm variants)
#endif
#include "lib/phase.glsl"
#include "lib/ray_march.glsl"
#include "lib/double_float.glsl"
#include "shared/path_state_gpu.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const uint kMode = kModeMs;            // Mode
layout(constant_id = 1) const uint kSampler = kSamplerExtBrick;  // SamplerKind
layout(constant_id = 2) const uint kTraversal = kTraversalGridDda;  // TraversalKind
layout(constant_id = 3) const uint kBackend = kBackendSw;      // Backend
layout(constant_id = 4) const bool kPathRegeneration = false;  // gpu::ContextOptions::pathRegeneration
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
        if ((p.flags & kPathShadow) != 0u) {
            uint lookups0 = c.lookups;
            resolveShadow(p, shadowTransmittance(p.o, p.shadowDir, p.shadowDist, cfg(), p.rng, c));
            c.shadowLookups += c.lookups - lookups0;
        }
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

// Counts one path's quantity q (kPath*): its histogram bin and its largest count so far. Every
// path enters the lookup histogram (the paths finished so far: PathTracePass's progress); a count
// of 0 of the other quantities is left to the host (PathStats::add), sparing most paths' atomics.
void recordPath(uint q, uint n, inout uint largest) {
    if (n > 0u || q == kPathLookups) atomicAdd(UintRW(P.pathStats).v[kPathStatsBins + q * kPathBins + pathBin(n)], 1u);
    largest = max(largest, n);
}

// The pixel of local invocation `l` (x fastest over the 8 x 8 workgroup), as gl_GlobalInvocationID
// places it: rows rowOffset, rowOffset + rowStride, ... below rowEnd.
uvec2 pixelOfLocal(uint l) {
    uvec2 g = gl_WorkGroupID.xy * uvec2(8u) + uvec2(l % 8u, l / 8u);
    return uvec2(g.x, pc.rowOffset + g.y * max(pc.rowStride, 1u));
}
bool inImageOf(uvec2 pix) { return pix.x < P.view.width && pix.y < min(P.view.height, pc.rowEnd); }

// Traces sample `sampleIndex` of pixel `pix` and counts its path: its radiance (NaN or Inf
// counted and zeroed).
vec3 tracePixelSample(uvec2 pix, uint sampleIndex, inout Counters c, inout uint pathMax[kPathQuantities],
                      inout uint nanSamples) {
    PathStateGpu path = startPath(pix, pix.y * P.view.width + pix.x, sampleIndex);
    Counters before = c;
    vec3 L = radiance(path, c);
    recordPath(kPathLookups, c.lookups - before.lookups, pathMax[kPathLookups]);
    recordPath(kPathNulls, c.nulls - before.nulls, pathMax[kPathNulls]);
    recordPath(kPathReal, c.real - before.real, pathMax[kPathReal]);
    recordPath(kPathSteps, c.steps - before.steps, pathMax[kPathSteps]);
    if (any(isnan(L)) || any(isinf(L))) {
        L = vec3(0.0);
        ++nanSamples;
    }
    return L;
}

// Path regeneration within the workgroup (kPathRegeneration): its 64 pixels' samples are a pool of
// items (sample k of local pixel l, pixels fastest), taken one at a time by whichever invocation
// is free, so a lane whose path ended takes the next sample instead of idling beside a long one.
// Each item's radiance waits in shared memory; then every invocation adds its own pixel's samples
// in sample order, exactly the sums of tracing them one after the other. Pools of kPoolSamples
// samples a pixel at a time (8 x 64 radiances: 6-8 KiB of shared memory).
const uint kPoolPixels = 64u;
const uint kPoolSamples = 8u;
shared uint sNextItem;
shared vec3 sRadiance[kPoolSamples * kPoolPixels];

void main() {
    gParams = ParamsRef(pc.params);
    uint pathMax[kPathQuantities] = uint[kPathQuantities](0u, 0u, 0u, 0u);
    uint local = gl_LocalInvocationIndex;
    uvec2 pix = pixelOfLocal(local);
    bool inImage = inImageOf(pix);
    Counters c = newCounters();
    uint nanSamples = 0u;
    vec4 sumHi = vec4(0.0), sumLo = vec4(0.0), sumSqHi = vec4(0.0), sumSqLo = vec4(0.0);
    if (!kPathRegeneration) {
        if (inImage)
            for (uint k = 0u; k < pc.samples; ++k) {
                vec3 L = tracePixelSample(pix, pc.frameIndex + k, c, pathMax, nanSamples);
                addDoubleFloat(sumHi, sumLo, vec4(L, 1.0));
                addDoubleFloat(sumSqHi, sumSqLo, vec4(L * L, 0.0));
            }
    } else {
        for (uint first = 0u; first < pc.samples; first += kPoolSamples) {
            uint items = min(kPoolSamples, pc.samples - first) * kPoolPixels;
            if (local == 0u) sNextItem = 0u;
            memoryBarrierShared();
            barrier();
            for (;;) {
                uint item = atomicAdd(sNextItem, 1u);
                if (item >= items) break;
                uvec2 ipix = pixelOfLocal(item % kPoolPixels);
                if (inImageOf(ipix))
                    sRadiance[item] = tracePixelSample(ipix, pc.frameIndex + first + item / kPoolPixels, c, pathMax, nanSamples);
            }
            memoryBarrierShared();
            barrier();
            if (inImage)
                for (uint k = 0u; k * kPoolPixels < items; ++k) {
                    vec3 L = sRadiance[k * kPoolPixels + local];
                    addDoubleFloat(sumHi, sumLo, vec4(L, 1.0));
                    addDoubleFloat(sumSqHi, sumSqLo, vec4(L * L, 0.0));
                }
            barrier();  // every pixel has its samples before the next pool overwrites them
        }
    }
    if (inImage) {
        uint pixel = pix.y * P.view.width + pix.x;
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
    uint v8 = subgroupAdd(c.shadowLookups), v9 = subgroupAdd(c.thinned);
    uint m[kPathQuantities];
    for (uint q = 0u; q < kPathQuantities; ++q) m[q] = subgroupMax(pathMax[q]);
    if (subgroupElect()) {
        atomicAdd(counters.v[kCounterDensityLookups], v0);
        atomicAdd(counters.v[kCounterRealCollisions], v1);
        atomicAdd(counters.v[kCounterNullCollisions], v2);
        atomicAdd(counters.v[kCounterTraversalSteps], v3);
        atomicAdd(counters.v[kCounterMajorantViolations], v4);
        atomicAdd(counters.v[kCounterNanSamples], v5);
        atomicAdd(counters.v[kCounterTrackingCapHits], v6);
        atomicAdd(counters.v[kCounterLookupLaneSlots], v7);
        atomicAdd(counters.v[kCounterShadowLookups], v8);
        atomicAdd(counters.v[kCounterSubMajorantSkips], v9);
        UintRW pathStats = UintRW(P.pathStats);
        for (uint q = 0u; q < kPathQuantities; ++q) atomicMax(pathStats.v[kPathStatsMax + q], m[q]);
    }
}
