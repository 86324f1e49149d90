// Camera paths (session/camera_path.h): keyframes kept sorted, one a frame, added, moved and
// deleted with one-line errors; the camera equals each keyframe exactly at its frame; the easing
// stops the camera at every keyframe (finite differences, against an uneased path that does not);
// a half orbit keeps the eye's distance to the target where a straight line from eye to eye passes
// through the target (the same check refuses it); distances interpolate geometrically; degenerate
// input is refused or falls back without NaN; the frame-to-step rule; the session's
// "cameraPath" round trip and its one-line errors.
#include "session/camera_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>
#include <random>

#include "core/error.h"
#include "scene/tf_presets.h"
#include "session/session.h"
#include "test_data.h"

using namespace amrvk;
using session::CameraPath;

namespace {

scene::Camera cam(glm::dvec3 eye, glm::dvec3 target, glm::dvec3 up = {0, 0, 1}, double fov = 40) {
    return scene::Camera{eye, target, up, fov};
}

bool finite(const scene::Camera& c) {
    for (const glm::dvec3& v : {c.eye, c.target, c.up})
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) return false;
    return std::isfinite(c.fovYDegrees);
}

// The up vector as the picture uses it: the unit vector of up perpendicular to the view (a
// keyframe's up is kept as given; between keyframes it is that vector).
glm::dvec3 viewUp(const scene::Camera& c) {
    const glm::dvec3 v = glm::normalize(c.target - c.eye);
    return glm::normalize(c.up - glm::dot(c.up, v) * v);
}

// How far the camera moves per frame around path time f: eye, target and up (as the picture uses
// it) changes, fov in degrees.
double speed(const std::function<scene::Camera(double)>& at, double f0, double f1) {
    const scene::Camera a = at(f0), b = at(f1);
    const double d = glm::length(b.eye - a.eye) + glm::length(b.target - a.target) +
                     glm::length(viewUp(b) - viewUp(a)) + std::abs(b.fovYDegrees - a.fovYDegrees);
    return d / std::abs(f1 - f0);
}

// The largest relative departure of the eye's distance to the target from `r` over the frames
// [0, last] in steps of 1/8 frame.
double worstDistanceError(const std::function<scene::Camera(double)>& at, double last, double r) {
    double worst = 0;
    for (double f = 0; f <= last; f += 0.125)
        worst = std::max(worst, std::abs(glm::length(at(f).eye - at(f).target) / r - 1));
    return worst;
}

CameraPath threeKeys() {
    CameraPath p;
    p.add(10, cam({0, -8, 2}, {1, 1, 1}, {0, 0, 1}, 50));
    p.add(0, cam({5, 0, 1}, {0, 0, 0}));
    p.add(4, cam({0, 3, 3}, {0.5, 0, 0}, {0, 1, 1}, 30));
    return p;
}

}  // namespace

TEST(CameraPath, KeyframesAreSortedOneAFrameAndEdited) {
    CameraPath p = threeKeys();
    ASSERT_EQ(p.keyframes().size(), 3u);
    EXPECT_EQ(p.keyframes()[0].frame, 0u);
    EXPECT_EQ(p.keyframes()[1].frame, 4u);
    EXPECT_EQ(p.keyframes()[2].frame, 10u);
    EXPECT_EQ(p.frameCount(), 11u);
    const scene::Camera fourth = p.keyframes()[1].camera;
    // Two keyframes at one frame: refused with one line naming it; the path is unchanged.
    const std::string taken = test::errorOf([&] { p.add(4, cam({1, 1, 1}, {0, 0, 0})); });
    EXPECT_NE(taken.find("frame 4 already has a keyframe"), std::string::npos) << taken;
    EXPECT_EQ(taken.find('\n'), std::string::npos);
    EXPECT_EQ(p.keyframes().size(), 3u);
    EXPECT_NE(test::errorOf([&] { p.move(4, 10); }).find("frame 10 already has a keyframe"), std::string::npos);
    // Move: the camera goes with it, the order follows.
    p.move(4, 12);
    EXPECT_EQ(p.keyframes()[1].frame, 10u);
    EXPECT_EQ(p.keyframes()[2].frame, 12u);
    EXPECT_EQ(p.keyframes()[2].camera, fourth);
    EXPECT_EQ(p.frameCount(), 13u);
    // Change a keyframe's camera; delete one.
    p.setCamera(12, cam({9, 9, 9}, {0, 0, 0}));
    EXPECT_EQ(p.cameraAt(12).eye, glm::dvec3(9, 9, 9));
    p.remove(12);
    EXPECT_EQ(p.frameCount(), 11u);
    EXPECT_NE(test::errorOf([&] { p.remove(12); }).find("no keyframe at frame 12"), std::string::npos);
    EXPECT_NE(test::errorOf([&] {
                  p.add(session::kMaxPathFrames, cam({1, 0, 0}, {0, 0, 0}));
              }).find("outside"),
              std::string::npos);
    EXPECT_NE(test::errorOf([&] { p.setFps(0); }).find("fps 0 is outside (0, 1000]"), std::string::npos);
}

