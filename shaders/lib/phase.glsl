// Henyey-Greenstein phase function. Directions are propagation directions: cosTheta is between
// the incoming ray direction and the scattered one (g > 0 scatters forward). |g| < 1e-3 is
// treated as isotropic; callers keep |g| <= 0.999 (the CLI clamps), so no NaN near |g| = 1.
// CPU twin: scene/reference_integrator.cpp (sampleHenyeyGreenstein, henyeyGreenstein).
#ifndef AMRVK_PHASE_GLSL
#define AMRVK_PHASE_GLSL

const float kInvFourPi = 0.07957747154594767;

float henyeyGreenstein(float cosTheta, float g) {
    float denom = 1.0 + g * g - 2.0 * g * cosTheta;
    return kInvFourPi * (1.0 - g * g) / (denom * sqrt(max(denom, 1e-12)));
}

// Orthonormal basis around unit n (Duff et al. 2017).
void makeBasis(vec3 n, out vec3 t, out vec3 b) {
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

// Samples a scattered direction for incoming direction d; pdf = henyeyGreenstein(cos, g).
vec3 sampleHenyeyGreenstein(vec3 d, float g, float u1, float u2) {
    float cosTheta;
    if (abs(g) < 1e-3) {
        cosTheta = 1.0 - 2.0 * u1;
    } else {
        float sq = (1.0 - g * g) / (1.0 - g + 2.0 * g * u1);
        cosTheta = (1.0 + g * g - sq * sq) / (2.0 * g);
    }
    cosTheta = clamp(cosTheta, -1.0, 1.0);
    float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
    float phi = 6.283185307179586 * u2;
    vec3 t, b;
    makeBasis(d, t, b);
    return normalize(sinTheta * cos(phi) * t + sinTheta * sin(phi) * b + cosTheta * d);
}

#endif
