// What a session change means for the viewer's data (viewer/logic/data_change.*): only read.scale and
// read.logFloor are a rescale (read again, camera kept); another input, field or read option is
// refused with a reason naming it and both values; a TF refitted to the new field range keeps its
// shape (every node at the same relative position, checked against the hand-computed positions);
// on a new scale an unedited fitted preset is fitted again (its nodes at the logs of the linear
// ones: the same cells), every other TF keeps its shape.
#include "viewer/logic/data_change.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "model_fixtures.h"
#include "scene/tf_presets.h"
#include "viewer/logic/tf_editor.h"

using namespace amrvk;
using viewer::DataChange;

namespace {

session::Session shown() {
    session::Session s;
    s.input = "/data/enzo/DD0018/DD0018";
    s.field = "Density";
    return s;
}

}  // namespace

TEST(DataChange, OnlyTheScaleAndItsFloorAreARescale) {
    session::Session next = shown();
    EXPECT_EQ(viewer::dataChange(shown(), next).kind, DataChange::None);
    next.settings.densityScale = 7;  // not data
    next.settings.camera.eye = {1, 2, 3};
    EXPECT_EQ(viewer::dataChange(shown(), next).kind, DataChange::None);
    next.read.scale = amr::FieldScale::Log;
    EXPECT_EQ(viewer::dataChange(shown(), next).kind, DataChange::Rescale);
    session::Session logShown = shown();
    logShown.read.scale = amr::FieldScale::Log;
    session::Session floorOnly = logShown;
    floorOnly.read.logFloor = 1e-3;
    EXPECT_EQ(viewer::dataChange(logShown, floorOnly).kind, DataChange::Rescale);
    // On the linear scale the floor changes no value: nothing to read.
    session::Session linearFloor = shown();
    linearFloor.read.logFloor = 1e-3;
    EXPECT_EQ(viewer::dataChange(shown(), linearFloor).kind, DataChange::None);
    EXPECT_EQ(viewer::dataChange(floorOnly, linearFloor).kind, DataChange::Rescale) << "log -> linear";
    // The same file written another way is the same data.
    session::Session dotted = shown();
    dotted.input = "/data/enzo/./DD0018/../DD0018/DD0018";
    EXPECT_EQ(viewer::dataChange(shown(), dotted).kind, DataChange::None);
}

TEST(DataChange, OtherDataIsRefusedWithItsReason) {
    struct Case {
        const char* what;
        void (*edit)(session::Session&);
        const char* inReason;
    };
    const Case cases[] = {
        {"input", [](session::Session& s) { s.input = "/data/other"; }, "another data set: /data/other"},
        {"field", [](session::Session& s) { s.field = "Temperature"; }, "another field: 'Temperature'"},
        {"format", [](session::Session& s) { s.read.format = "enzo"; }, "read.format enzo (this viewer read auto)"},
        {"nan", [](session::Session& s) { s.read.nanPolicy = amr::NanPolicy::Drop; },
         "read.nan drop (this viewer read reject)"},
        {"dims",
         [](session::Session& s) {
             s.read.rawDims = {4, 5, 6};
         },
         "read.dims 4x5x6 (this viewer read from the name)"},
        {"type", [](session::Session& s) { s.read.rawType = "uint8"; }, "read.type 'uint8'"},
        {"threshold", [](session::Session& s) { s.read.rawThreshold = 0.5; }, "read.threshold 0.5"},
    };
    for (const Case& c : cases) {
        session::Session next = shown();
        c.edit(next);
        next.read.scale = amr::FieldScale::Log;  // a scale change beside it does not make it a rescale
        const viewer::DataChangeCheck check = viewer::dataChange(shown(), next);
        EXPECT_EQ(check.kind, DataChange::Other) << c.what;
        EXPECT_NE(check.reason.find(c.inReason), std::string::npos) << c.what << ": " << check.reason;
    }
}

