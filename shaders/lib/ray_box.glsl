// The ray/box slab test, the one copy every traversal uses. CPU twin: accel/ray_box.h (the same
// operations in the same order, so float results are bit-identical).
#ifndef AMRVK_RAY_BOX_GLSL
#define AMRVK_RAY_BOX_GLSL

// Parametric interval (entry, exit) of the ray o + t d inside the box [lo, hi]; entry > exit when
// they miss. A zero direction component (+0 or -0) never divides: the ray counts as inside that
// slab when lo <= o < hi, so a ray lying in the plane of a box's upper face misses it (the box
// beyond that plane, if any, covers it), the convention hardware ray queries follow too.
vec2 rayBoxInterval(vec3 lo, vec3 hi, vec3 o, vec3 d) {
    float e = -kInf, x = kInf;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0) {
            if (o[a] < lo[a] || o[a] >= hi[a]) return vec2(kInf, -kInf);
            continue;
        }
        precise float inv = 1.0 / d[a];
        precise float t0 = (lo[a] - o[a]) * inv;
        precise float t1 = (hi[a] - o[a]) * inv;
        e = max(e, min(t0, t1));
        x = min(x, max(t0, t1));
    }
    return vec2(e, x);
}

// Narrows [tMin, tMax] to the ray's overlap with the box; false when they do not overlap.
bool clipRay(vec3 lo, vec3 hi, vec3 o, vec3 d, inout float tMin, inout float tMax) {
    vec2 ex = rayBoxInterval(lo, hi, o, d);
    tMin = max(tMin, ex.x);
    tMax = min(tMax, ex.y);
    return tMin <= tMax;
}

#endif