TEST(CameraPath, AtEachKeyframeTheCameraIsTheKeyframe) {
    const CameraPath p = threeKeys();
    for (const session::Keyframe& k : p.keyframes()) EXPECT_EQ(p.cameraAt(k.frame), k.camera) << k.frame;
    // Between keyframes it is neither end (the path moves).
    EXPECT_NE(p.cameraAt(2).eye, p.keyframes()[0].camera.eye);
    EXPECT_NE(p.cameraAt(2).eye, p.keyframes()[1].camera.eye);
    // Outside the path: the nearest end's camera.
    EXPECT_EQ(p.cameraAt(-3.0), p.keyframes().front().camera);
    EXPECT_EQ(p.cameraAt(40.0), p.keyframes().back().camera);
}

TEST(CameraPath, EasingStopsTheCameraAtEveryKeyframe) {
    const CameraPath p = threeKeys();
    const auto eased = [&](double f) { return p.cameraAt(f); };
    // The same turns without easing (the parameter linear in time), to show the check's power.
    const auto uneased = [&](double f) {
        const auto& k = p.keyframes();
        const size_t i = f < k[1].frame ? 0 : 1;
        const double u = (f - k[i].frame) / double(k[i + 1].frame - k[i].frame);
        return session::interpolateCamera(k[i].camera, k[i + 1].camera, u);
    };
    // Speed at the keyframes over speed mid-segment, by one-sided differences: into the path at its
    // start, out of and into the middle keyframe, into the last.
    const auto stopRatio = [](const std::function<scene::Camera(double)>& at) {
        const double h = 1e-4;
        const double mid = speed(at, 2 - h, 2 + h);
        EXPECT_GT(mid, 0.1);
        return std::max({speed(at, 0, h), speed(at, 4 - h, 4), speed(at, 4, 4 + h), speed(at, 10 - h, 10)}) / mid;
    };
    // smoothstep: velocity 6u(1-u)/span, O(h) at the keyframes.
    EXPECT_LT(stopRatio(eased), 1e-3) << "the camera does not stop at a keyframe";
    EXPECT_GT(stopRatio(uneased), 0.2) << "the check would not see the easing missing";
}

TEST(CameraPath, AHalfOrbitKeepsTheDistanceToTheTarget) {
    const double r = 10;
    // Eye directions exactly opposite: turned about the up axis (the documented fallback).
    CameraPath half;
    half.add(0, cam({r, 0, 0}, {0, 0, 0}));
    half.add(12, cam({-r, 0, 0}, {0, 0, 0}));
    // 170 degrees: the great circle through the keyframes.
    CameraPath most;
    const double a = 170 * M_PI / 180;
    most.add(0, cam({r, 0, 2}, {0, 0, 2}));
    most.add(12, cam({r * std::cos(a), r * std::sin(a), 2}, {0, 0, 2}));
    for (const CameraPath* p : {&half, &most}) {
        EXPECT_LT(worstDistanceError([&](double f) { return p->cameraAt(f); }, 12, r), 1e-12);
        for (double f = 0; f <= 12; f += 0.5) {
            const scene::Camera c = p->cameraAt(f);
            EXPECT_NEAR(c.eye.z, c.target.z, 1e-9) << "the orbit leaves its plane at frame " << f;
            EXPECT_NEAR(glm::length(c.up), 1, 1e-12);
            EXPECT_NEAR(glm::dot(c.up, glm::normalize(c.target - c.eye)), 0, 1e-12);
        }
    }
    // Halfway round the half orbit the eye is a quarter turn from both ends.
    const glm::dvec3 mid = half.cameraAt(6).eye;
    EXPECT_NEAR(std::abs(mid.y), r, 1e-9);
    // A straight line from eye to eye (the same easing) passes through the data: the check refuses it.
    const auto lerp = [&](double f) {
        scene::Camera c = half.cameraAt(0);
        c.eye = glm::mix(half.keyframes()[0].camera.eye, half.keyframes()[1].camera.eye, session::easeInOut(f / 12));
        return c;
    };
    EXPECT_GT(worstDistanceError(lerp, 12, r), 0.99);
}

