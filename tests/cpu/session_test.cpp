// Session files: every field round-trips; a relative input is taken relative to the file; every
// bad value gives one line naming the file and the key; the file is written atomically.
#include "session/session.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "scene/invalidation.h"
#include "scene/tf_presets.h"
#include "session/picture_description.h"
#include "test_data.h"

using namespace amrvk;
using session::Session;

namespace {

Session fullSession() {
    Session s;
    s.input = "/data/enzo/DD0018/DD0018";
    s.read.format = "enzo";
    s.read.nanPolicy = amr::NanPolicy::Drop;
    s.read.scale = amr::FieldScale::Log;
    s.read.logFloor = 1e-3;
    s.field = "Density";
    s.spp = 128;
    scene::RenderSettings& r = s.settings;
    r.mode = scene::Mode::Ss;
    r.width = 320;
    r.height = 200;
    r.seed = 77;
    r.camera.eye = {1.5, -2.25, 3.0};
    r.camera.target = {0.5, 0.5, 0.5};
    r.camera.up = {0.0, 0.0, 1.0};
    r.camera.fovYDegrees = 33.0;
    r.densityScale = 0.05;
    r.g = -0.3;
    r.ambient = {0.1, 0.2, 0.3};
    r.background = glm::dvec3(0.0, 0.0, 0.01);
    r.dvrStep = 0.25;
    r.dvrShading = true;
    r.transmittance = scene::Transmittance::Ubrm;
    r.controlExtinction = scene::ControlExtinction::Minorant;
    r.lights.push_back({false, {1.0, -1.0, 2.0}, {3.0, 3.0, 2.5}});
    r.lights.push_back({true, {0.2, 0.3, 4.0}, {10.0, 9.0, 8.0}});
    r.cut.crop = scene::CropBox{{0.0, 0.125, 0.25}, {1.0, 0.75, 0.5}};
    r.cut.clips.push_back({{0.5, 0.5, 0.5}, {1.0, 1.0, 0.0}});
    r.cut.clips.push_back({{0.25, 0.5, 0.5}, {0.0, 0.0, -1.0}});
    s.structure.traversal = scene::TraversalKind::KdTree;
    s.structure.sampler = scene::SamplerKind::Abr;
    s.structure.backend = scene::Backend::Auto;
    s.structure.grid = "64";
    s.structure.kdLeaves = 512;
    s.structure.denseMaxBytes = uint64_t(300) << 20;
    s.tf = scene::TfChannels::split(scene::makePreset("spiky", 0.0f, 3.0f));
    s.tf.name = "spiky edit";
    s.tfColors = scene::TfColors::Linear;  // not the default, so the round trip shows it is kept
    return s;
}

std::string errorOfParse(const std::string& text) {
    return test::errorOf([&] { session::parseSession(text, "/tmp/s.json"); });
}

}  // namespace

TEST(Session, EveryFieldRoundTrips) {
    const Session s = fullSession();
    const auto file = test::scratchDir() / "full.json";
    session::saveSession(file, s);
    const Session t = session::loadSession(file);
    EXPECT_EQ(t.input, s.input);
    EXPECT_EQ(t.read.format, "enzo");
    EXPECT_EQ(t.read.nanPolicy, amr::NanPolicy::Drop);
    EXPECT_EQ(t.read.scale, amr::FieldScale::Log);
    EXPECT_EQ(t.read.logFloor, 1e-3);
    EXPECT_EQ(t.field, "Density");
    EXPECT_EQ(t.spp, 128u);
    const scene::RenderSettings &a = s.settings, &b = t.settings;
    EXPECT_TRUE(scene::settingsChanges(a, b).empty()) << scene::describe(scene::settingsChanges(a, b));
    EXPECT_EQ(b.seed, 77u);
    EXPECT_EQ(b.width, 320);
    ASSERT_EQ(b.lights.size(), 2u);
    EXPECT_TRUE(b.lights[1].point);
    EXPECT_EQ(b.cut, a.cut);
    ASSERT_EQ(b.cut.clips.size(), 2u);
    EXPECT_EQ(t.structure.label(), s.structure.label());
    EXPECT_EQ(t.structure.grid, "64");
    EXPECT_EQ(t.structure.kdLeaves, 512u);
    EXPECT_EQ(t.structure.denseMaxBytes, s.structure.denseMaxBytes);
    const scene::TransferFunction x = s.tf.merged(), y = t.tf.merged();
    EXPECT_EQ(y.positions(), x.positions());
    EXPECT_EQ(y.colors(), x.colors());
    EXPECT_EQ(t.tf.name, "spiky edit");
    EXPECT_EQ(t.tfColors, scene::TfColors::Linear);
    // Saving what was loaded gives the same text.
    EXPECT_EQ(session::sessionJson(t), session::sessionJson(s));
}

