// Unbiased ray marching (Kettunen et al. 2021, in the form below): the shadow rays' estimator of
// the path tracers built with AMRVK_UBRM (--transmittance ubrm; lib/estimator.glsl
// shadowTransmittance; ratio tracking, lib/tracking.glsl ratioTrack, otherwise). It writes
// T = exp(-tau) = exp(-c) sum_k (c - tau)^k / k! around a control c and estimates it with
// independent combs X_1, X_2, ... (E[X_j] = tau):
//   T^ = exp(-c) [1 + sum_{k=1..K} prod_{j<=k} (c - X_j) / (j p_j)],
// where term k is reached with probability p_1 ... p_k and p_j = min(1, lambda / j). The control
// and lambda come from two half-density combs A and B drawn first (c = (A + B) / 2, lambda =
// max(|A - B|, kUbrmLambdaMin)); they are independent of every X_j, so E[T^] = T exactly for any
// c and lambda (each factor has mean c - tau given the ones before it). T^ may leave [0, 1]; it has
// zero variance in a constant medium under one majorant (every comb returns tau). Where A
// has passed kUbrmRouletteDepth the ray is nearly opaque: it ends with probability 1 - q (T^ = 0)
// and otherwise goes on with weight 1 / q, a decision of the control's comb alone (unbiased).
// A comb is stratified in the majorant's optical depth: with rho(t) = min(M(t), two per finest cell)
// per unit length (M: the segment's majorant) and S the integral of rho over the ray, its n =
// ceil(density S) points lie at S(t_i) = (u + i) S / n (one u a comb), and X = sum sigma(t_i) S /
// (n rho(t_i)) is unbiased for tau (rho = 0 only where M = 0, so sigma = 0). Its cost follows the
// majorant as ratio tracking's does, stratified instead of Poisson, and only up to the data's
// resolution, so a loose majorant (spiky TF) costs at most two lookups per finest cell; under one
// majorant a constant medium gives X = tau exactly. Points in a sub-box whose sub-majorant is 0
// have sigma = 0 and are not looked up. S is found first by a pass over the segments (no lookups).
// Independent oracle: scene/reference_integrator.cpp (ratio tracking, double precision).
#ifndef AMRVK_UNBIASED_MARCH_GLSL
#define AMRVK_UNBIASED_MARCH_GLSL

const float kUbrmLambdaMin = 1.0;      // the least expected correction order (measured best of 0.1-2)
const float kUbrmRouletteDepth = 8.0;  // the control comb's depth past which the ray may end
const float kUbrmRouletteKeep = 0.1;   // ... kept with this probability, weighted by its inverse
const uint kUbrmMaxOrder = 64u;        // a series longer than this is counted as capped (never seen)

// The comb density per unit length in a segment of majorant maj (extinction per voxel unit).
float combDensity(float maj) { return min(maj, 2.0 * P.scene.invFinestCellWidth); }

