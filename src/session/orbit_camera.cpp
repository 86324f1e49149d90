#include "session/orbit_camera.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace amrvk::session {

namespace {

constexpr double kMaxElevation = 89.0 * M_PI / 180.0;

glm::dvec3 unitAxis(int k) { return glm::dvec3(k == 0, k == 1, k == 2); }

// (right, forward, up) axes of the orbit frame for a world up axis: azimuth turns in the plane of
// the first two.
void frameAxes(int up, glm::dvec3& a, glm::dvec3& b, glm::dvec3& u) {
    u = unitAxis(up);
    a = unitAxis((up + 1) % 3);
    b = unitAxis((up + 2) % 3);
}

}  // namespace

OrbitCamera::OrbitCamera(glm::dvec3 worldLo, glm::dvec3 worldHi, double fovYDegrees, int upAxis)
    : mLo(worldLo), mHi(worldHi) {
    setFov(fovYDegrees);
    AMRVK_CHECK(upAxis >= 0 && upAxis <= 2, "up axis ", upAxis, " is not 0 (x), 1 (y) or 2 (z)");
    mUp = upAxis;
    frame();
}

void OrbitCamera::frame() {
    // defaultCamera's three-quarter view (z up); its direction components are taken in the orbit
    // frame of the chosen up axis, so every up axis gets the same kind of view.
    const scene::Camera c = scene::defaultCamera(mLo, mHi, mFov);
    mTarget = c.target;
    mDistance = glm::length(c.eye - c.target);
    const glm::dvec3 d = glm::normalize(c.eye - c.target);
    mAzimuth = std::atan2(d.y, d.x);
    mElevation = std::asin(std::clamp(d.z, -1.0, 1.0));
}

glm::dvec3 OrbitCamera::direction() const {
    glm::dvec3 a, b, u;
    frameAxes(mUp, a, b, u);
    const double c = std::cos(mElevation);
    return glm::normalize(a * (c * std::cos(mAzimuth)) + b * (c * std::sin(mAzimuth)) + u * std::sin(mElevation));
}

scene::Camera OrbitCamera::camera() const {
    scene::Camera c;
    c.target = mTarget;
    c.eye = mTarget + direction() * mDistance;
    c.up = unitAxis(mUp);
    c.fovYDegrees = mFov;
    return c;
}

void OrbitCamera::setCamera(const scene::Camera& camera) {
    const glm::dvec3 offset = camera.eye - camera.target;
    AMRVK_CHECK(glm::length(offset) > 0, "camera: eye and target coincide");
    setFov(camera.fovYDegrees);
    int up = 0;
    for (int k = 1; k < 3; ++k)
        if (std::abs(camera.up[k]) > std::abs(camera.up[up])) up = k;
    mUp = up;
    mTarget = camera.target;
    mDistance = glm::length(offset);
    glm::dvec3 a, b, u;
    frameAxes(mUp, a, b, u);
    const glm::dvec3 d = offset / mDistance;
    mElevation = std::clamp(std::asin(std::clamp(glm::dot(d, u), -1.0, 1.0)), -kMaxElevation, kMaxElevation);
    mAzimuth = std::atan2(glm::dot(d, b), glm::dot(d, a));
}

void OrbitCamera::orbit(double dx, double dy, double height) {
    const double perPixel = M_PI / std::max(height, 1.0);
    mAzimuth -= dx * perPixel;
    mElevation = std::clamp(mElevation + dy * perPixel, -kMaxElevation, kMaxElevation);
}

void OrbitCamera::pan(double dx, double dy, double height) {
    const scene::Camera c = camera();
    const glm::dvec3 forward = glm::normalize(c.target - c.eye);
    const glm::dvec3 right = glm::normalize(glm::cross(forward, c.up));
    const glm::dvec3 up = glm::cross(right, forward);
    // World units per pixel at the target's depth.
    const double perPixel = 2.0 * mDistance * std::tan(glm::radians(mFov) * 0.5) / std::max(height, 1.0);
    mTarget += (-dx * right + dy * up) * perPixel;
}

void OrbitCamera::zoom(double steps) {
    const double radius = std::max(0.5 * glm::length(mHi - mLo), 1e-300);
    mDistance = std::clamp(mDistance * std::pow(0.9, steps), 1e-3 * radius, 100.0 * radius);
}

void OrbitCamera::setFov(double fov) {
    AMRVK_CHECK(fov > 0 && fov < 180, "field of view ", fov, " degrees is outside (0, 180)");
    mFov = fov;
}

void OrbitCamera::setUpAxis(int axis) {
    AMRVK_CHECK(axis >= 0 && axis <= 2, "up axis ", axis, " is not 0 (x), 1 (y) or 2 (z)");
    scene::Camera c = camera();
    c.up = unitAxis(axis);
    setCamera(c);
}

void OrbitCamera::reset() { frame(); }

}  // namespace amrvk::session
