// Orbit / pan / zoom: the framing view equals the default camera; orbiting keeps the distance and
// target; a full viewport height turns 180 degrees; elevation stops short of the poles; panning
// moves the target in the view plane by the world size of the pixels; zoom is clamped; an explicit
// camera round-trips; every up axis works.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "session/orbit_camera.h"

using namespace amrvk;
using session::OrbitCamera;

namespace {
const glm::dvec3 kLo(0.0), kHi(4.0, 2.0, 1.0);

void expectNear(glm::dvec3 a, glm::dvec3 b, double tol, const char* what) {
    EXPECT_NEAR(glm::length(a - b), 0.0, tol) << what << ": (" << a.x << ", " << a.y << ", " << a.z << ") vs ("
                                              << b.x << ", " << b.y << ", " << b.z << ")";
}
}  // namespace

TEST(OrbitCamera, FramesLikeTheDefaultCamera) {
    const OrbitCamera o(kLo, kHi, 35.0);
    const scene::Camera c = o.camera(), d = scene::defaultCamera(kLo, kHi, 35.0);
    expectNear(c.eye, d.eye, 1e-9, "eye");
    expectNear(c.target, d.target, 1e-12, "target");
    EXPECT_EQ(c.up, glm::dvec3(0, 0, 1));
    EXPECT_EQ(c.fovYDegrees, 35.0);
}

TEST(OrbitCamera, OrbitTurnsAroundTheTarget) {
    OrbitCamera o(kLo, kHi);
    const scene::Camera before = o.camera();
    o.orbit(300.0, 0.0, 600.0);  // half the height: 90 degrees of azimuth
    const scene::Camera after = o.camera();
    expectNear(after.target, before.target, 1e-12, "target");
    EXPECT_NEAR(glm::length(after.eye - after.target), glm::length(before.eye - before.target), 1e-9);
    const glm::dvec3 a = before.eye - before.target, b = after.eye - after.target;
    // Horizontal parts are perpendicular, heights equal (pure azimuth).
    EXPECT_NEAR(a.x * b.x + a.y * b.y, 0.0, 1e-9);
    EXPECT_NEAR(a.z, b.z, 1e-9);
    o.orbit(0.0, 1e6, 600.0);  // far past the pole
    const glm::dvec3 top = glm::normalize(o.camera().eye - o.camera().target);
    EXPECT_NEAR(std::asin(top.z) * 180.0 / M_PI, 89.0, 1e-6) << "elevation stops at 89 degrees";
    EXPECT_GT(glm::length(glm::cross(o.camera().target - o.camera().eye, o.camera().up)), 1e-3)
        << "up never parallel to the view";
}

TEST(OrbitCamera, PanMovesThePointUnderTheCursor) {
    OrbitCamera o(kLo, kHi, 40.0);
    const scene::Camera c = o.camera();
    const double height = 500.0;
    const double perPixel = 2.0 * o.distance() * std::tan(glm::radians(20.0)) / height;
    o.pan(100.0, 0.0, height);
    const glm::dvec3 forward = glm::normalize(c.target - c.eye), right = glm::normalize(glm::cross(forward, c.up));
    expectNear(o.target(), c.target - right * (100.0 * perPixel), 1e-9, "pan right drags the scene right");
    EXPECT_NEAR(o.distance(), glm::length(c.eye - c.target), 1e-9);
}

TEST(OrbitCamera, ZoomIsClampedAndResetRestores) {
    OrbitCamera o(kLo, kHi);
    const double d0 = o.distance();
    o.zoom(1.0);
    EXPECT_NEAR(o.distance(), 0.9 * d0, 1e-12);
    o.zoom(1e6);
    const double radius = 0.5 * glm::length(kHi - kLo);
    EXPECT_NEAR(o.distance(), 1e-3 * radius, 1e-12);
    o.zoom(-1e6);
    EXPECT_NEAR(o.distance(), 100.0 * radius, 1e-9);
    o.orbit(10, 20, 100);
    o.pan(5, 5, 100);
    o.reset();
    expectNear(o.camera().eye, OrbitCamera(kLo, kHi).camera().eye, 1e-9, "reset");
}

TEST(OrbitCamera, ExplicitCamerasAndUpAxesRoundTrip) {
    OrbitCamera o(kLo, kHi);
    scene::Camera c;
    c.eye = {10.0, -3.0, 7.0};
    c.target = {1.0, 1.0, 0.5};
    c.up = {0.1, 0.05, 1.0};  // snapped to +z
    c.fovYDegrees = 25.0;
    o.setCamera(c);
    expectNear(o.camera().eye, c.eye, 1e-9, "eye");
    expectNear(o.camera().target, c.target, 1e-12, "target");
    EXPECT_EQ(o.camera().up, glm::dvec3(0, 0, 1));
    EXPECT_EQ(o.fovYDegrees(), 25.0);
    for (int axis : {0, 1, 2}) {
        OrbitCamera y(kLo, kHi, 40.0, axis);
        const scene::Camera v = y.camera();
        EXPECT_EQ(v.up[axis], 1.0);
        EXPECT_GT(glm::length(glm::cross(v.target - v.eye, v.up)), 1e-6);
        y.orbit(50, -30, 200);
        y.setUpAxis((axis + 1) % 3);
        EXPECT_EQ(y.upAxis(), (axis + 1) % 3);
        EXPECT_NEAR(glm::length(y.camera().eye - y.camera().target), y.distance(), 1e-9);
    }
    EXPECT_THROW(o.setFov(0.0), Error);
    EXPECT_THROW(o.setUpAxis(3), Error);
}
