#include "session/camera_path.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "scene/limits.h"

namespace amrvk::session {

namespace {

bool finite(glm::dvec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// v turned by `angle` radians about the unit axis k (Rodrigues; right-handed).
glm::dvec3 rotate(glm::dvec3 v, glm::dvec3 k, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return v * c + glm::cross(k, v) * s + k * glm::dot(k, v) * (1 - c);
}

// The turn that takes unit vector a towards unit vector b along the great circle: its unit axis
// and angle (radians, [0, pi]). Opposite vectors have no such circle: `fallbackAxis` (a unit
// vector perpendicular to a) is taken, with the angle pi.
struct Turn {
    glm::dvec3 axis{0.0, 0.0, 1.0};
    double angle = 0;
};
Turn turnBetween(glm::dvec3 a, glm::dvec3 b, glm::dvec3 fallbackAxis) {
    const glm::dvec3 c = glm::cross(a, b);
    const double sine = glm::length(c), cosine = glm::dot(a, b);
    if (sine > 1e-12) return {c / sine, std::atan2(sine, cosine)};
    if (cosine > 0) return {};  // the same direction: no turn
    return {fallbackAxis, M_PI};
}

// A unit vector perpendicular to unit vector d, as near to `hint` as can be; when hint is parallel
// to d, the axis least aligned with d.
glm::dvec3 perpendicularTo(glm::dvec3 d, glm::dvec3 hint) {
    glm::dvec3 p = hint - glm::dot(hint, d) * d;
    if (glm::length(p) < 1e-9) {
        const glm::dvec3 m = glm::abs(d);
        const glm::dvec3 axis = m.x <= m.y && m.x <= m.z ? glm::dvec3(1, 0, 0)
                                : m.y <= m.z             ? glm::dvec3(0, 1, 0)
                                                         : glm::dvec3(0, 0, 1);
        p = axis - glm::dot(axis, d) * d;
    }
    return glm::normalize(p);
}

const Keyframe* keyAt(const std::vector<Keyframe>& keys, uint32_t frame) {
    const auto it =
        std::lower_bound(keys.begin(), keys.end(), frame, [](const Keyframe& k, uint32_t f) { return k.frame < f; });
    return it != keys.end() && it->frame == frame ? &*it : nullptr;
}

}  // namespace

void checkKeyframeCamera(uint32_t frame, const scene::Camera& c) {
    AMRVK_CHECK(finite(c.eye) && finite(c.target) && finite(c.up), "camera path keyframe at frame ", frame,
                ": eye, target and up must be finite");
    AMRVK_CHECK(scene::validFov(c.fovYDegrees), "camera path keyframe at frame ", frame, ": fovY ", c.fovYDegrees,
                " is outside (0, ", scene::kMaxFovDegrees, ")");
    const glm::dvec3 forward = c.target - c.eye;
    AMRVK_CHECK(glm::length(forward) > 0, "camera path keyframe at frame ", frame, ": eye and target coincide");
    AMRVK_CHECK(glm::length(c.up) > 0 && glm::length(glm::cross(glm::normalize(forward), glm::normalize(c.up))) > 1e-9,
                "camera path keyframe at frame ", frame, ": up is parallel to the view direction (or zero)");
}

double easeInOut(double u) {
    u = std::clamp(u, 0.0, 1.0);
    return u * u * (3 - 2 * u);
}

scene::Camera interpolateCamera(const scene::Camera& a, const scene::Camera& b, double s) {
    if (s <= 0) return a;
    if (s >= 1) return b;
    scene::Camera c;
    c.target = a.target + (b.target - a.target) * s;
    // The eye about the target: direction turned along the great circle, distance log-linear.
    const double ra = glm::length(a.eye - a.target), rb = glm::length(b.eye - b.target);
    const glm::dvec3 da = (a.eye - a.target) / ra, db = (b.eye - b.target) / rb;
    const glm::dvec3 ua = glm::normalize(a.up), ub = glm::normalize(b.up);
    const Turn eyeTurn = turnBetween(da, db, perpendicularTo(da, ua));  // opposite: about a's up
    const glm::dvec3 dir = rotate(da, eyeTurn.axis, s * eyeTurn.angle);
    c.eye = c.target + dir * std::exp(std::log(ra) + (std::log(rb) - std::log(ra)) * s);
    // Up: turned from a's to b's (opposite: about a's view), then perpendicular to the view.
    const Turn upTurn = turnBetween(ua, ub, perpendicularTo(ua, da));
    glm::dvec3 up = rotate(ua, upTurn.axis, s * upTurn.angle);
    up -= glm::dot(up, dir) * dir;
    if (glm::length(up) < 1e-9) {  // the turned up lies along the view: a's up carried by the view's turn
        up = rotate(ua, eyeTurn.axis, s * eyeTurn.angle);
        up -= glm::dot(up, dir) * dir;  // a's up is not along da, so this one is not along dir
    }
    c.up = glm::normalize(up);
    c.fovYDegrees = a.fovYDegrees + (b.fovYDegrees - a.fovYDegrees) * s;
    return c;
}

uint32_t stepOfFrame(uint32_t frame, uint32_t frames, uint32_t steps) {
    AMRVK_CHECK(frame < frames, "internal: frame ", frame, " of a ", frames, "-frame movie");
    return uint32_t(uint64_t(frame) * steps / frames);
}

bool CameraPath::hasKeyframe(uint32_t frame) const { return keyAt(mKeys, frame) != nullptr; }

void CameraPath::add(uint32_t frame, const scene::Camera& camera) {
    AMRVK_CHECK(frame < kMaxPathFrames, "camera path: frame ", frame, " is outside [0, ", kMaxPathFrames - 1, "]");
    AMRVK_CHECK(!hasKeyframe(frame), "camera path: frame ", frame, " already has a keyframe (move or delete it first)");
    AMRVK_CHECK(mKeys.size() < kMaxKeyframes, "camera path: at most ", kMaxKeyframes, " keyframes");
    checkKeyframeCamera(frame, camera);
    const auto at =
        std::upper_bound(mKeys.begin(), mKeys.end(), frame, [](uint32_t f, const Keyframe& k) { return f < k.frame; });
    mKeys.insert(at, Keyframe{frame, camera});
}

void CameraPath::remove(uint32_t frame) {
    const Keyframe* k = keyAt(mKeys, frame);
    AMRVK_CHECK(k, "camera path: no keyframe at frame ", frame);
    mKeys.erase(mKeys.begin() + (k - mKeys.data()));
}

void CameraPath::move(uint32_t from, uint32_t to) {
    const Keyframe* k = keyAt(mKeys, from);
    AMRVK_CHECK(k, "camera path: no keyframe at frame ", from);
    if (from == to) return;
    AMRVK_CHECK(to < kMaxPathFrames, "camera path: frame ", to, " is outside [0, ", kMaxPathFrames - 1, "]");
    AMRVK_CHECK(!hasKeyframe(to), "camera path: frame ", to, " already has a keyframe (move or delete it first)");
    const scene::Camera camera = k->camera;
    remove(from);
    add(to, camera);
}

void CameraPath::setCamera(uint32_t frame, const scene::Camera& camera) {
    const Keyframe* k = keyAt(mKeys, frame);
    AMRVK_CHECK(k, "camera path: no keyframe at frame ", frame);
    checkKeyframeCamera(frame, camera);
    mKeys[size_t(k - mKeys.data())].camera = camera;
}

void CameraPath::setFps(double fps) {
    AMRVK_CHECK(std::isfinite(fps) && fps > 0 && fps <= kMaxPathFps, "camera path: fps ", fps, " is outside (0, ",
                kMaxPathFps, "]");
    mFps = fps;
}

scene::Camera CameraPath::cameraAt(double frame) const {
    AMRVK_CHECK(!mKeys.empty(), "camera path: no keyframes");
    AMRVK_CHECK(std::isfinite(frame), "camera path: frame ", frame, " is not finite");
    if (frame <= double(mKeys.front().frame)) return mKeys.front().camera;
    if (frame >= double(mKeys.back().frame)) return mKeys.back().camera;
    // The segment [a, b) holding the frame: b is the first keyframe after it.
    const auto b = std::upper_bound(mKeys.begin(), mKeys.end(), frame,
                                    [](double f, const Keyframe& k) { return f < double(k.frame); });
    const auto a = std::prev(b);
    if (frame == double(a->frame)) return a->camera;
    const double u = (frame - double(a->frame)) / double(b->frame - a->frame);
    return interpolateCamera(a->camera, b->camera, easeInOut(u));
}

}  // namespace amrvk::session
