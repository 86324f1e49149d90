// The crop box's handles (viewer/logic/cut_handles.h): projection agrees with the renderer's camera ray
// through the projected pixel (the ray passes through the point), picking takes the nearest handle
// within the radius, and a drag moves the face as far as the pointer moved along the face normal's
// screen direction, measured on an axis-aligned camera where the answer is known in closed form.
#include "viewer/logic/cut_handles.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace amrvk;
using viewer::CutHandles;

namespace {

scene::Camera obliqueCamera() {
    scene::Camera c;
    c.eye = {3.0, -2.0, 2.5};
    c.target = {0.5, 0.4, 0.45};
    c.up = {0.0, 0.0, 1.0};
    c.fovYDegrees = 35.0;
    return c;
}

}  // namespace

TEST(CutHandles, ProjectionIsThePixelWhoseRayPassesThroughThePoint) {
    const scene::Camera cam = obliqueCamera();
    const int w = 320, h = 200;
    const scene::RayBasis rb = scene::makeRayBasis(cam, w, h, amr::Transform{});
    for (const glm::dvec3 p : {glm::dvec3(0.5, 0.4, 0.45), glm::dvec3(0, 0, 0), glm::dvec3(1, 1, 1), glm::dvec3(0.2, 0.9, 0.1)}) {
        const auto px = CutHandles::project(cam, w, h, p);
        ASSERT_TRUE(px.has_value());
        const glm::dvec3 d = glm::normalize(rb.dir00 + px->x * rb.du + px->y * rb.dv);
        const glm::dvec3 toPoint = glm::normalize(p - rb.eye);
        EXPECT_NEAR(glm::length(glm::cross(d, toPoint)), 0.0, 1e-12) << p.x << " " << p.y << " " << p.z;
    }
    // The target is the picture's centre; a point behind the eye has no projection.
    const auto centre = CutHandles::project(cam, w, h, cam.target);
    EXPECT_NEAR(centre->x, w / 2.0, 1e-9);
    EXPECT_NEAR(centre->y, h / 2.0, 1e-9);
    EXPECT_FALSE(CutHandles::project(cam, w, h, cam.eye + (cam.eye - cam.target)).has_value());
}

TEST(CutHandles, EdgesAreTheTwelveEdgesOfTheBox) {
    const scene::CropBox box{{0, 0, 0}, {1, 2, 3}};
    double total = 0;
    for (const auto& e : CutHandles::edges(box)) {
        const glm::dvec3 d = glm::abs(e[1] - e[0]);
        EXPECT_EQ((d.x > 0) + (d.y > 0) + (d.z > 0), 1) << "an edge runs along one axis";
        total += d.x + d.y + d.z;
    }
    EXPECT_DOUBLE_EQ(total, 4.0 * (1 + 2 + 3));
}

TEST(CutHandles, PickTakesTheNearestHandleWithinTheRadius) {
    const scene::Camera cam = obliqueCamera();
    const scene::CropBox box{{0, 0, 0}, {1, 1, 0.9}};
    for (int f = 0; f < 6; ++f) {
        const auto p = CutHandles::project(cam, 320, 200, CutHandles::faceCentre(box, f));
        ASSERT_TRUE(p.has_value());
        EXPECT_EQ(CutHandles::pick(cam, 320, 200, box, *p + glm::dvec2(1.0, -1.0), 8.0), f);
    }
    EXPECT_EQ(CutHandles::pick(cam, 320, 200, box, {-50.0, -50.0}, 8.0), -1);
}

TEST(CutHandles, DragMovesTheFaceByThePointersMotionAlongItsNormal) {
    // Looking down -y at the box from far away with a narrow field of view: x maps to picture x
    // with a known scale, z to picture -y; the y faces point at the eye.
    scene::Camera cam;
    cam.eye = {0.5, -20.0, 0.5};
    cam.target = {0.5, 0.5, 0.5};
    cam.up = {0.0, 0.0, 1.0};
    cam.fovYDegrees = 10.0;
    const int w = 400, h = 400;
    const scene::CropBox box{{0.2, 0.2, 0.2}, {0.8, 0.8, 0.8}};
    // Pixels per world unit at the upper x face (distance 20.8 - ... along the view axis).
    const double depth = 0.5 - (-20.0) + 0.0;  // the face centre is at y = 0.5
    const double pixelsPerUnit = (h / 2.0) / (depth * std::tan(glm::radians(5.0)));
    const glm::dvec3 lo(0.0), hi(1.0);
    scene::CropBox out = CutHandles::drag(cam, w, h, box, 1, {10.0, 3.0}, lo, hi, 1e-3);  // upper x face, 10 px right
    EXPECT_NEAR(out.hi.x, 0.8 + 10.0 / pixelsPerUnit, 1e-6);
    EXPECT_EQ(out.lo, box.lo);
    EXPECT_EQ(out.hi.y, box.hi.y);
    out = CutHandles::drag(cam, w, h, box, 4, {0.0, 20.0}, lo, hi, 1e-3);  // lower z face, 20 px down
    EXPECT_NEAR(out.lo.z, 0.2 - 20.0 / pixelsPerUnit, 1e-6);
    // Clamped at the data's bounds and short of the opposite face.
    out = CutHandles::drag(cam, w, h, box, 1, {1e6, 0.0}, lo, hi, 1e-3);
    EXPECT_EQ(out.hi.x, 1.0);
    out = CutHandles::drag(cam, w, h, box, 1, {-1e6, 0.0}, lo, hi, 1e-3);
    EXPECT_NEAR(out.hi.x, 0.2 + 1e-3, 1e-12);
    // A face whose normal points at the eye does not move.
    out = CutHandles::drag(cam, w, h, box, 2, {30.0, 30.0}, lo, hi, 1e-3);
    EXPECT_NEAR(out.lo.y, box.lo.y, 1e-9);
}
