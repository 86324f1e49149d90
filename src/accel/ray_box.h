#pragma once
// The ray/box slab test. CPU twin of shaders/lib/ray_box.glsl: the same operations in the same
// order (templated on the scalar type: float reproduces the shader bit for bit, double is the
// precise reference).
#include <glm/glm.hpp>

#include <algorithm>
#include <limits>

namespace amrvk::accel {

// Parametric interval (entry, exit) of the ray o + t d inside the box [lo, hi]; entry > exit when
// they miss. A zero direction component (+0 or -0) never divides: the ray counts as inside that
// slab when lo <= o < hi, so a ray lying in the plane of a box's upper face misses it.
template <typename T>
glm::vec<2, T> rayBoxInterval(glm::vec<3, T> lo, glm::vec<3, T> hi, glm::vec<3, T> o, glm::vec<3, T> d) {
    const T inf = std::numeric_limits<T>::infinity();
    T e = -inf, x = inf;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == T(0)) {
            if (o[a] < lo[a] || o[a] >= hi[a]) return {inf, -inf};
            continue;
        }
        const T inv = T(1) / d[a];
        const T t0 = (lo[a] - o[a]) * inv;
        const T t1 = (hi[a] - o[a]) * inv;
        e = std::max(e, std::min(t0, t1));
        x = std::min(x, std::max(t0, t1));
    }
    return {e, x};
}

// Narrows [tMin, tMax] to the ray's overlap with the box; false when they do not overlap.
template <typename T>
bool clipRay(glm::vec<3, T> lo, glm::vec<3, T> hi, glm::vec<3, T> o, glm::vec<3, T> d, T& tMin, T& tMax) {
    const glm::vec<2, T> ex = rayBoxInterval(lo, hi, o, d);
    tMin = std::max(tMin, ex.x);
    tMax = std::min(tMax, ex.y);
    return tMin <= tMax;
}

}  // namespace amrvk::accel