TEST(Session, KeysLeftOutTakeTheDefaultsTheFrontEndsStartWith) {
    // Only what a session must name: every other key of every section reads as its default, the
    // same default a Session (and the CLI) starts with, and writing it back states them.
    const std::string text = R"({"amrvk": "session", "version": 3, "input": "/d/c.cells",
        "camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "up": [0, 1, 0]}, "image": {"width": 8, "height": 6},
        "transferFunction": {"Name": "t", "RGBPoints": [0, 1, 1, 1, 1, 1, 1, 1], "Points": [0, 0, 0.5, 0, 1, 1, 0.5, 0]}})";
    const Session s = session::parseSession(text, "/tmp/min.json");
    const Session d;
    EXPECT_EQ(s.read.format, d.read.format);
    EXPECT_EQ(s.read.nanPolicy, d.read.nanPolicy);
    EXPECT_EQ(s.read.scale, d.read.scale);
    EXPECT_EQ(s.read.rawDims, d.read.rawDims);
    EXPECT_EQ(s.spp, d.spp);
    EXPECT_EQ(s.settings.mode, d.settings.mode);
    EXPECT_EQ(s.settings.seed, d.settings.seed);
    EXPECT_EQ(s.settings.densityScale, d.settings.densityScale);
    EXPECT_EQ(s.settings.g, d.settings.g);
    EXPECT_EQ(s.settings.ambient, d.settings.ambient);
    EXPECT_EQ(s.settings.background, d.settings.background);
    EXPECT_EQ(s.settings.background, glm::dvec3(0.0));  // black: the data lit by the sky, on black
    EXPECT_EQ(s.read.scale, amr::FieldScale::Auto);
    EXPECT_EQ(s.settings.camera.fovYDegrees, d.settings.camera.fovYDegrees);
    EXPECT_EQ(s.settings.dvrStep, d.settings.dvrStep);
    EXPECT_EQ(s.structure.traversal, d.structure.traversal);
    EXPECT_EQ(s.structure.sampler, d.structure.sampler);
    EXPECT_EQ(s.structure.grid, d.structure.grid);
    EXPECT_EQ(s.structure.kdLeaves, d.structure.kdLeaves);
    EXPECT_EQ(s.structure.denseMaxBytes, d.structure.denseMaxBytes);
    EXPECT_TRUE(s.legend == d.legend);
    const std::string written = session::sessionJson(s);
    for (const char* key : {"\"nan\"", "\"spp\"", "\"seed\"", "\"dvrShading\"", "\"sampler\"", "\"denseMaxMiB\"",
                            "\"background\""})
        EXPECT_NE(written.find(key), std::string::npos) << key;
    for (const char* key : {"\"dims\"", "\"threshold\"", "\"scale\"", "\"legend\""})
        EXPECT_EQ(written.find(key), std::string::npos) << key << " is written only when set";
}