TEST(CameraPath, DistanceIsGeometricAndFovLinear) {
    CameraPath p;
    p.add(0, cam({1, 0, 0}, {0, 0, 0}, {0, 0, 1}, 20));
    p.add(2, cam({0, 100, 0}, {0, 0, 0}, {0, 0, 1}, 60));
    const scene::Camera c = p.cameraAt(1);  // eased parameter 0.5
    EXPECT_NEAR(glm::length(c.eye - c.target), 10, 1e-9);
    EXPECT_NEAR(c.fovYDegrees, 40, 1e-12);
    EXPECT_NEAR(glm::dot(glm::normalize(c.eye), glm::normalize(glm::dvec3(1, 1, 0))), 1, 1e-12);
    // The target moves linearly in the eased parameter.
    CameraPath t;
    t.add(0, cam({0, -5, 0}, {0, 0, 0}));
    t.add(4, cam({4, -5, 0}, {4, 0, 0}));
    EXPECT_NEAR(t.cameraAt(1).target.x, 4 * session::easeInOut(0.25), 1e-12);
}

TEST(CameraPath, DegenerateInputIsRefusedOrFallsBackWithoutNaN) {
    // One keyframe: a still of one frame.
    CameraPath one;
    one.add(0, cam({3, 0, 0}, {0, 0, 0}));
    EXPECT_EQ(one.frameCount(), 1u);
    EXPECT_EQ(one.cameraAt(0), one.keyframes()[0].camera);
    CameraPath p;
    const struct {
        scene::Camera camera;
        const char* fragment;
    } refused[] = {
        {cam({1, 1, 1}, {1, 1, 1}), "eye and target coincide"},
        {cam({0, 0, 5}, {0, 0, 0}, {0, 0, 1}), "up is parallel to the view direction"},
        {cam({1, 0, 0}, {0, 0, 0}, {0, 0, 0}), "up is parallel to the view direction (or zero)"},
        {cam({NAN, 0, 0}, {0, 0, 0}), "eye, target and up must be finite"},
        {cam({1, 0, 0}, {0, 0, 0}, {0, 0, 1}, 180), "fovY 180 is outside (0, 180)"},
    };
    for (const auto& c : refused) {
        const std::string e = test::errorOf([&] { p.add(7, c.camera); });
        EXPECT_NE(e.find(std::string("camera path keyframe at frame 7: ") + c.fragment), std::string::npos) << e;
        EXPECT_EQ(e.find('\n'), std::string::npos);
    }
    EXPECT_TRUE(p.empty());
    EXPECT_NE(test::errorOf([&] { (void)p.cameraAt(0); }).find("no keyframes"), std::string::npos);
    // The turned up vector meets the view direction halfway: a's up carried by the view's turn.
    const scene::Camera a = cam({1, 0, 0}, {0, 0, 0}, {0, 0, 1}), b = cam({0, 0, 1}, {0, 0, 0}, {1, 0, 0});
    // Opposite eye directions and opposite ups, and random keyframes: every camera finite, its up
    // a unit vector perpendicular to the view, its eye off the target.
    std::vector<std::pair<scene::Camera, scene::Camera>> pairs = {
        {a, b}, {cam({1, 0, 0}, {0, 0, 0}, {0, 0, 1}), cam({-1, 0, 0}, {0, 0, 0}, {0, 0, -1})}};
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    const auto v = [&] { return glm::dvec3(u(rng), u(rng), u(rng)); };
    while (pairs.size() < 200) {
        const scene::Camera c = cam(v() * 1e3, v(), v()), d = cam(v() * 1e-3, v() * 1e-3, v());
        try {
            session::checkKeyframeCamera(0, c);
            session::checkKeyframeCamera(1, d);
            pairs.emplace_back(c, d);
        } catch (const Error&) {
        }
    }
    for (const auto& [c, d] : pairs)
        for (double s = 0; s <= 1; s += 1.0 / 64) {
            const scene::Camera m = session::interpolateCamera(c, d, s);
            ASSERT_TRUE(finite(m)) << s;
            const glm::dvec3 view = glm::normalize(m.target - m.eye);
            EXPECT_GT(glm::length(m.eye - m.target), 0);
            if (s > 0 && s < 1) {
                EXPECT_NEAR(glm::length(m.up), 1, 1e-9);
                EXPECT_NEAR(glm::dot(m.up, view), 0, 1e-9) << s;
            }
        }
}

