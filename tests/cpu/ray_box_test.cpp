// The one ray/box slab test (accel/ray_box.h, twin of shaders/lib/ray_box.glsl) against brute
// force: points along the ray are inside the half-open box exactly for t in the interval, on
// random rays and on the hard ones (zero direction components of either sign, rays lying in face
// planes, through edges and corners, starting inside); float agrees with double.
#include <gtest/gtest.h>

#include <random>

#include "accel/ray_box.h"

using namespace amrvk::accel;

namespace {

const glm::dvec3 kLo(-2.0, 1.0, 0.5), kHi(4.0, 3.5, 2.0);

// Where a zero direction component keeps the ray, the half-open slab decides; elsewhere the
// closed box (the interval's ends are on the faces).
bool inside(glm::dvec3 p, glm::dvec3 d, double eps) {
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0) {
            if (p[a] < kLo[a] || p[a] >= kHi[a]) return false;
        } else if (p[a] < kLo[a] - eps || p[a] > kHi[a] + eps) {
            return false;
        }
    }
    return true;
}

void checkRay(glm::dvec3 o, glm::dvec3 d, const std::string& what) {
    const glm::dvec2 iv = rayBoxInterval(kLo, kHi, o, d);
    const bool hits = iv.x <= iv.y;
    // Brute force: dense samples of t; any inside point must lie within the interval.
    double firstIn = INFINITY, lastIn = -INFINITY;
    for (int i = -4000; i <= 4000; ++i) {
        const double t = i * 0.005;
        if (inside(o + d * t, d, 1e-12)) {
            firstIn = std::min(firstIn, t);
            lastIn = std::max(lastIn, t);
        }
    }
    if (!hits) {
        EXPECT_EQ(firstIn, INFINITY) << what << ": the interval is empty but t = " << firstIn << " is inside";
        return;
    }
    EXPECT_LE(iv.x, firstIn + 1e-9) << what;
    EXPECT_GE(iv.y, lastIn - 1e-9) << what;
    // Both ends and the middle lie in the box (closed where the ray moves).
    for (double t : {iv.x, 0.5 * (iv.x + iv.y), iv.y}) {
        if (std::isfinite(t)) {
            EXPECT_TRUE(inside(o + d * t, d, 1e-9)) << what << " at t = " << t;
        }
    }
    // The float twin gives the same interval to float precision.
    const glm::vec2 f = rayBoxInterval(glm::vec3(kLo), glm::vec3(kHi), glm::vec3(o), glm::vec3(d));
    if (std::isfinite(iv.x)) {
        EXPECT_NEAR(f.x, iv.x, 1e-5 * (1 + std::abs(iv.x))) << what;
    }
    if (std::isfinite(iv.y)) {
        EXPECT_NEAR(f.y, iv.y, 1e-5 * (1 + std::abs(iv.y))) << what;
    }
}

}  // namespace

TEST(RayBox, RandomRaysMatchBruteForce) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0), pos(-6.0, 8.0);
    for (int i = 0; i < 400; ++i) {
        const glm::dvec3 d(u(rng), u(rng), u(rng));
        if (glm::length(d) < 1e-3) continue;
        checkRay({pos(rng), pos(rng), pos(rng)}, glm::normalize(d), "random " + std::to_string(i));
    }
}

TEST(RayBox, HardRays) {
    for (double zero : {0.0, -0.0}) {
        checkRay({-10.0, 2.0, 1.0}, {1.0, zero, zero}, "axis-parallel through");
        checkRay({-10.0, 1.0, 1.0}, {1.0, zero, zero}, "in the lower y face plane: inside");
        checkRay({-10.0, 3.5, 1.0}, {1.0, zero, -zero}, "in the upper y face plane: outside");
        checkRay({-10.0, 1.0, 0.5}, {1.0, zero, zero}, "along a lower edge");
        checkRay({0.0, 2.0, 1.0}, {zero, zero, -1.0}, "starting inside");
    }
    checkRay(kLo - glm::dvec3(1.0), glm::normalize(kHi - kLo), "through two corners");
    checkRay({-2.0, 1.0, 0.5}, glm::normalize(glm::dvec3(-1.0, 1.0, 1.0)), "touching a corner");
    const glm::dvec2 upper = rayBoxInterval(kLo, kHi, {-10.0, 3.5, 1.0}, {1.0, 0.0, 0.0});
    EXPECT_GT(upper.x, upper.y) << "a ray in the upper face plane misses (the box above covers it)";
    double t0 = 0.0, t1 = 5.0;
    EXPECT_TRUE(clipRay(kLo, kHi, glm::dvec3(-4.0, 2.0, 1.0), glm::dvec3(1.0, 0.0, 0.0), t0, t1));
    EXPECT_EQ(t0, 2.0);
    EXPECT_EQ(t1, 5.0);
    t0 = 0.0;
    t1 = 1.5;
    EXPECT_FALSE(clipRay(kLo, kHi, glm::dvec3(-4.0, 2.0, 1.0), glm::dvec3(1.0, 0.0, 0.0), t0, t1))
        << "the box starts after tMax";
}
