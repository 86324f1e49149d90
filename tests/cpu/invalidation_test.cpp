// The invalidation rule: which edit redoes what. The renderer follows it (tests/gpu/renderer_gpu_test
// checks that it really does); here the rule itself and the detection of changes between settings.
#include <gtest/gtest.h>

#include "scene/invalidation.h"

using namespace amrvk;
using scene::Change;
using scene::ChangeSet;

TEST(Invalidation, EachSettingMapsToExactlyItsChange) {
    const scene::RenderSettings base;
    EXPECT_TRUE(scene::settingsChanges(base, base).empty());
    auto expectOnly = [&](const scene::RenderSettings& s, Change c, const char* what) {
        const ChangeSet got = scene::settingsChanges(base, s);
        EXPECT_EQ(got.bits, uint32_t(c)) << what << ": " << scene::describe(got);
        EXPECT_EQ(scene::settingsChanges(s, base).bits, uint32_t(c)) << what << " (reverse)";
    };
    scene::RenderSettings s = base;
    s.camera.eye.x += 1;
    expectOnly(s, Change::Camera, "eye");
    s = base;
    s.camera.fovYDegrees = 30;
    expectOnly(s, Change::Camera, "fov");
    s = base;
    s.camera.up = {1, 0, 0};
    expectOnly(s, Change::Camera, "up");
    s = base;
    s.height = 17;
    expectOnly(s, Change::ImageSize, "height");
    s = base;
    s.seed = 9;
    expectOnly(s, Change::Seed, "seed");
    s = base;
    s.mode = scene::Mode::Ae;
    expectOnly(s, Change::Mode, "mode");
    s = base;
    s.ambient = glm::dvec3(0.5);
    expectOnly(s, Change::Lighting, "ambient");
    s = base;
    s.background = glm::dvec3(1.0);  // equal to the ambient, but now explicit
    expectOnly(s, Change::Lighting, "background");
    s = base;
    s.lights.push_back({false, {0, 0, 1}, glm::dvec3(2)});
    expectOnly(s, Change::Lighting, "a light");
    scene::RenderSettings t = s;
    t.lights[0].radiance.g = 3;
    EXPECT_EQ(scene::settingsChanges(s, t).bits, uint32_t(Change::Lighting)) << "light radiance";
    s = base;
    s.densityScale = 2;
    expectOnly(s, Change::Medium, "density");
    s = base;
    s.g = 0.5;
    expectOnly(s, Change::Medium, "g");
    s = base;
    s.maxTrackingSteps = 10;
    expectOnly(s, Change::Medium, "tracking cap");
    s = base;
    s.cut.crop = scene::CropBox{glm::dvec3(0.0), glm::dvec3(1.0)};
    expectOnly(s, Change::Medium, "a crop box");
    s = base;
    s.cut.clips.push_back({glm::dvec3(0.5), {0.0, 0.0, 1.0}});
    expectOnly(s, Change::Medium, "a clip plane");
    s = base;
    s.dvrStep = 0.25;
    expectOnly(s, Change::DvrOptions, "dt");
    s = base;
    s.dvrShading = true;
    expectOnly(s, Change::DvrOptions, "dvr shading");
    s = base;
    s.camera.eye.x += 1;
    s.densityScale = 3;
    EXPECT_EQ(scene::describe(scene::settingsChanges(base, s)), "camera|medium");
}

TEST(Invalidation, OnlyWhatDependsOnAChangeIsRedone) {
    const scene::Invalidation none = scene::invalidatedBy(ChangeSet());
    EXPECT_FALSE(none.accumulation || none.viewParams || none.shadingParams || none.pipelines || none.majorants ||
                 none.deviceScene);

    const scene::Invalidation camera = scene::invalidatedBy(Change::Camera);
    EXPECT_TRUE(camera.accumulation && camera.viewParams);
    EXPECT_FALSE(camera.accumulationBuffer || camera.pipelines || camera.majorants || camera.culling ||
                 camera.kdTree || camera.deviceScene);

    const scene::Invalidation size = scene::invalidatedBy(Change::ImageSize);
    EXPECT_TRUE(size.accumulation && size.accumulationBuffer && size.viewParams);
    EXPECT_FALSE(size.majorants || size.deviceScene || size.pipelines);

    for (Change c : {Change::Lighting, Change::Medium, Change::DvrOptions}) {
        const scene::Invalidation v = scene::invalidatedBy(c);
        EXPECT_TRUE(v.accumulation && v.shadingParams) << scene::describe(c);
        EXPECT_FALSE(v.viewParams || v.majorants || v.deviceScene || v.pipelines) << scene::describe(c);
    }
    const scene::Invalidation mode = scene::invalidatedBy(Change::Mode);
    EXPECT_TRUE(mode.accumulation);
    EXPECT_FALSE(mode.majorants || mode.deviceScene || mode.pipelines) << "a mode picks a pipeline, drops none";

    const scene::Invalidation tf = scene::invalidatedBy(Change::TransferFunction);
    EXPECT_TRUE(tf.accumulation && tf.majorants && tf.culling && tf.kdTree);
    EXPECT_FALSE(tf.deviceScene || tf.pipelines || tf.viewParams || tf.shadingParams);

    const scene::Invalidation structure = scene::invalidatedBy(Change::Structure);
    EXPECT_TRUE(structure.accumulation && structure.deviceScene && structure.majorants && structure.culling &&
                structure.kdTree && structure.pipelines);
    EXPECT_FALSE(structure.viewParams || structure.accumulationBuffer);

    const scene::Invalidation shaders = scene::invalidatedBy(Change::Shaders);
    EXPECT_TRUE(shaders.accumulation && shaders.pipelines);
    EXPECT_FALSE(shaders.majorants || shaders.deviceScene);

    // The control extinction makes or drops the minorants and redoes the majorant pass that writes
    // them, and nothing else of the structures.
    const scene::Invalidation control = scene::invalidatedBy(Change::Control);
    EXPECT_TRUE(control.accumulation && control.minorants && control.majorants);
    EXPECT_FALSE(control.deviceScene || control.pipelines || control.viewParams);
    scene::RenderSettings a, b;
    b.controlExtinction = scene::ControlExtinction::Minorant;
    EXPECT_EQ(scene::describe(scene::settingsChanges(a, b)), "control extinction");

    const scene::Invalidation both = scene::invalidatedBy(ChangeSet(Change::Camera) | Change::TransferFunction);
    EXPECT_TRUE(both.viewParams && both.majorants);
    EXPECT_EQ(scene::describe(ChangeSet(Change::Camera) | Change::TransferFunction), "camera|transfer function");
}