TEST(CameraPath, FramesShowTheStepsInOrder) {
    std::vector<uint32_t> steps;
    for (uint32_t k = 0; k < 6; ++k) steps.push_back(session::stepOfFrame(k, 6, 3));
    EXPECT_EQ(steps, (std::vector<uint32_t>{0, 0, 1, 1, 2, 2}));
    for (uint32_t k = 0; k < 5; ++k) EXPECT_EQ(session::stepOfFrame(k, 5, 5), k);
    EXPECT_EQ(session::stepOfFrame(4, 5, 1), 0u);
    EXPECT_EQ(session::stepOfFrame(99999, 100000, 100000), 99999u);  // no overflow (64-bit product)
}

TEST(CameraPath, SessionsKeepThePathAndNameBadValues) {
    session::Session s;
    s.input = "/data/x.cells";
    s.tf = scene::TfChannels::split(scene::makePreset("ramp", 0.0f, 1.0f));
    s.cameraPath = threeKeys();
    s.cameraPath.setFps(12.5);
    const std::string text = session::sessionJson(s);
    const session::Session t = session::parseSession(text, "/tmp/s.json");
    EXPECT_EQ(t.cameraPath, s.cameraPath);
    EXPECT_EQ(session::sessionJson(t), text);
    // No path: no key, the file as before.
    session::Session none = s;
    none.cameraPath = CameraPath();
    EXPECT_EQ(session::sessionJson(none).find("cameraPath"), std::string::npos);
    EXPECT_TRUE(session::parseSession(session::sessionJson(none), "/tmp/s.json").cameraPath.empty());
    auto with = [&](const std::string& from, const std::string& to) {
        std::string r = text;
        const size_t at = r.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        if (at != std::string::npos) r.replace(at, from.size(), to);
        return r;
    };
    const struct {
        std::string text;
        std::string fragment;
    } cases[] = {
        {with("\"frame\": 10", "\"frame\": 4"),
         "/tmp/s.json.cameraPath.keyframes[2].frame: 4 is another keyframe's frame"},
        {with("\"frame\": 10", "\"frame\": 1.5"),
         "/tmp/s.json.cameraPath.keyframes[2].frame: 1.5 is not an integer in [0, 99999]"},
        {with("\"frame\": 10", "\"frame\": 100000"), "keyframes[2].frame: 100000 is not an integer"},
        {with("\"fps\": 12.5", "\"fps\": 0"), "/tmp/s.json.cameraPath.fps: 0 is outside (0, 1000]"},
        {with("\"fps\": 12.5", "\"fps\": 12.5, \"loop\": true"), "/tmp/s.json.cameraPath.loop: unknown key"},
        {with("\"frame\": 4,", "\"frame\": 4, \"ease\": 1,"), "/tmp/s.json.cameraPath.keyframes[1].ease: unknown key"},
        {with("\"fovY\": 30.0", "\"fovY\": 190"), "/tmp/s.json.cameraPath.keyframes[1].camera.fovY"},
        {with("\"fovY\": 30.0", "\"fov\": 30"), "keyframes[1].camera.fov: unknown key"},
        {with("\"keyframes\": [", "\"keyframes\": [], \"x\": ["), "cameraPath.x: unknown key"},
    };
    for (const auto& c : cases) {
        const std::string e = test::errorOf([&] { session::parseSession(c.text, "/tmp/s.json"); });
        EXPECT_NE(e.find(c.fragment), std::string::npos) << "'" << c.fragment << "' not in: " << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    }
    // Edited as JSON: not an object, no keyframes, and a keyframe whose eye is its target.
    nlohmann::ordered_json j = nlohmann::ordered_json::parse(text);
    j["cameraPath"] = 5;
    const std::string five = test::errorOf([&] { session::parseSession(j.dump(), "/tmp/s.json"); });
    EXPECT_NE(five.find("/tmp/s.json.cameraPath: expected an object"), std::string::npos) << five;
    j = nlohmann::ordered_json::parse(text);
    j["cameraPath"]["keyframes"] = nlohmann::ordered_json::array();
    const std::string none0 = test::errorOf([&] { session::parseSession(j.dump(), "/tmp/s.json"); });
    EXPECT_NE(none0.find("/tmp/s.json.cameraPath.keyframes: no keyframes"), std::string::npos) << none0;
    j = nlohmann::ordered_json::parse(text);
    j["cameraPath"]["keyframes"][1]["camera"]["eye"] = j["cameraPath"]["keyframes"][1]["camera"]["target"];
    const std::string same = test::errorOf([&] { session::parseSession(j.dump(), "/tmp/s.json"); });
    EXPECT_NE(same.find("/tmp/s.json.cameraPath.keyframes[1].camera: camera path keyframe at frame 4: eye and target "
                        "coincide"),
              std::string::npos)
        << same;
}