TEST(Session, RelativeInputIsRelativeToTheFile) {
    std::string text = session::sessionJson(fullSession());
    const std::string from = "\"/data/enzo/DD0018/DD0018\"", to = "\"../data/cloud.cells\"";
    text.replace(text.find(from), from.size(), to);
    const Session s = session::parseSession(text, "/home/me/sessions/a.json");
    EXPECT_EQ(s.input, "/home/me/data/cloud.cells");
}

TEST(Session, BadValuesNameTheFileAndTheKey) {
    const std::string good = session::sessionJson(fullSession());
    auto with = [&](const std::string& from, const std::string& to) {
        std::string t = good;
        const size_t at = t.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        if (at != std::string::npos) t.replace(at, from.size(), to);
        return t;
    };
    // Cut-aways the CLI would refuse, and a clip plane without its point, written as the viewer writes.
    auto withCut = [](const std::function<void(scene::CutAway&)>& edit) {
        Session s = fullSession();
        edit(s.settings.cut);
        return session::sessionJson(s);
    };
    const std::string badCrop = withCut([](scene::CutAway& c) { c.crop->lo.x = 2.0; });
    const std::string badClip = withCut([](scene::CutAway& c) { c.clips[0].normal = glm::dvec3(0.0); });
    std::string noPoint = withCut([](scene::CutAway&) {});
    // {"normal": P, "normal": N}: nlohmann keeps one of them, and "point" is missing.
    noPoint.replace(noPoint.find("\"point\": ["), 7, "\"normal\"");
    const struct {
        std::string text;
        std::vector<std::string> fragments;
    } cases[] = {
        {"{", {"/tmp/s.json", "malformed JSON"}},
        {"[]", {"/tmp/s.json", "not an amrvk session"}},
        {with("\"version\": 3", "\"version\": 7"), {"version 7"}},
        {with("\"tfColors\": \"linear\"", "\"tfColors\": \"gamma\""),
         {"/tmp/s.json.tfColors: 'gamma' is not one of srgb|linear"}},
        {with("\"fovY\": 33.0", "\"fovY\": 0.0"), {"camera.fovY", "(0, 180)"}},
        {with("\"width\": 320", "\"width\": 0"), {"image.width", "[1, 16384]"}},
        {with("\"mode\": \"ss\"", "\"mode\": \"xx\""), {"render.mode", "'xx' is not one of ae|ss|ms|dvr"}},
        {with("\"densityScale\": 0.05", "\"densityScale\": -1"), {"render.densityScale"}},
        {with("\"g\": -0.3", "\"g\": \"a\""), {"render.g", "expected a number"}},
        {with("\"type\": \"point\"", "\"type\": \"spot\""), {"lights[1].type", "spot"}},
        {with("\"traversal\": \"kdtree\"", "\"traversal\": \"octree\""),
         {"structure.traversal: 'octree' is not one of grid-dda|"}},
        {with("\"RGBPoints\"", "\"RGBPointz\""), {"transferFunction", "no RGBPoints"}},
        {with("\"eye\": [", "\"eye\": [\"x\", "), {"camera.eye"}},
        {badCrop, {"/tmp/s.json", ".cut", "--crop", "axis x"}},
        {badClip, {".cut", "--clip", "normal 0 0 0"}},
        {with("\"clip\": [",
              "\"clip\": [{\"point\": [0, 0, 0], \"normal\": [1, 0, 0]}, {\"point\": [0, 0, 0], \"normal\": [1, 0, "
              "0]}, {\"point\": [0, 0, 0], \"normal\": [1, 0, 0]},"),
         {".cut.clip", "at most 4 planes (got 5)"}},
        {with("\"format\": \"enzo\"", "\"format\": \"enzo\", \"dims\": [4, 1048577, 4]"),
         {"read.dims[1]", "1048577 is not an integer in [1, 1048576]"}},
        {with("\"dvrStep\": 0.25", "\"dvrStep\": 0"), {"render.dvrStep", "0 is outside (0, 64]"}},
        {with("\"logFloor\": 0.001", "\"logFloor\": -2"), {"read.logFloor", "-2 must be >= 0"}},
        {with("\"spp\": 128", "\"spp\": 16777217"), {"render.spp: 16777217 is outside [1, 16777216]"}},
        {with("\"kdLeaves\": 512", "\"kdLeaves\": 0"), {"structure.kdLeaves", "[1, 16777215]"}},
        {with("\"transferFunction\"", "\"legend\": {\"show\": 1}, \"transferFunction\""),
         {"legend.show", "expected true or false"}},
        {with("\"transferFunction\"", "\"legend\": [], \"transferFunction\""), {"legend", "expected an object"}},
        {with("\"sampler\": \"abr\"", "\"sampler\": \"dense\""), {"/tmp/s.json.structure", "dense"}},
        {noPoint, {".cut.clip[0]", "missing \"point\""}},
        // A cut that is not an object was read as no cut-away (issue 52, point 9).
        {with("\"transferFunction\"", "\"cut\": 5, \"transferFunction\""), {"/tmp/s.json.cut: expected an object"}},
        // A key this amrvk does not know (a typo, a newer amrvk's setting) is named, not dropped.
        {with("\"point\": [", "\"pont\": ["), {".cut.clip[0].pont: unknown key", "keys here: point, normal"}},
        {with("\"densityScale\"", "\"densityscale\""), {"/tmp/s.json.render.densityscale: unknown key"}},
        {with("\"structure\": {", "\"structure\": {\"bvhLeaf\": 4, "), {".structure.bvhLeaf: unknown key"}},
        {with("\"amrvk\": \"session\",", "\"amrvk\": \"session\", \"denoise\": true,"),
         {"/tmp/s.json.denoise: unknown key"}},
    };
    for (const auto& c : cases) {
        const std::string e = errorOfParse(c.text);
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
        for (const auto& f : c.fragments) EXPECT_NE(e.find(f), std::string::npos) << "'" << f << "' not in: " << e;
    }
    EXPECT_NE(test::errorOf([] { session::loadSession("/nonexistent/s.json"); }).find("no such session file"),
              std::string::npos);
}