// One pass along o + t d, t in [0, tMax]. n = 0: returns S, the comb density's integral (traversal
// steps, no lookups). n > 0: an unbiased comb estimate of the optical depth with n points over the
// span S; with `roulette` (the control's comb), past kUbrmRouletteDepth the ray ends with
// probability 1 - q (weight 0) or goes on (weight 1 / q). Reaching the step cap returns the depth so
// far and counts the cap (biased, as ratio tracking's). One function for both, called from one
// place: each call site inlines every traversal, and three of them overflowed spirv-opt's ids.
float combPass(vec3 o, vec3 d, float tMax, StructureConfig cfg, float span, uint n, bool roulette, inout uint rng,
               inout Counters c, out float weight) {
    weight = 1.0;
    float tBase;
    if (!rebaseRay(o, d, tMax, tBase)) return 0.0;
    Traversal s;
    if (!traversalInit(cfg, o, d, 0.0, tMax, s)) return 0.0;
    uint seg;
    float majAlpha, t0, t1;
    uint stepsLeft = P.shading.maxTrackingSteps;
    bool gridSegments = cfg.traversal == kTraversalGridDda || cfg.traversal == kTraversalGridBvh;
    float spacing = n > 0u ? span / float(n) : 0.0;
    float tau = 0.0, total = 0.0;
    float next = rand(rng) * spacing;  // comb density to the next point
    uint left = n;
    while (traversalNext(cfg, s, c.steps, seg, majAlpha, t0, t1)) {
        float maj = extinctionOfAlpha(majAlpha);
        float len = t1 - t0;
        if (!(maj > 0.0) || !(len > 0.0)) continue;
        float rho = combDensity(maj);
        float here = rho * len;
        total += here;
        if (n == 0u) continue;
        if (left == 0u) break;
        if (next >= here) {
            next -= here;
            continue;
        }
        SubBoxes sub;
        sub.word = kSubNotRefined;
        if (gridSegments) sub = subBoxesOf(seg);
        for (; next < here && left > 0u; next += spacing) {
            if (stepsLeft == 0u) {
                c.capped++;
                return tau;
            }
            --stepsLeft;
            --left;
            vec3 p = o + d * (t0 + next / rho);
            float share = sub.word != kSubNotRefined ? subMajorantShare(sub, p) : 1.0;
            vec4 tfc;
            if (share == 0.0) {  // sigma <= 0 there: no lookup
                c.thinned++;
                if (P.majorants.subMajorantCheck != 0u && extinctionAt(p, cfg, seg, c, tfc) > 0.0) c.violations++;
                continue;
            }
            float sigma = extinctionAt(p, cfg, seg, c, tfc);
            if (sigma > maj * share * kViolationTolerance) c.violations++;
            tau += sigma * spacing / rho;
        }
        next -= here;
        if (roulette && weight == 1.0 && tau > kUbrmRouletteDepth) {
            if (rand(rng) >= kUbrmRouletteKeep) {
                weight = 0.0;
                return tau;
            }
            weight = 1.0 / kUbrmRouletteKeep;
        }
    }
    return n == 0u ? total : tau;
}

// Unbiased estimate of the transmittance along o + t d, t in [0, tMax] (the series above). Pass 0
// finds the span, passes 1 and 2 are the control's half combs A and B, pass 2 + k the k-th
// correction's comb, reached with probability p_k.
float ubrmTransmittance(vec3 o, vec3 d, float tMax, StructureConfig cfg, inout uint rng, inout Counters c) {
    float span = 0.0, a = 0.0, control = 0.0, lambda = 1.0, weight = 1.0, sum = 1.0, term = 1.0;
    uint full = 0u, halfN = 0u;
    for (uint pass = 0u; pass < kUbrmMaxOrder + 3u; ++pass) {
        uint k = pass >= 3u ? pass - 2u : 0u;
        float pk = k > 0u ? min(1.0, lambda / float(k)) : 1.0;
        if (k > 0u && rand(rng) >= pk) return weight * exp(-control) * sum;
        float w;
        float x = combPass(o, d, tMax, cfg, span, pass == 0u ? 0u : (pass <= 2u ? halfN : full), pass == 1u, rng, c, w);
        if (pass == 0u) {
            if (!(x > 0.0)) return 1.0;  // no medium along the ray (every comb is 0)
            span = x;
            full = uint(min(ceil(span), 1e7));
            halfN = (full + 1u) / 2u;
        } else if (pass == 1u) {
            if (w == 0.0) return 0.0;  // ended by the roulette
            weight = w;
            a = x;
        } else if (pass == 2u) {
            control = 0.5 * (a + x);
            lambda = max(abs(a - x), kUbrmLambdaMin);
        } else {
            term *= (control - x) / (float(k) * pk);
            sum += term;
        }
    }
    c.capped++;
    return weight * exp(-control) * sum;
}

#endif
