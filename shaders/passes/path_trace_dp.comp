#version 460
// Data-parallel path tracing (one stage per dispatch, pc.stage; mpi/data_parallel.cpp runs them
// and reduces between them over MPI): the estimators of path_trace.comp (ae, ss, ms) with each
// tracking call cut to this rank's box of space. Unbiased across ranks because the boxes are
// disjoint and cover the domain: the first real collision along a ray is the nearest of the
// ranks' independent first collisions in their boxes (the free-flight survival probability is the
// product of the boxes' transmittances), and a shadow ray's transmittance is the product of the
// ranks' independent ratio-tracking estimates. The rank that owns a collision supplies its TF
// colour; everything else (light choice, phase sampling, roulette) is drawn from the path's
// shared random state, so every rank holds the same paths. Specialization as path_trace.comp.
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
#include "lib/tracking.glsl"
#include "lib/phase.glsl"
#include "lib/ray_box.glsl"
#include "lib/double_float.glsl"

layout(local_size_x = 64) in;
layout(constant_id = 0) const uint kMode = kModeMs;
layout(constant_id = 1) const uint kSampler = kSamplerExtBrick;
layout(constant_id = 2) const uint kTraversal = kTraversalGridDda;
layout(constant_id = 3) const uint kBackend = kBackendSw;

StructureConfig cfg() { return StructureConfig(kSampler, kTraversal, kBackend); }

layout(buffer_reference, scalar) buffer PathRW { DataParallelPathGpu v[]; };
layout(buffer_reference, scalar) buffer HitRW { DataParallelHitGpu v[]; };

// Random numbers of this rank's tracking for path i: independent of the other ranks' and of the
// path's shared state.
uint localRng(uint i, DataParallelPathGpu p, uint kind) {
    return seedRng(i, pcgHash(pc.sampleIndex) ^ (p.bounce * 2u + kind), P.view.seed ^ pc.rankSeed);
}

// [t0, t1] of o + t d inside this rank's box within [0, tMax]; false when empty.
bool ownedInterval(vec3 o, vec3 d, float tMax, out float t0, out float t1) {
    t0 = 0.0;
    t1 = tMax;
    return clipRay(pc.ownedLo, pc.ownedHi, o, d, t0, t1) && t0 < t1;
}

// Sets up next-event estimation from p.o (ss and ms): one light (or the ambient environment)
// chosen uniformly among n, its contribution `weight` x phase x radiance waiting for the shadow
// transmittance.
void setUpShadow(inout DataParallelPathGpu p, vec3 weight, uint n, bool ambientCounts) {
    uint k = min(uint(rand(p.rng) * float(n)), n - 1u);
    float g = P.shading.g;
    uint lights = P.shading.lightCount;
    vec3 contribution;
    if (ambientCounts && k == lights) {
        p.shadowDir = sampleHenyeyGreenstein(p.d, g, rand(p.rng), rand(p.rng));  // phase / pdf = 1
        p.shadowDist = kInf;
        contribution = P.shading.ambient;
    } else {
        LightGpu L = P.shading.lights[k];
        vec3 Le = L.radiance;
        if (L.type == kLightPoint) {
            vec3 to = L.posOrDir - p.o;
            float dist = length(to);
            if (!(dist > 0.0)) return;
            p.shadowDir = to / dist;
            p.shadowDist = dist;
            Le /= dist * dist;
        } else {
            p.shadowDir = normalize(L.posOrDir);
            p.shadowDist = kInf;
        }
        contribution = Le * henyeyGreenstein(dot(p.d, p.shadowDir), g);
    }
    p.pending = weight * float(n) * contribution;
    p.flags |= kDpPathShadow;
}

