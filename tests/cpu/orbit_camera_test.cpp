// Orbit / pan / zoom as edits of a camera: the framing view equals the default camera; orbiting
// keeps the distance and target; a full viewport height turns 180 degrees; elevation stops short of
// the poles; panning moves the target in the view plane by the world size of the pixels; zoom is
// clamped; an explicit camera is kept as it is until an edit (then its up vector is snapped);
// every up axis works.
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
    const OrbitCamera o(kLo, kHi);
    const scene::Camera c = o.framing(35.0), d = scene::defaultCamera(kLo, kHi, 35.0);
    expectNear(c.eye, d.eye, 1e-9, "eye");
    expectNear(c.target, d.target, 1e-12, "target");
    EXPECT_EQ(c.up, glm::dvec3(0, 0, 1));
    EXPECT_EQ(c.fovYDegrees, 35.0);
}

TEST(OrbitCamera, OrbitTurnsAroundTheTarget) {
    const OrbitCamera o(kLo, kHi);
    const scene::Camera before = o.framing();
    scene::Camera after = before;
    o.orbit(after, 300.0, 0.0, 600.0);  // half the height: 90 degrees of azimuth
    expectNear(after.target, before.target, 1e-12, "target");
    EXPECT_NEAR(glm::length(after.eye - after.target), glm::length(before.eye - before.target), 1e-9);
    const glm::dvec3 a = before.eye - before.target, b = after.eye - after.target;
    // Horizontal parts are perpendicular, heights equal (pure azimuth).
    EXPECT_NEAR(a.x * b.x + a.y * b.y, 0.0, 1e-9);
    EXPECT_NEAR(a.z, b.z, 1e-9);
    o.orbit(after, 0.0, 1e6, 600.0);  // far past the pole
    const glm::dvec3 top = glm::normalize(after.eye - after.target);
    EXPECT_NEAR(std::asin(top.z) * 180.0 / M_PI, 89.0, 1e-6) << "elevation stops at 89 degrees";
    EXPECT_GT(glm::length(glm::cross(after.target - after.eye, after.up)), 1e-3) << "up never parallel to the view";
    // Many small drags there and back end where they started (no drift from the angle round trips).
    scene::Camera c = before;
    for (int i = 0; i < 1000; ++i) o.orbit(c, 3.0, 0.1, 600.0);  // 900 degrees around, 30 up
    for (int i = 0; i < 1000; ++i) o.orbit(c, -3.0, -0.1, 600.0);
    expectNear(c.eye, before.eye, 1e-9, "a thousand drags and back");
}

TEST(OrbitCamera, PanMovesThePointUnderTheCursor) {
    const OrbitCamera o(kLo, kHi);
    const scene::Camera c = o.framing(40.0);
    const double height = 500.0;
    const double distance = glm::length(c.eye - c.target);
    const double perPixel = 2.0 * distance * std::tan(glm::radians(20.0)) / height;
    scene::Camera p = c;
    o.pan(p, 100.0, 0.0, height);
    const glm::dvec3 forward = glm::normalize(c.target - c.eye), right = glm::normalize(glm::cross(forward, c.up));
    expectNear(p.target, c.target - right * (100.0 * perPixel), 1e-9, "pan right drags the scene right");
    EXPECT_NEAR(glm::length(p.eye - p.target), distance, 1e-9);
}

TEST(OrbitCamera, ZoomIsClampedAndResetRestores) {
    const OrbitCamera o(kLo, kHi);
    scene::Camera c = o.framing();
    const double d0 = glm::length(c.eye - c.target);
    o.zoom(c, 1.0);
    EXPECT_NEAR(glm::length(c.eye - c.target), 0.9 * d0, 1e-12);
    o.zoom(c, 1e6);
    const double radius = 0.5 * glm::length(kHi - kLo);
    EXPECT_NEAR(glm::length(c.eye - c.target), 1e-3 * radius, 1e-12);
    o.zoom(c, -1e6);
    EXPECT_NEAR(glm::length(c.eye - c.target), 100.0 * radius, 1e-9);
    o.orbit(c, 10, 20, 100);
    o.pan(c, 5, 5, 100);
    o.reset(c);
    expectNear(c.eye, o.framing().eye, 1e-9, "reset");
}

