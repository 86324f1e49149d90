// The ray-marching baseline (dvr mode; exabrick-reference.md 5, "DVR"): emission-absorption along
// the ray by a Riemann sum, front to back, over the segments of any traversal (segments with
// majorant 0 are skipped: empty-space skipping). Step h = dt x the finest cell width among the
// bricks with weight at the previous sample (ExaBrick: the finest width of the ABR); jittered
// start (again after each skipped gap); opacity correction alpha' = 1 - exp(-sigma h), i.e.
// 1 - (1 - alpha)^(h / finest width) in the TF's units; stops at opacity P.shading.dvrOpacityStop (0.99).
// Biased by h and by the termination; as dt -> 0 it tends to the ae mode's expectation.
#ifndef AMRVK_RAY_MARCH_GLSL
#define AMRVK_RAY_MARCH_GLSL

// Central-difference gradient of the field at p with spacing h (voxel units): 6 lookups. A
// neighbour outside every cell support (no data) is replaced by the centre value vc, so the
// difference becomes one-sided at the edge of the data instead of jumping to 0.
vec3 fieldGradient(vec3 p, float h, float vc, StructureConfig cfg, inout Counters c) {
    vec3 g;
    for (int a = 0; a < 3; ++a) {
        vec3 e = vec3(0.0);
        e[a] = h;
        FieldSample s0 = sampleField(cfg.samplerKind, cfg.backend, p - e);
        FieldSample s1 = sampleField(cfg.samplerKind, cfg.backend, p + e);
        c.lookups += 2u;
        float span = (s0.weightSum > 0.0 ? h : 0.0) + (s1.weightSum > 0.0 ? h : 0.0);
        float v0 = s0.weightSum > 0.0 ? s0.value : vc, v1 = s1.weightSum > 0.0 ? s1.value : vc;
        g[a] = span > 0.0 ? (v1 - v0) / span : 0.0;
    }
    return g;
}

// Radiance along o + t d: sum of T * alpha' * colour (shaded when P.shading.dvrShading) + T * background.
vec3 rayMarch(vec3 o, vec3 d, StructureConfig cfg, inout uint rng, inout Counters c) {
    Traversal s;
    vec3 L = vec3(0.0);
    float T = 1.0;
    const float dt = P.shading.dvrStep;
    const float stopTransmittance = 1.0 - P.shading.dvrOpacityStop;
    float tMax = kInf, tBase;
    if (rebaseRay(o, d, tMax, tBase) && traversalInit(cfg, o, d, 0.0, tMax, s)) {
        uint seg;
        float majAlpha, t0, t1;
        float h = dt / P.scene.invFinestCellWidth;  // dt x the finest cell width of the data set, until a sample says more
        float t = -1.0;  // next sample; < t0 means a gap was skipped: jitter again
        while (T > stopTransmittance && traversalNext(cfg, s, c.steps, seg, majAlpha, t0, t1)) {
            if (!(majAlpha > 0.0)) continue;
            if (t < t0) t = t0 + rand(rng) * h;
            while (t < t1 && T > stopTransmittance) {
                vec3 p = o + d * t;
                vec4 tfc;
                FieldSample fs = sampleInSegment(p, cfg, seg, c);
                c.real++;
                if (fs.inside && fs.finestLevel < kNoLevel) h = dt * float(1 << fs.finestLevel);
                float sigma = 0.0;
                if (fs.inside) {
                    tfc = evalTf(fs.value);
                    sigma = extinctionOfAlpha(tfc.a);
                }
                if (sigma > 0.0) {
                    float alpha = 1.0 - exp(-sigma * h);
                    vec3 colour = tfc.rgb;
                    if (P.shading.dvrShading != 0u) {
                        vec3 g = fieldGradient(p, max(h / dt, 1.0), fs.value, cfg, c);
                        float len = length(g);
                        float lambert = len > 0.0 ? abs(dot(g / len, P.shading.dvrLightDir)) : 1.0;
                        colour *= P.shading.dvrAmbient + (1.0 - P.shading.dvrAmbient) * lambert;
                    }
                    L += T * alpha * colour;
                    T *= 1.0 - alpha;
                }
                t += h;
            }
        }
    }
    return L + T * P.shading.background;
}

#endif
