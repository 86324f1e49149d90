// The path tracer's estimators (ae, ss, ms), written once: what a path does with the result of
// tracking its ray. Both passes run these functions and differ only in where tracking happens:
//   passes/path_trace.comp     one loop per path; tracking and shadow rays draw from p.rng
//   passes/path_trace_dp.comp  one stage per event; tracking is cut to the rank's box of space
//                              with per-rank random numbers and agreed over MPI in between
// The path's own decisions (light choice, phase sampling, roulette) draw from p.rng in the same
// order in both, so a data-parallel rank holds the same paths as every other. Shadow rays are
// next-event estimation: p.pending waits for the transmittance along (p.o, p.shadowDir,
// p.shadowDist), then resolveShadow adds it. Independent oracle: scene/reference_integrator.cpp.
// Needs kMode, lib/rng.glsl, lib/phase.glsl, shared/path_state_gpu.h, and with AMRVK_UBRM
// lib/unbiased_march.glsl.
#ifndef AMRVK_ESTIMATOR_GLSL
#define AMRVK_ESTIMATOR_GLSL

// Sample `sampleIndex` of pixel `pix` (index `pixel`): a camera ray jittered inside the pixel,
// seeded by the sample's number, so an image does not depend on how samples are grouped.
PathStateGpu startPath(uvec2 pix, uint pixel, uint sampleIndex) {
    PathStateGpu p;
    p.rng = seedRng(pixel, sampleIndex, P.view.seed);
    vec2 jitter = vec2(rand(p.rng), rand(p.rng));
    p.d = normalize(P.view.dir00 + (float(pix.x) + jitter.x) * P.view.du + (float(pix.y) + jitter.y) * P.view.dv);
    p.o = P.view.eye;
    p.bounce = 0u;
    p.throughput = vec3(1.0);
    p.flags = kPathLive;
    p.radiance = vec3(0.0);
    p.pixel = pixel;
    p.pending = vec3(0.0);
    p.shadowDist = 0.0;
    p.shadowDir = vec3(0.0);
    p.pad = 0u;
    return p;
}

// The transmittance estimate of a shadow ray: unbiased ray marching in the shaders built with
// AMRVK_UBRM (--transmittance ubrm), ratio tracking otherwise.
float shadowTransmittance(vec3 o, vec3 d, float tMax, StructureConfig cfg, inout uint rng, inout Counters c) {
#ifdef AMRVK_UBRM
    return ubrmTransmittance(o, d, tMax, cfg, rng, c);
#else
    return ratioTrack(o, d, tMax, cfg, rng, c);
#endif
}

// Next-event estimation from p.o: one of n lights chosen uniformly (with ambientCounts, k = the
// light count stands for the ambient environment, sampled through the phase function, whose
// phase / pdf is 1); its contribution weight x n x phase x radiance waits in p.pending.
void setUpShadow(inout PathStateGpu p, vec3 weight, uint n, bool ambientCounts) {
    uint k = min(uint(rand(p.rng) * float(n)), n - 1u);
    float g = P.shading.g;
    vec3 contribution;
    if (ambientCounts && k == P.shading.lightCount) {
        p.shadowDir = sampleHenyeyGreenstein(p.d, g, rand(p.rng), rand(p.rng));
        p.shadowDist = kInf;
        contribution = P.shading.ambient;
    } else {
        LightGpu L = P.shading.lights[k];
        vec3 Le = L.radiance;
        if (L.type == kLightPoint) {
            vec3 to = L.posOrDir - p.o;
            float dist = length(to);
            if (!(dist > 0.0)) return;  // at the light: no contribution
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
    p.flags |= kPathShadow;
}

// Acts on the tracking result of p's ray: a real collision at distance t with TF colour `color`
// (hit), or none. Ends the path, or sets up next-event estimation (kPathShadow) and, in ms, keeps
// it live for scatterPath. Returns true where the bounce limit (kMaxBounces) ended it.
bool shadeCollision(inout PathStateGpu p, bool hit, float t, vec3 color) {
    p.flags &= ~kPathLive;
    if (kMode == kModeAe) {
        p.radiance = hit ? color : P.shading.background;
        return false;
    }
    if (!hit) {  // escaped: the environment (primary rays see the background)
        p.radiance += p.throughput * (p.bounce == 0u ? P.shading.background : P.shading.ambient);
        return false;
    }
    if (kMode == kModeSs) {
        p.o += p.d * t;
        bool ambientOn = any(greaterThan(P.shading.ambient, vec3(0.0)));
        uint n = P.shading.lightCount + (ambientOn ? 1u : 0u);
        if (n > 0u) setUpShadow(p, color, n, ambientOn);
        return false;
    }
    // ms: the environment is reached only by escaping rays; point and directional lights (never
    // hit by rays) by next-event estimation at every collision.
    if (p.bounce + 1u >= kMaxBounces) return true;
    p.throughput *= color;
    p.o += p.d * t;
    uint lights = P.shading.lightCount;
    if (lights > 0u) setUpShadow(p, p.throughput, lights, false);
    p.flags |= kPathLive;
    return false;
}

// ms after shadeCollision kept the path live: Russian roulette below a throughput of 0.25, then
// a new direction from the phase function. Counts the bounce either way.
void scatterPath(inout PathStateGpu p) {
    if ((p.flags & kPathLive) == 0u) return;
    float q = max(p.throughput.r, max(p.throughput.g, p.throughput.b));
    bool survives = q > 0.0;
    if (survives && q < 0.25) {
        float survive = q / 0.25;
        survives = rand(p.rng) < survive;
        if (survives) p.throughput /= survive;
    }
    if (survives) p.d = sampleHenyeyGreenstein(p.d, P.shading.g, rand(p.rng), rand(p.rng));
    else p.flags &= ~kPathLive;
    ++p.bounce;
}

// Adds the waiting light contribution with the shadow ray's transmittance.
void resolveShadow(inout PathStateGpu p, float transmittance) {
    p.radiance += p.pending * transmittance;
    p.pending = vec3(0.0);
    p.flags &= ~kPathShadow;
}

#endif
