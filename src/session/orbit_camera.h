#pragma once
// Orbit / pan / zoom around a target, the camera control of the viewer (ANARI-viewer style: left
// drag orbits, right drag or the wheel zooms, middle or shift drag pans). Window-free: mouse
// motion arrives in pixels with the viewport height, keys as steps. World space throughout; the
// up axis is one of +x, +y, +z (default +z, the data convention of amrvk's default camera).
#include <glm/glm.hpp>

#include "scene/camera.h"

namespace amrvk::session {

class OrbitCamera {
public:
    // Frames the world box [lo, hi] from the default three-quarter view with `upAxis` (0 x, 1 y, 2 z).
    OrbitCamera(glm::dvec3 worldLo, glm::dvec3 worldHi, double fovYDegrees = 40.0, int upAxis = 2);

    // Takes over an explicit camera (--camera, a session): target, distance and angles from it;
    // its up vector is snapped to the nearest axis. The bounds stay for reset and zoom limits.
    void setCamera(const scene::Camera& camera);
    scene::Camera camera() const;

    // A drag of (dx, dy) pixels in a viewport `height` pixels tall: a full height turns 180 degrees;
    // elevation stays within +-89 degrees of the horizon.
    void orbit(double dxPixels, double dyPixels, double viewportHeight);
    // Moves the target in the view plane so the point under the cursor follows it.
    void pan(double dxPixels, double dyPixels, double viewportHeight);
    // steps > 0 moves closer (each step 10 %), within 1/1000 to 100 radii of the bounds.
    void zoom(double steps);
    void setFov(double fovYDegrees);  // (0, 180) exclusive; throws otherwise
    void setUpAxis(int axis);         // 0, 1 or 2; keeps the view direction where it can
    void reset();                     // the framing view of the constructor (keeps fov and up axis)

    glm::dvec3 target() const { return mTarget; }
    double distance() const { return mDistance; }
    double fovYDegrees() const { return mFov; }
    int upAxis() const { return mUp; }

private:
    glm::dvec3 direction() const;  // unit vector from the target towards the eye
    void frame();

    glm::dvec3 mLo, mHi;
    glm::dvec3 mTarget{0.0};
    double mDistance = 1;
    double mAzimuth = 0, mElevation = 0;  // radians, around the up axis / above its plane
    double mFov = 40;
    int mUp = 2;
};

}  // namespace amrvk::session
