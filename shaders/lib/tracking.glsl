// Free-flight sampling over majorant segments, in the shape of pbrt-v4's SampleT_maj: ONE loop
// (sampleTmaj) steps exponential distances with each segment's majorant and hands every tentative
// collision to the estimator the caller chose, which decides what it means:
//   kEstimatorDelta  delta (Woodcock) tracking: real with probability sigma / majorant, stops there
//   kEstimatorRatio  ratio tracking (Novak et al. 2014): transmittance *= 1 - sigma / majorant,
//                    Russian roulette below 0.05
// Restarting at each segment boundary is valid because exponential free flights are memoryless.
// With a control extinction (--control-extinction minorant: MajorantsGpu::gridMinorants, a
// minorant m <= sigma of each macrocell) the medium splits into m and the residual sigma - m in
// [0, M - m], and only the residual is tracked, with majorant M - m:
//   delta: decomposition tracking (Kutz et al. 2017): the first collision is the nearer of the
//          control's (where the control's optical depth reaches an Exp(1) draw, always real) and
//          the residual's (accepted with probability (sigma - m) / (M - m)).
//   ratio: residual ratio tracking (Novak et al. 2014): exp(-sum of m * length) exactly (applied at
//          each residual collision, before its weight and roulette, once it exceeds e^-1, then
//          with the roulette, and at the end), times the residual's ratio-tracking weights
//          1 - (sigma - m) / (M - m).
// Both are unbiased; a control collision needs a lookup for its colour only. Where m = 0 they are
// delta and ratio tracking step for step.
// Majorant and acceptance test are in the same units (extinction per voxel unit), unlike upstream
// ExaBrick. A call takes at most P.shading.maxTrackingSteps steps; reaching that cap, or a mean
// free path too short to advance t in float, ends it (delta: no collision, ratio: transmittance 0
// — biased) and is counted (kCounterTrackingCapHits), never silent.
// CPU twin: scene/reference_integrator.cpp (sampleTmaj, deltaTrack, ratioTrack).
#ifndef AMRVK_TRACKING_GLSL
#define AMRVK_TRACKING_GLSL

// --control-extinction minorant (render::TracerVariant::control): a specialization constant, so a
// pipeline without it runs none of the control's code. On, the control is used where
// MajorantsGpu::gridMinorants is set. (Its code still costs lavapipe about 0.45 s of cold compile a
// path tracer, specialised off or not: a shader variant, as ubrm's, would take that away.)
layout(constant_id = 5) const bool kControlExtinction = false;

const float kViolationTolerance = 1.0 + 1e-6;
const uint kEstimatorDelta = 0u;
const uint kEstimatorRatio = 1u;

struct Counters {
    uint lookups, real, nulls, steps, violations, capped;
    uint shadowLookups;  // of lookups, those of shadow rays (the pass counts them)
    uint thinned;        // collisions decided by a sub-majorant without a lookup
};

Counters newCounters() { return Counters(0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u); }

// Extinction per voxel unit of a TF alpha (or a majorant in alpha units).
float extinctionOfAlpha(float alpha) { return alpha * P.shading.densityScale * P.scene.invFinestCellWidth; }

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
    return extinctionOfAlpha(tfColor.a);
}

// What an estimator has found so far.
struct TrackState {
    bool hit;             // delta: a real collision was sampled
    float tHit;           // delta: its distance
    vec4 tfHit;           // delta: the TF colour there
    float transmittance;  // ratio: the running estimate
};

TrackState newTrackState() { return TrackState(false, kInf, vec4(0.0), 1.0); }

// Russian roulette below 0.05: returns false (transmittance 0) to stop tracking.
bool ratioRoulette(inout TrackState st, inout uint rng) {
    if (st.transmittance < 0.05) {
        if (rand(rng) * 0.05 >= st.transmittance) {
            st.transmittance = 0.0;
            return false;
        }
        st.transmittance = 0.05;
    }
    return true;
}

// Ratio tracking's weight at a collision against majorant maj (extinction sigma), then the
// roulette. Returns false to stop tracking.
bool onRatioCollision(float sigma, float maj, inout TrackState st, inout uint rng, inout Counters c) {
    st.transmittance *= max(0.0, 1.0 - sigma / maj);
    c.nulls++;
    return ratioRoulette(st, rng);
}