// "copy as command": every read option, setting and structure choice of the session appears as the
// render option that sets it, arguments with spaces are quoted, and an unset spp becomes render's 64.
TEST(Session, RenderCommandLineCarriesEverySetting) {
    Session s = fullSession();
    s.input = "/data/my run/plt00010";
    const std::string c = session::renderCommandLine(s, "/tmp/a tf.json", "out.png");
    EXPECT_EQ(c.rfind("amrvk render '/data/my run/plt00010' ", 0), 0u) << c;
    for (const char* part :
         {" --field Density", " --format enzo", " --nan drop", " --scale log", " --log-floor 0.001", " --tf '/tmp/a tf.json'", " --tf-colors linear", " --mode ss", " --size 320x200",
          " --seed 77", " --camera 1.5 -2.25 3 0.5 0.5 0.5 0 0 1", " --fov 33", " --density-scale 0.05", " --g -0.3",
          " --ambient 0.1 0.2 0.3", " --background 0 0 0.01", " --light-dir 1 -1 2 3 3 2.5",
          " --light-point 0.2 0.3 4 10 9 8", " --dt 0.25", " --dvr-shading", " --transmittance ubrm", " --control-extinction minorant", " --spp 128", " --traversal kdtree",
          " --sampler abr", " --backend auto", " --grid 64", " --kd-leaves 512", " --dense-max-mib 300", " -o out.png",
          " --crop 0 0.125 0.25 1 0.75 0.5", " --clip 0.5 0.5 0.5 1 1 0 --clip 0.25 0.5 0.5 0 0 -1"})
        EXPECT_NE(c.find(part), std::string::npos) << part << " missing from: " << c;
    s.spp = 0;  // the viewer's "run on"
    EXPECT_NE(session::renderCommandLine(s, "t.json", "o.png").find(" --spp 64"), std::string::npos);
    // A background that is the ambient's is stated too: render's own default is black (issue 52,
    // point 8: bench's recorded reference commands left it out and rendered another picture).
    s.settings.background.reset();
    EXPECT_NE(session::renderCommandLine(s, "t.json", "o.png").find(" --background 0.1 0.2 0.3"), std::string::npos);
}

