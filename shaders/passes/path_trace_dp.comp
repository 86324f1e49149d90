#version 460
// Data-parallel path tracing (one stage per dispatch, pc.stage; mpi/data_parallel.cpp runs them
// and reduces between them over MPI): the estimators of lib/estimator.glsl (ae, ss, ms), which
// path_trace.comp runs too, with each tracking call cut to this rank's box of space. Unbiased
// across ranks because the boxes are disjoint and cover the domain: the first real collision
// along a ray is the nearest of the ranks' independent first collisions in their boxes (the
// free-flight survival probability is the product of the boxes' transmittances), and a shadow
// ray's transmittance is the product of the ranks' independent ratio-tracking estimates. The rank
// that owns a collision supplies its TF colour; everything else (light choice, phase sampling,
// roulette) is drawn from the path's own random state, the same on every rank, so every rank
// holds the same paths. Specialization as path_trace.comp.
#extension GL_KHR_shader_subgroup_arithmetic : require
#ifdef AMRVK_RAY_QUERY
#extension GL_EXT_ray_query : require
#endif
#include "lib/common.glsl"
#include "shared/data_parallel_gpu.h"
layout(push_constant, scalar) uniform Push { DataParallelPush pc; };
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
#include "lib/ray_box.glsl"
#include "lib/double_float.glsl"

layout(local_size_x = 64) in;
layout(constant_id = 0) const uint kMode = kModeMs;
layout(constant_id = 1) const uint kSampler = kSamplerExtBrick;
layout(constant_id = 2) const uint kTraversal = kTraversalGridDda;
layout(constant_id = 3) const uint kBackend = kBackendSw;
#include "lib/estimator.glsl"

StructureConfig cfg() { return StructureConfig(kSampler, kTraversal, kBackend); }

layout(buffer_reference, scalar) buffer PathRW { PathStateGpu v[]; };
layout(buffer_reference, scalar) buffer HitRW { DataParallelHitGpu v[]; };

// Random numbers of this rank's tracking for path i: independent of the other ranks' and of the
// path's shared state.
uint localRng(uint i, PathStateGpu p, uint kind) {
    return seedRng(i, pcgHash(pc.sampleIndex) ^ (p.bounce * 2u + kind), P.view.seed ^ pc.rankSeed);
}

// [t0, t1] of o + t d inside this rank's box within [0, tMax]; false when empty.
bool ownedInterval(vec3 o, vec3 d, float tMax, out float t0, out float t1) {
    t0 = 0.0;
    t1 = tMax;
    return clipRay(pc.ownedLo, pc.ownedHi, o, d, t0, t1) && t0 < t1;
}

void main() {
    gParams = ParamsRef(pc.params);
    uint i = gl_GlobalInvocationID.x;
    Counters c = newCounters();
    uint live = 0u, bounceLimit = 0u, nanSamples = 0u;
    if (i < pc.count) {
        PathRW paths = PathRW(pc.paths);
        PathStateGpu p = paths.v[i];
        if (pc.stage == kDpStageGenerate) {
            paths.v[i] = startPath(uvec2(i % P.view.width, i / P.view.width), i, pc.sampleIndex);
        } else if (pc.stage == kDpStageTrack) {
            DataParallelHitGpu h = DataParallelHitGpu(-1.0, vec3(0.0));
            if ((p.flags & kPathLive) != 0u) {
                h.t = kInf;
                float t0, t1;
                if (ownedInterval(p.o, p.d, kInf, t0, t1)) {
                    uint rng = localRng(i, p, 0u);
                    float tHit;
                    vec4 tf;
                    if (deltaTrack(p.o + p.d * t0, p.d, t1 - t0, cfg(), rng, c, tHit, tf)) {
                        h.t = t0 + tHit;
                        h.color = tf.rgb;
                    }
                }
            }
            HitRW(pc.hits).v[i] = h;
        } else if (pc.stage == kDpStageShade) {
            if ((p.flags & kPathLive) != 0u) {
                DataParallelHitGpu h = HitRW(pc.hits).v[i];
                if (shadeCollision(p, h.t < kInf, h.t, h.color)) bounceLimit = 1u;
                scatterPath(p);
                paths.v[i] = p;
            }
            live = (p.flags & (kPathLive | kPathShadow)) != 0u ? 1u : 0u;
        } else if (pc.stage == kDpStageShadow) {
            float transmittance = -1.0;
            if ((p.flags & kPathShadow) != 0u) {
                transmittance = 1.0;
                float t0, t1;
                if (ownedInterval(p.o, p.shadowDir, p.shadowDist, t0, t1)) {
                    uint rng = localRng(i, p, 1u);
                    transmittance = shadowTransmittance(p.o + p.shadowDir * t0, p.shadowDir, t1 - t0, cfg(), rng, c);
                }
            }
            FloatRW(pc.shadow).v[i] = transmittance;
        } else if (pc.stage == kDpStageResolve) {
            if ((p.flags & kPathShadow) != 0u) {
                resolveShadow(p, FloatRW(pc.shadow).v[i]);
                paths.v[i] = p;
            }
        } else if (pc.stage == kDpStageAccumulate) {
            vec3 L = p.radiance;
            if (any(isnan(L)) || any(isinf(L))) {
                L = vec3(0.0);
                nanSamples = 1u;
            }
            AccumRW acc = AccumRW(P.accum);
            AccumPixelGpu a = acc.v[p.pixel];
            addDoubleFloat(a.sumHi, a.sumLo, vec4(L, 1.0));
            addDoubleFloat(a.sumSqHi, a.sumSqLo, vec4(L * L, 0.0));
            acc.v[p.pixel] = a;
        }
    }
    UintRW counters = UintRW(pc.counters);
    uint v0 = subgroupAdd(c.lookups), v1 = subgroupAdd(c.real), v2 = subgroupAdd(c.nulls);
    uint v3 = subgroupAdd(c.steps), v4 = subgroupAdd(c.violations), v5 = subgroupAdd(nanSamples);
    uint v6 = subgroupAdd(c.capped), v7 = subgroupAdd(bounceLimit), v8 = subgroupAdd(live);
    uint v9 = pc.stage == kDpStageShadow ? v0 : 0u;  // every lookup of the shadow stage is a shadow ray's
    uint v10 = subgroupAdd(c.thinned);
    if (subgroupElect()) {
        atomicAdd(counters.v[kCounterDensityLookups], v0);
        atomicAdd(counters.v[kCounterRealCollisions], v1);
        atomicAdd(counters.v[kCounterNullCollisions], v2);
        atomicAdd(counters.v[kCounterTraversalSteps], v3);
        atomicAdd(counters.v[kCounterMajorantViolations], v4);
        atomicAdd(counters.v[kCounterNanSamples], v5);
        atomicAdd(counters.v[kCounterTrackingCapHits], v6);
        atomicAdd(counters.v[kCounterBounceLimitHits], v7);
        atomicAdd(counters.v[kCounterShadowLookups], v9);
        atomicAdd(counters.v[kCounterSubMajorantSkips], v10);
        atomicAdd(counters.v[kCounterCount], v8);
    }
}