// Ratio tracking with a control: the control's optical depth passed so far applied exactly.
void foldControl(inout float depth, inout TrackState st) {
    if (depth > 0.0) {
        st.transmittance *= exp(-depth);
        depth = 0.0;
    }
}

// The control's share of macrocell [t0, t1] (control extinction m > 0). Ratio: its optical depth is
// added to `depth` and applied once past e^-1, then the roulette (false stops the call). Delta:
// tControl is where its collision falls (kInf: beyond t1), from `left`, the control's optical depth
// left before that collision (drawn at the first macrocell, where left < 0).
bool controlSegment(uint estimator, float m, float t0, float t1, inout float depth, inout float left,
                    inout TrackState st, inout uint rng, out float tControl) {
    tControl = kInf;
    float here = m * (t1 - t0);
    if (estimator != kEstimatorDelta) {
        depth += here;
        if (!(depth > 1.0)) return true;
        foldControl(depth, st);
        return ratioRoulette(st, rng);
    }
    if (left < 0.0) left = -log(1.0 - rand(rng));
    if (here > left) tControl = t0 + left / m;
    left -= here;  // a collision in this macrocell ends the call
    return true;
}

// Delta: the control's collision at t (always real), looked up for its colour.
void controlCollision(vec3 o, vec3 d, float t, float tBase, float m, StructureConfig cfg, uint seg,
                      inout TrackState st, inout Counters c) {
    vec4 tfc;
    if (extinctionAt(o + d * t, cfg, seg, c, tfc) < m) c.violations++;
    c.real++;
    st.hit = true;
    st.tHit = tBase + t;
    st.tfHit = tfc;
}

// The estimator's decision at a tentative collision at t (extinction sigma, majorant maj, TF
// colour tfc). Returns false to stop tracking.
bool onCollision(uint estimator, float t, float sigma, float maj, vec4 tfc, inout TrackState st, inout uint rng,
                 inout Counters c) {
    if (estimator == kEstimatorDelta) {
        if (rand(rng) * maj < sigma) {
            c.real++;
            st.hit = true;
            st.tHit = t;
            st.tfHit = tfc;
            return false;
        }
        c.nulls++;
        return true;
    }
    return onRatioCollision(sigma, maj, st, rng, c);
}