TEST(OrbitCamera, ExplicitCamerasAndUpAxes) {
    const OrbitCamera o(kLo, kHi);
    scene::Camera c;
    c.eye = {10.0, -3.0, 7.0};
    c.target = {1.0, 1.0, 0.5};
    c.up = {0.1, 0.05, 1.0};  // nearest axis +z
    c.fovYDegrees = 25.0;
    EXPECT_EQ(OrbitCamera::upAxis(c), 2);
    scene::Camera edited = c;
    o.orbit(edited, 0.0, 0.0, 100.0);  // an edit of nothing: the view stays, the up vector snaps
    expectNear(edited.eye, c.eye, 1e-9, "eye");
    expectNear(edited.target, c.target, 1e-12, "target");
    EXPECT_EQ(edited.up, glm::dvec3(0, 0, 1));
    EXPECT_EQ(edited.fovYDegrees, 25.0);
    for (int axis : {0, 1, 2}) {
        scene::Camera v = o.framing(40.0, axis);
        EXPECT_EQ(v.up[axis], 1.0);
        EXPECT_GT(glm::length(glm::cross(v.target - v.eye, v.up)), 1e-6);
        o.orbit(v, 50, -30, 200);
        const double distance = glm::length(v.eye - v.target);
        OrbitCamera::setUpAxis(v, (axis + 1) % 3);
        EXPECT_EQ(OrbitCamera::upAxis(v), (axis + 1) % 3);
        EXPECT_NEAR(glm::length(v.eye - v.target), distance, 1e-9);
    }
    EXPECT_THROW(OrbitCamera::setFov(c, 0.0), Error);
    EXPECT_THROW(OrbitCamera::setUpAxis(c, 3), Error);
    EXPECT_THROW(o.framing(40.0, -1), Error);
}

// render --orbit: a rigid turn about the vertical line through the data's centre, checked against
// rotations written out by hand (90 degrees about +z maps (x, y) to (-y, x)).
TEST(OrbitCamera, OrbitedAboutTurnsTheWholeCameraAboutTheCentre) {
    const scene::Camera c{.eye = {5, 1, 3}, .target = {2, 1, 1}, .up = {0, 0, 2}, .fovYDegrees = 30};
    const glm::dvec3 centre(2, 1, 0);
    const scene::Camera q = OrbitCamera::orbitedAbout(c, centre, 90);
    expectNear(q.eye, glm::dvec3(2, 4, 3), 1e-12, "eye: (3, 0, 3) from the centre turns to (0, 3, 3)");
    expectNear(q.target, glm::dvec3(2, 1, 1), 1e-12, "target on the axis stays");
    expectNear(q.up, glm::dvec3(0, 0, 2), 1e-12, "up along the axis stays");
    EXPECT_EQ(q.fovYDegrees, 30.0);
    const scene::Camera h = OrbitCamera::orbitedAbout(c, centre, -180);
    expectNear(h.eye, glm::dvec3(-1, 1, 3), 1e-12, "half a turn the other way");
    // A tilted up vector (y up, target off the axis): the whole camera turns about y.
    const scene::Camera t{.eye = {0, 0, 4}, .target = {1, 0, 0}, .up = {0, 1, 0}};
    const scene::Camera r = OrbitCamera::orbitedAbout(t, glm::dvec3(0), 90);  // about +y: z -> x, x -> -z
    expectNear(r.eye, glm::dvec3(4, 0, 0), 1e-12, "eye");
    expectNear(r.target, glm::dvec3(0, 0, -1), 1e-12, "target");
    // Turns compose, and a full turn (or 36 steps of 10 degrees) comes back.
    const scene::Camera a = OrbitCamera::orbitedAbout(OrbitCamera::orbitedAbout(c, centre, 30), centre, 60);
    expectNear(a.eye, q.eye, 1e-12, "30 + 60 = 90");
    scene::Camera s = c;
    for (int i = 0; i < 36; ++i) s = OrbitCamera::orbitedAbout(s, centre, 10);
    expectNear(s.eye, c.eye, 1e-12, "36 x 10 degrees");
    expectNear(s.target, c.target, 1e-12, "36 x 10 degrees");
}