void main() {
    gParams = ParamsRef(pc.params);
    uint i = gl_GlobalInvocationID.x;
    Counters c = newCounters();
    uint live = 0u, bounceLimit = 0u, nanSamples = 0u;
    if (i < pc.count) {
        PathRW paths = PathRW(pc.paths);
        DataParallelPathGpu p = paths.v[i];
        if (pc.stage == kDpStageGenerate) {
            uint pixel = i;
            uvec2 pix = uvec2(pixel % P.view.width, pixel / P.view.width);
            p.rng = seedRng(pixel, pc.sampleIndex, P.view.seed);
            vec2 jitter = vec2(rand(p.rng), rand(p.rng));
            p.d = normalize(P.view.dir00 + (float(pix.x) + jitter.x) * P.view.du + (float(pix.y) + jitter.y) * P.view.dv);
            p.o = P.view.eye;
            p.bounce = 0u;
            p.throughput = vec3(1.0);
            p.flags = kDpPathLive;
            p.radiance = vec3(0.0);
            p.pixel = pixel;
            p.pending = vec3(0.0);
            paths.v[i] = p;
        } else if (pc.stage == kDpStageTrack) {
            DataParallelHitGpu h = DataParallelHitGpu(-1.0, vec3(0.0));
            if ((p.flags & kDpPathLive) != 0u) {
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
            if ((p.flags & kDpPathLive) != 0u) {
                DataParallelHitGpu h = HitRW(pc.hits).v[i];
                bool hit = h.t < kInf;
                p.flags &= ~kDpPathLive;
                if (kMode == kModeAe) {
                    p.radiance = hit ? h.color : P.shading.background;
                } else if (!hit) {
                    p.radiance += p.throughput * (p.bounce == 0u ? P.shading.background : P.shading.ambient);
                } else if (kMode == kModeSs) {
                    p.o += p.d * h.t;
                    bool ambientOn = any(greaterThan(P.shading.ambient, vec3(0.0)));
                    uint n = P.shading.lightCount + (ambientOn ? 1u : 0u);
                    if (n > 0u) setUpShadow(p, h.color, n, ambientOn);
                } else if (p.bounce + 1u >= kMaxBounces) {
                    bounceLimit = 1u;
                } else {  // ms: as path_trace.comp's loop body
                    p.throughput *= h.color;
                    p.o += p.d * h.t;
                    uint lights = P.shading.lightCount;
                    if (lights > 0u) setUpShadow(p, p.throughput, lights, false);
                    float q = max(p.throughput.r, max(p.throughput.g, p.throughput.b));
                    bool survives = q > 0.0;
                    if (survives && q < 0.25) {
                        float survive = q / 0.25;
                        survives = rand(p.rng) < survive;
                        if (survives) p.throughput /= survive;
                    }
                    if (survives) {
                        p.d = sampleHenyeyGreenstein(p.d, P.shading.g, rand(p.rng), rand(p.rng));
                        p.flags |= kDpPathLive;
                    }
                    ++p.bounce;
                }
                paths.v[i] = p;
            }
            live = (p.flags & (kDpPathLive | kDpPathShadow)) != 0u ? 1u : 0u;
        } else if (pc.stage == kDpStageShadow) {
            float transmittance = -1.0;
            if ((p.flags & kDpPathShadow) != 0u) {
                transmittance = 1.0;
                float t0, t1;
                if (ownedInterval(p.o, p.shadowDir, p.shadowDist, t0, t1)) {
                    uint rng = localRng(i, p, 1u);
                    transmittance = ratioTrack(p.o + p.shadowDir * t0, p.shadowDir, t1 - t0, cfg(), rng, c);
                }
            }
            FloatRW(pc.shadow).v[i] = transmittance;
        } else if (pc.stage == kDpStageResolve) {
            if ((p.flags & kDpPathShadow) != 0u) {
                p.radiance += p.pending * FloatRW(pc.shadow).v[i];
                p.pending = vec3(0.0);
                p.flags &= ~kDpPathShadow;
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
    if (subgroupElect()) {
        atomicAdd(counters.v[kCounterDensityLookups], v0);
        atomicAdd(counters.v[kCounterRealCollisions], v1);
        atomicAdd(counters.v[kCounterNullCollisions], v2);
        atomicAdd(counters.v[kCounterTraversalSteps], v3);
        atomicAdd(counters.v[kCounterMajorantViolations], v4);
        atomicAdd(counters.v[kCounterNanSamples], v5);
        atomicAdd(counters.v[kCounterTrackingCapHits], v6);
        atomicAdd(counters.v[kCounterBounceLimitHits], v7);
        atomicAdd(counters.v[kCounterCount], v8);
    }
}