// Issue 35: a version 1 session (before "tfColors") meant its TF colours as linear albedo and loads
// so; a version 2 file says its convention, and one without the key means the default (srgb).
TEST(Session, OlderSessionsKeepTheirColourMeaning) {
    Session s = fullSession();
    s.tfColors = scene::TfColors::Srgb;
    const std::string v2 = session::sessionJson(s);
    ASSERT_NE(v2.find("\"version\": 3"), std::string::npos);
    ASSERT_NE(v2.find("\"tfColors\": \"srgb\""), std::string::npos);
    EXPECT_EQ(session::parseSession(v2, "/tmp/s.json").tfColors, scene::TfColors::Srgb);
    auto without = [](std::string t, const std::string& version) {
        const std::string key = ",\n  \"tfColors\": \"srgb\"";
        const size_t at = t.find(key);
        if (at != std::string::npos) t.erase(at, key.size());
        const size_t v = t.find("\"version\": 3");
        if (v != std::string::npos) t.replace(v, 12, "\"version\": " + version);
        return t;
    };
    // As written before issue 35: version 1, no key.
    const std::string v1 = without(v2, "1");
    ASSERT_EQ(v1.find("tfColors"), std::string::npos);
    EXPECT_EQ(session::parseSession(v1, "/tmp/s.json").tfColors, scene::TfColors::Linear);
    EXPECT_EQ(session::parseSession(without(v2, "2"), "/tmp/s.json").tfColors, scene::TfColors::Srgb);
    // Saved again, the old session says what it meant.
    const Session old = session::parseSession(v1, "/tmp/s.json");
    EXPECT_NE(session::sessionJson(old).find("\"tfColors\": \"linear\""), std::string::npos);
}

// Issue 33: version 3 starts from the auto scale and a black background; a version 1-2 file without
// those keys meant linear values and the ambient behind the data, loads so and says so when saved.
TEST(Session, OlderSessionsKeepTheirScaleAndBackground) {
    const std::string minimal = R"({"amrvk": "session", "version": V, "input": "/d/c.cells",
        "camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "up": [0, 1, 0]}, "image": {"width": 8, "height": 6},
        "transferFunction": {"Name": "t", "RGBPoints": [0, 1, 1, 1, 1, 1, 1, 1]}})";
    auto versioned = [&](const char* v) {
        std::string t = minimal;
        t.replace(t.find("V,"), 1, v);
        return session::parseSession(t, "/tmp/s.json");
    };
    for (const char* v : {"1", "2"}) {
        const Session old = versioned(v);
        EXPECT_EQ(old.read.scale, amr::FieldScale::Linear) << v;
        EXPECT_FALSE(old.settings.background.has_value()) << v;
        const std::string saved = session::sessionJson(old);
        EXPECT_NE(saved.find("\"scale\": \"linear\""), std::string::npos) << saved;
        EXPECT_NE(saved.find("\"background\": \"ambient\""), std::string::npos) << saved;
        const Session again = session::parseSession(saved, "/tmp/s.json");  // version 3 now
        EXPECT_EQ(again.read.scale, amr::FieldScale::Linear);
        EXPECT_FALSE(again.settings.background.has_value());
    }
    const Session now = versioned("3");
    EXPECT_EQ(now.read.scale, amr::FieldScale::Auto);
    EXPECT_EQ(now.settings.background, glm::dvec3(0.0));
    EXPECT_NE(test::errorOf([&] { versioned("4"); }).find("session version 4 (this amrvk reads versions 1 to 3)"),
              std::string::npos);
}
