#include "session/orbit_camera.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "session/setting_table.h"

namespace amrvk::session {

namespace {

constexpr double kMaxElevation = 89.0 * M_PI / 180.0;

glm::dvec3 unitAxis(int k) { return glm::dvec3(k == 0, k == 1, k == 2); }

// (a, b, u) axes of the orbit frame for a world up axis: azimuth turns in the plane of a and b.
void frameAxes(int up, glm::dvec3& a, glm::dvec3& b, glm::dvec3& u) {
    u = unitAxis(up);
    a = unitAxis((up + 1) % 3);
    b = unitAxis((up + 2) % 3);
}

// A camera as orbit parameters around its target (derived each time: the camera is the state).
struct Orbit {
    glm::dvec3 target{0.0};
    double distance = 1, azimuth = 0, elevation = 0;  // radians; elevation within +-89 degrees
    int up = 2;
};

Orbit orbitOf(const scene::Camera& c) {
    const glm::dvec3 offset = c.eye - c.target;
    AMRVK_CHECK(glm::length(offset) > 0, "camera: eye and target coincide");
    Orbit o;
    o.up = OrbitCamera::upAxis(c);
    o.target = c.target;
    o.distance = glm::length(offset);
    glm::dvec3 a, b, u;
    frameAxes(o.up, a, b, u);
    const glm::dvec3 d = offset / o.distance;
    o.elevation = std::clamp(std::asin(std::clamp(glm::dot(d, u), -1.0, 1.0)), -kMaxElevation, kMaxElevation);
    o.azimuth = std::atan2(glm::dot(d, b), glm::dot(d, a));
    return o;
}

void setOrbit(scene::Camera& c, const Orbit& o) {
    glm::dvec3 a, b, u;
    frameAxes(o.up, a, b, u);
    const double ce = std::cos(o.elevation);
    const glm::dvec3 d =
        glm::normalize(a * (ce * std::cos(o.azimuth)) + b * (ce * std::sin(o.azimuth)) + u * std::sin(o.elevation));
    c.target = o.target;
    c.eye = o.target + d * o.distance;
    c.up = u;
}

}  // namespace

OrbitCamera::OrbitCamera(glm::dvec3 worldLo, glm::dvec3 worldHi) : mLo(worldLo), mHi(worldHi) {}

scene::Camera OrbitCamera::framing(double fov, int upAxis) const {
    AMRVK_CHECK(upAxis >= 0 && upAxis <= 2, "up axis ", upAxis, " is not 0 (x), 1 (y) or 2 (z)");
    // defaultCamera's three-quarter view (z up); its direction components are taken in the orbit
    // frame of the chosen up axis, so every up axis gets the same kind of view.
    scene::Camera c = scene::defaultCamera(mLo, mHi, fov);
    setFov(c, fov);
    const glm::dvec3 d = glm::normalize(c.eye - c.target);
    Orbit o;
    o.target = c.target;
    o.distance = glm::length(c.eye - c.target);
    o.azimuth = std::atan2(d.y, d.x);
    o.elevation = std::asin(std::clamp(d.z, -1.0, 1.0));
    o.up = upAxis;
    setOrbit(c, o);
    return c;
}

void OrbitCamera::reset(scene::Camera& c) const { c = framing(c.fovYDegrees, upAxis(c)); }

void OrbitCamera::orbit(scene::Camera& c, double dx, double dy, double height) const {
    Orbit o = orbitOf(c);
    const double perPixel = M_PI / std::max(height, 1.0);
    o.azimuth -= dx * perPixel;
    o.elevation = std::clamp(o.elevation + dy * perPixel, -kMaxElevation, kMaxElevation);
    setOrbit(c, o);
}

void OrbitCamera::pan(scene::Camera& c, double dx, double dy, double height) const {
    Orbit o = orbitOf(c);
    setOrbit(c, o);  // up snapped, elevation clamped: the frame the drag moves in
    const glm::dvec3 forward = glm::normalize(c.target - c.eye);
    const glm::dvec3 right = glm::normalize(glm::cross(forward, c.up));
    const glm::dvec3 up = glm::cross(right, forward);
    // World units per pixel at the target's depth.
    const double perPixel = 2.0 * o.distance * std::tan(glm::radians(c.fovYDegrees) * 0.5) / std::max(height, 1.0);
    o.target += (-dx * right + dy * up) * perPixel;
    setOrbit(c, o);
}

void OrbitCamera::zoom(scene::Camera& c, double steps) const {
    Orbit o = orbitOf(c);
    const double radius = std::max(0.5 * glm::length(mHi - mLo), 1e-300);
    o.distance = std::clamp(o.distance * std::pow(0.9, steps), 1e-3 * radius, 100.0 * radius);
    setOrbit(c, o);
}

scene::Camera OrbitCamera::orbitedAbout(const scene::Camera& c, glm::dvec3 centre, double degrees) {
    AMRVK_CHECK(glm::length(c.up) > 0, "camera: the up vector is zero");
    const glm::dvec3 k = glm::normalize(c.up);
    const double angle = degrees * M_PI / 180.0, cs = std::cos(angle), sn = std::sin(angle);
    // Rodrigues' rotation of v about the unit axis k.
    auto rotate = [&](glm::dvec3 v) { return v * cs + glm::cross(k, v) * sn + k * glm::dot(k, v) * (1.0 - cs); };
    scene::Camera out = c;
    out.eye = centre + rotate(c.eye - centre);
    out.target = centre + rotate(c.target - centre);
    out.up = rotate(c.up);
    return out;
}

void OrbitCamera::setFov(scene::Camera& c, double fov) {
    checkSetting(settingForOption("--fov"), fov, "field of view");
    c.fovYDegrees = fov;
}

void OrbitCamera::setUpAxis(scene::Camera& c, int axis) {
    AMRVK_CHECK(axis >= 0 && axis <= 2, "up axis ", axis, " is not 0 (x), 1 (y) or 2 (z)");
    scene::Camera turned = c;
    turned.up = unitAxis(axis);
    setOrbit(c, orbitOf(turned));
}

int OrbitCamera::upAxis(const scene::Camera& c) {
    int up = 0;
    for (int k = 1; k < 3; ++k)
        if (std::abs(c.up[k]) > std::abs(c.up[up])) up = k;
    return up;
}

}  // namespace amrvk::session
