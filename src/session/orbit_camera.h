#pragma once
// Orbit / pan / zoom around a target, the camera control of the viewer (ANARI-viewer style: left
// drag orbits, right drag or the wheel zooms, middle or shift drag pans), as edits of a
// scene::Camera: the caller's camera (the viewer's session) is the one copy of the view; this
// class holds only the data's box, for the framing view and the zoom limits. Window-free: mouse
// motion arrives in pixels with the viewport height, keys as steps. World space throughout. The
// up axis is the world axis nearest to the camera's up vector (+x, +y or +z); an edit snaps the up
// vector to it and keeps the elevation within +-89 degrees of the horizon.
#include <glm/glm.hpp>

#include "scene/camera.h"

namespace amrvk::session {

class OrbitCamera {
public:
    // The world box [lo, hi] of the data.
    OrbitCamera(glm::dvec3 worldLo, glm::dvec3 worldHi);

    // The default three-quarter view of the box with `upAxis` (0 x, 1 y, 2 z): scene::defaultCamera
    // for z, the same kind of view for the others.
    scene::Camera framing(double fovYDegrees = 40.0, int upAxis = 2) const;
    // The framing view keeping c's field of view and up axis (key R).
    void reset(scene::Camera& c) const;

    // A drag of (dx, dy) pixels in a viewport `height` pixels tall: a full height turns 180 degrees.
    void orbit(scene::Camera& c, double dxPixels, double dyPixels, double viewportHeight) const;
    // Moves target and eye in the view plane so the point under the cursor follows it.
    void pan(scene::Camera& c, double dxPixels, double dyPixels, double viewportHeight) const;
    // steps > 0 moves closer (each step 10 %), within 1/1000 to 100 radii of the box.
    void zoom(scene::Camera& c, double steps) const;

    // c turned rigidly by `degrees` about the line through `centre` along c's up vector (eye,
    // target and up rotated alike; right-handed: counter-clockwise seen from above): the camera of
    // a frame of `render --orbit` (session/series.h). Distances to the centre are kept.
    static scene::Camera orbitedAbout(const scene::Camera& c, glm::dvec3 centre, double degrees);

    static void setFov(scene::Camera& c, double fovYDegrees);  // (0, 180) exclusive; throws otherwise
    static void setUpAxis(scene::Camera& c, int axis);         // 0, 1 or 2; keeps the view direction where it can
    static int upAxis(const scene::Camera& c);                 // the axis nearest to c.up

private:
    glm::dvec3 mLo, mHi;
};

}  // namespace amrvk::session