// Tracks o + t d over t in [0, tMax] through the traversal's majorant segments. The ray is first
// rebased where it enters the data (rebaseRay), so segments and sample positions are as accurate
// as the data's own coordinates whatever the distance of the origin: every range covers its box
// grown by 2^-18 of the extent (accel/majorant_bounds.h), far more than that rounding. In a
// macrocell with sub-majorants (lib/sub_majorants.glsl) a collision that its sub-box's majorant
// decides is not looked up: delta tracking draws its acceptance uniform u first and a u >= q / 255
// is a null collision (the same decision as with the lookup: sigma <= M q / 255 <= u M); ratio
// tracking keeps a collision with probability q / 255 and weights it against M q / 255.
void sampleTmaj(vec3 o, vec3 d, float tMax, StructureConfig cfg, uint estimator, inout TrackState st, inout uint rng,
                inout Counters c) {
    float tBase;
    if (!rebaseRay(o, d, tMax, tBase)) return;
    Traversal s;
    if (!traversalInit(cfg, o, d, 0.0, tMax, s)) return;
    uint seg;
    float majAlpha, t0, t1;
    uint stepsLeft = P.shading.maxTrackingSteps;
    bool gridSegments = cfg.traversal == kTraversalGridDda || cfg.traversal == kTraversalGridBvh;
    bool control = kControlExtinction && gridSegments && P.majorants.gridMinorants != 0ul;
    // The control's optical depth: ratio, passed but not yet applied (exp(-depth) is applied at
    // the next residual collision, once it exceeds 1, and at the end); delta, left before its
    // collision (one exponential draw per call, at the first macrocell with a control).
    float controlDepth = 0.0, controlLeft = -1.0;
    // The least step that still moves the position in float: an ulp of o's largest coordinate
    // along d's largest component. A mean free path below it makes no progress, also from t = 0
    // (a ray that starts at a collision in a medium of --density-scale 1e30 burned the step cap).
    float dMax = max(max(abs(d.x), abs(d.y)), abs(d.z));
    float stallStep = max(max(abs(o.x), abs(o.y)), abs(o.z)) * 1.2e-7 / max(dMax, 1e-30);
    while (traversalNext(cfg, s, c.steps, seg, majAlpha, t0, t1)) {
        float maj = extinctionOfAlpha(majAlpha);
        if (!(maj > 0.0)) continue;
        // The control extinction m of this macrocell (0 without one) and the residual's majorant.
        float m = control ? min(extinctionOfAlpha(FloatRef(P.majorants.gridMinorants).v[seg]), maj) : 0.0;
        float resMaj = maj - m;
        // The control's share: exactly for ratio tracking; for delta its collision distance.
        float tControl = kInf;
        if (m > 0.0 && !controlSegment(estimator, m, t0, t1, controlDepth, controlLeft, st, rng, tControl)) return;
        float meanStep = 1.0 / resMaj;
        SubBoxes sub;
        sub.word = kSubNotRefined;
        if (gridSegments) sub = subBoxesOf(seg);
        float tEnd = min(t1, tControl);
        float t = t0;
        // A residual of 0 is not tracked: only the control's collision, if any, is left.
        bool track = resMaj > 0.0;
        while (track) {
            // The cap, or a mean free path below float resolution at t or at the position (t
            // would stall and burn the cap in place, e.g. --density-scale 1e30): both end the
            // call, counted, at once.
            if (stepsLeft == 0u || t + meanStep == t || meanStep < stallStep) {
                c.capped++;
                st.hit = false;
                st.transmittance = 0.0;
                return;
            }
            --stepsLeft;
            t -= log(1.0 - rand(rng)) * meanStep;
            if (t >= tEnd) break;
            vec3 p = o + d * t;
            vec4 tfc;
            if (sub.word == kSubNotRefined) {
                float sigma = extinctionAt(p, cfg, seg, c, tfc);
                if (sigma > maj * kViolationTolerance || sigma < m) c.violations++;
                foldControl(controlDepth, st);
                if (!onCollision(estimator, tBase + t, sigma - m, resMaj, tfc, st, rng, c)) return;
                continue;
            }
            // The sub-box's majorant M q / 255 bounds the residual by M q / 255 - m: its share of resMaj.
            float subMaj = maj * subMajorantShare(sub, p);
            float share = clamp((subMaj - m) / resMaj, 0.0, 1.0);
            // Ratio tracking with a full share keeps every collision (no draw), as without sub-boxes.
            float u = estimator == kEstimatorDelta || (share > 0.0 && share < 1.0) ? rand(rng) : 0.0;
            if (u >= share) {  // decided by the sub-majorant: null (delta), weight 1 (ratio)
                c.thinned++;
                if (P.majorants.subMajorantCheck != 0u) {
                    float sigma = extinctionAt(p, cfg, seg, c, tfc);
                    if (sigma > subMaj * kViolationTolerance || sigma < m) c.violations++;
                }
                continue;
            }
            float sigma = extinctionAt(p, cfg, seg, c, tfc);
            if (sigma > subMaj * kViolationTolerance || sigma < m) c.violations++;
            if (estimator == kEstimatorDelta) {
                if (u * resMaj < sigma - m) {
                    c.real++;
                    st.hit = true;
                    st.tHit = tBase + t;
                    st.tfHit = tfc;
                    return;
                }
                c.nulls++;
                continue;
            }
            foldControl(controlDepth, st);
            if (!onRatioCollision(sigma - m, resMaj * share, st, rng, c)) return;
        }
        // Delta: the control's collision comes first (no residual collision before it in this
        // macrocell).
        if (tControl < t1) {
            controlCollision(o, d, tControl, tBase, m, cfg, seg, st, c);
            return;
        }
    }
    foldControl(controlDepth, st);
}

// Samples a real collision along o + t d, t in [0, tMax]. Returns true with its distance and TF colour.
bool deltaTrack(vec3 o, vec3 d, float tMax, StructureConfig cfg, inout uint rng, inout Counters c, out float tHit,
                out vec4 tfHit) {
    TrackState st = newTrackState();
    sampleTmaj(o, d, tMax, cfg, kEstimatorDelta, st, rng, c);
    tHit = st.hit ? st.tHit : tMax;
    tfHit = st.tfHit;
    return st.hit;
}

// Unbiased estimate of the transmittance along o + t d, t in [0, tMax].
float ratioTrack(vec3 o, vec3 d, float tMax, StructureConfig cfg, inout uint rng, inout Counters c) {
    TrackState st = newTrackState();
    sampleTmaj(o, d, tMax, cfg, kEstimatorRatio, st, rng, c);
    return st.transmittance;
}

#endif