TEST(DataChange, TheTfKeepsItsShapeOnTheNewRange) {
    // Opacity nodes at 0, 1, 3, 4 on [0, 4] (relative 0, 1/4, 3/4, 1) -> on [-2, 2]: -2, -1, 1, 2.
    scene::TfChannels tf;
    tf.name = "mine";
    tf.opacityPositions = {0, 1, 3, 4};
    tf.alphas = {0, 0.5f, 2, 0.25f};
    tf.colorPositions = {0, 4};
    tf.colors = {{1, 0, 0}, {0, 0, 1}};
    const scene::TfChannels out = viewer::refitTfRange(tf, -2, 2);
    ASSERT_EQ(out.opacityPositions.size(), 4u);
    const float expected[] = {-2, -1, 1, 2};
    for (size_t i = 0; i < 4; ++i) {
        EXPECT_FLOAT_EQ(out.opacityPositions[i], expected[i]);
        EXPECT_EQ(out.alphas[i], tf.alphas[i]) << "opacity values kept";
    }
    EXPECT_EQ(out.colors, tf.colors);
    EXPECT_EQ(out.name, "mine");
    // A constant field: one unit above its value.
    const scene::TfChannels flat = viewer::refitTfRange(tf, 3, 3);
    EXPECT_FLOAT_EQ(flat.opacityPositions.front(), 3.0f);
    EXPECT_FLOAT_EQ(flat.opacityPositions.back(), 4.0f);
    EXPECT_THROW(viewer::refitTfRange(tf, 2, 1), Error);
    EXPECT_THROW(viewer::refitTfRange(tf, 0, INFINITY), Error);
}

TEST(DataChange, AnUneditedFittedPresetIsFittedAgainOnTheNewScale) {
    const std::shared_ptr<const scene::Volume> linear = scene::makeVolume(test::makeThreeLevelCloud());
    amr::Model logModel = test::makeThreeLevelCloud();
    amr::applyFieldScale(logModel, amr::FieldScale::Log);
    const std::shared_ptr<const scene::Volume> log = scene::makeVolume(std::move(logModel));
    ASSERT_GT(linear->valueLo(), 0.0f) << "no floor: every linear node has a log";
    for (const char* name : {"spiky", "foggy", "layers"}) {
        SCOPED_TRACE(name);
        const scene::TfChannels tf =
            scene::TfChannels::split(scene::makePreset(name, linear->percentiles, linear->volumeHistogram));
        const scene::TfChannels onLog = viewer::tfOnNewScale(tf, *linear, *log);
        EXPECT_EQ(onLog, scene::TfChannels::split(scene::makePreset(name, log->percentiles, log->volumeHistogram)));
        // The old rule (the shape moved linearly onto the log range) puts the nodes elsewhere.
        EXPECT_NE(onLog, viewer::refitTfRange(tf, log->valueLo(), log->valueHi()));
        // Back on the linear scale: the TF it started from.
        EXPECT_EQ(viewer::tfOnNewScale(onLog, *log, *linear), tf);
        // The editor's form of the same TF (the viewer's panels hold it so) is the same preset.
        EXPECT_EQ(viewer::tfOnNewScale(viewer::TfEditor::editable(tf), *linear, *log), onLog);
        if (std::string(name) == "layers") continue;  // layers sit at fractions of the range, not percentiles
        // spiky and foggy mark the same cells: every node at the log10 of its linear value
        // (percentiles of the logs are the logs of the percentiles).
        ASSERT_EQ(onLog.opacityPositions.size(), tf.opacityPositions.size());
        for (size_t i = 0; i < tf.opacityPositions.size(); ++i) {
            EXPECT_NEAR(onLog.opacityPositions[i], std::log10(double(tf.opacityPositions[i])), 1e-5) << "node " << i;
            EXPECT_EQ(onLog.alphas[i], tf.alphas[i]) << "node " << i;
        }
    }
}

TEST(DataChange, AnyOtherTfKeepsItsShapeOnTheNewScale) {
    const std::shared_ptr<const scene::Volume> linear = scene::makeVolume(test::makeThreeLevelCloud());
    amr::Model logModel = test::makeThreeLevelCloud();
    amr::applyFieldScale(logModel, amr::FieldScale::Log);
    const std::shared_ptr<const scene::Volume> log = scene::makeVolume(std::move(logModel));
    auto keepsShape = [&](const scene::TfChannels& tf, const char* what) {
        EXPECT_EQ(viewer::tfOnNewScale(tf, *linear, *log), viewer::refitTfRange(tf, log->valueLo(), log->valueHi()))
            << what;
    };
    scene::TfChannels edited =
        scene::TfChannels::split(scene::makePreset("spiky", linear->percentiles, linear->volumeHistogram));
    *std::max_element(edited.alphas.begin(), edited.alphas.end()) = 0.75f;  // a peak lowered
    keepsShape(edited, "an edited spiky");
    keepsShape(scene::TfChannels::split(scene::makePreset("spiky", linear->valueLo(), linear->valueHi())),
               "spiky over a given range (--tf-range)");
    keepsShape(scene::TfChannels::split(scene::makePreset("ramp", linear->percentiles, linear->volumeHistogram)),
               "ramp, which follows the range only");
    scene::TfChannels mine =
        scene::TfChannels::split(scene::makePreset("foggy", linear->percentiles, linear->volumeHistogram));
    mine.name = "mine";
    keepsShape(mine, "foggy's nodes under another name (a file)");
}
