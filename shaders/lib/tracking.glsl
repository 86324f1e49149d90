// Free-flight sampling over majorant segments (Woodcock / delta tracking) and transmittance
// estimation (ratio tracking, Novak et al. 2014), over any traversal (traversal.glsl). Restarting at each
// segment boundary is valid because exponential free flights are memoryless. Majorant and
// acceptance test are in the same units (extinction per voxel unit), unlike upstream ExaBrick.
// CPU twin: render/reference_integrator.cpp (deltaTrack, ratioTrack).
#ifndef AMRVK_TRACKING_GLSL
#define AMRVK_TRACKING_GLSL

const uint kMaxTrackingSteps = 1u << 22;  // per ray; reaching it is counted as a violation
const float kViolationTolerance = 1.0 + 1e-6;

struct Counters {
    uint lookups, real, nulls, steps, violations;
};

// The field at local point p inside segment box `segmentId` (counted as one lookup). abr
// traversal + abr sampler: the segment's ABR is the containing one, so no search is needed.
FieldSample sampleInSegment(vec3 p, StructureConfig cfg, uint segmentId, inout Counters c) {
    c.lookups++;
    return (cfg.traversal == kTraversalAbr && cfg.samplerKind == kSamplerAbr) ? sampleInAbr(segmentId, p)
                                                                              : sampleField(cfg.samplerKind, cfg.backend, p);
}

// Extinction (per voxel unit) and TF colour at local point p, inside segment box `segmentId`.
float extinctionAt(vec3 p, StructureConfig cfg, uint segmentId, inout Counters c, out vec4 tfColor) {
    FieldSample s = sampleInSegment(p, cfg, segmentId, c);
    if (!s.inside) {
        tfColor = vec4(0.0);
        return 0.0;
    }
    tfColor = evalTf(s.value);
    return tfColor.a * P.boundsHi.w * P.boundsLo.w;
}

// Extinction per voxel unit from a majorant in alpha units.
float majorantExtinction(float majAlpha) { return majAlpha * P.boundsHi.w * P.boundsLo.w; }

// Samples a real collision along o + t d, t in [0, tMax]. Returns true with its distance and TF colour.
bool deltaTrack(vec3 o, vec3 d, float tMax, StructureConfig cfg, inout uint rng,
                inout Counters c, out float tHit, out vec4 tfHit) {
    Traversal s;
    tHit = tMax;
    tfHit = vec4(0.0);
    if (!traversalInit(cfg, o, d, 0.0, tMax, s)) return false;
    uint seg;
    float majAlpha, t0, t1;
    uint budget = kMaxTrackingSteps;
    while (traversalNext(cfg, s, c.steps, seg, majAlpha, t0, t1)) {
        float maj = majorantExtinction(majAlpha);
        if (!(maj > 0.0)) continue;
        float t = t0;
        while (budget-- > 0u) {
            t -= log(1.0 - rand(rng)) / maj;
            if (t >= t1) break;
            vec4 tfc;
            float sigma = extinctionAt(o + d * t, cfg, seg, c, tfc);
            if (sigma > maj * kViolationTolerance) c.violations++;
            if (rand(rng) * maj < sigma) {
                c.real++;
                tHit = t;
                tfHit = tfc;
                return true;
            }
            c.nulls++;
        }
        if (budget == 0u) {
            c.violations++;
            return false;
        }
    }
    return false;
}

// Unbiased estimate of the transmittance along o + t d, t in [0, tMax]; Russian roulette below 0.05.
float ratioTrack(vec3 o, vec3 d, float tMax, StructureConfig cfg, inout uint rng,
                 inout Counters c) {
    Traversal s;
    if (!traversalInit(cfg, o, d, 0.0, tMax, s)) return 1.0;
    float tr = 1.0;
    uint seg;
    float majAlpha, t0, t1;
    uint budget = kMaxTrackingSteps;
    while (traversalNext(cfg, s, c.steps, seg, majAlpha, t0, t1)) {
        float maj = majorantExtinction(majAlpha);
        if (!(maj > 0.0)) continue;
        float t = t0;
        while (budget-- > 0u) {
            t -= log(1.0 - rand(rng)) / maj;
            if (t >= t1) break;
            vec4 tfc;
            float sigma = extinctionAt(o + d * t, cfg, seg, c, tfc);
            if (sigma > maj * kViolationTolerance) c.violations++;
            tr *= max(0.0, 1.0 - sigma / maj);
            c.nulls++;
            if (tr < 0.05) {
                if (rand(rng) * 0.05 >= tr) return 0.0;
                tr = 0.05;
            }
        }
        if (budget == 0u) {
            c.violations++;
            return 0.0;
        }
    }
    return tr;
}

#endif
