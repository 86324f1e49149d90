// Random numbers: a PCG hash seeds a per-sample state; rand() returns floats in [0, 1) with 24
// random bits (so 1 - rand() is never 0). CPU twin: scene/reference_integrator.cpp (Rng).
#ifndef AMRVK_RNG_GLSL
#define AMRVK_RNG_GLSL

uint pcgHash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

uint seedRng(uint pixel, uint frame, uint seed) {
    return pcgHash(pixel ^ pcgHash(frame ^ pcgHash(seed)));
}

float rand(inout uint state) {
    state = state * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    word = (word >> 22u) ^ word;
    return float(word >> 8) * (1.0 / 16777216.0);
}

#endif
