// The series of `amrvk render` (session/series.h): natural order against a hand-sorted list,
// glob expansion over real files (order, no match, duplicates, literal names with wildcard
// characters), the frame plan's refusals, azimuths, frame names and manifests (round trip and the
// errors of damaged ones), and the series' one TF range.
#include "session/series.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <random>

#include "core/error.h"
#include "model_fixtures.h"
#include "scene/tf_presets.h"
#include "scene/transfer_function.h"
#include "scene/volume.h"
#include "session/picture_description.h"
#include "test_data.h"

using namespace amrvk;
using namespace amrvk::session;
namespace fs = std::filesystem;

namespace {
void touch(const fs::path& p) { std::ofstream(p) << "x"; }
}  // namespace

TEST(Series, NaturalOrderSortsDigitRunsAsNumbers) {
    // The expected order written out by hand.
    const std::vector<std::string> expected = {"output_1",
                                               "output_2",
                                               "output_02b",
                                               "output_10",
                                               "output_10a",
                                               "output_010b",
                                               "output_100",
                                               "plt1e3",
                                               "plt00009",
                                               "plt00010",
                                               "plt99999999999999999999",
                                               "plt100000000000000000000"};
    std::vector<std::string> shuffled = expected;
    std::mt19937 rng(7);
    for (int trial = 0; trial < 20; ++trial) {
        std::shuffle(shuffled.begin(), shuffled.end(), rng);
        std::sort(shuffled.begin(), shuffled.end(), naturalLess);
        EXPECT_EQ(shuffled, expected);
    }
    // Equal as numbers: leading zeros fall back to plain order, so the order is strict and total.
    EXPECT_TRUE(naturalLess("f_007", "f_7"));
    EXPECT_FALSE(naturalLess("f_7", "f_007"));
    EXPECT_FALSE(naturalLess("a", "a"));
    EXPECT_TRUE(naturalLess("a", "a1"));
    EXPECT_TRUE(naturalLess("DD0009/DD0009", "DD0010/DD0010"));
}

TEST(Series, GlobPatternsExpandInNaturalOrder) {
    const fs::path dir = test::scratchDir();
    for (const char* name : {"out_10.cells", "out_2.cells", "out_1.cells", "other.cells", "b[1].cells"})
        touch(dir / name);
    const std::string d = dir.string() + "/";
    EXPECT_EQ(expandInputs({d + "out_*.cells"}),
              (std::vector<std::string>{d + "out_1.cells", d + "out_2.cells", d + "out_10.cells"}));
    // Paths given one by one (as a shell's unquoted glob gives them, 10 before 2) are sorted too.
    EXPECT_EQ(expandInputs({d + "out_10.cells", d + "out_2.cells"}),
              (std::vector<std::string>{d + "out_2.cells", d + "out_10.cells"}));
    // An existing name with wildcard characters is a path, not a pattern.
    EXPECT_EQ(expandInputs({d + "b[1].cells"}), (std::vector<std::string>{d + "b[1].cells"}));
    // A missing plain path passes through (its reader names it).
    EXPECT_EQ(expandInputs({d + "missing.cells"}), (std::vector<std::string>{d + "missing.cells"}));
    const std::string none = test::errorOf([&] { expandInputs({d + "nothing_*.cells"}); });
    EXPECT_NE(none.find("nothing_*.cells': no file or directory matches the pattern"), std::string::npos) << none;
    const std::string twice = test::errorOf([&] { expandInputs({d + "out_*.cells", d + "out_2.cells"}); });
    EXPECT_NE(twice.find("out_2.cells' is named twice"), std::string::npos) << twice;
}

TEST(Series, FramePlanAndItsRefusals) {
    EXPECT_EQ(planFrames({"a", "b"}, std::nullopt, false), (std::vector<std::string>{"a", "b"}));
    EXPECT_EQ(planFrames({"a", "b"}, std::nullopt, true), (std::vector<std::string>{"a", "b"}));
    EXPECT_EQ(planFrames({"a"}, 3u, true), (std::vector<std::string>{"a", "a", "a"}));
    EXPECT_NE(test::errorOf([] {
                  planFrames({"a", "b"}, 3u, true);
              }).find("--frames 3: renders one input"),
              std::string::npos);
    EXPECT_NE(test::errorOf([] { planFrames({"a"}, 3u, false); }).find("without --orbit"), std::string::npos);
    EXPECT_NE(
        test::errorOf([] { planFrames({"a"}, std::nullopt, true); }).find("--orbit over one input needs --frames"),
        std::string::npos);
    EXPECT_NE(test::errorOf([] { planFrames({"a"}, 100001u, true); }).find("outside [1, 100000]"), std::string::npos);
    EXPECT_EQ(frameAzimuth(0, 4, 360), 0.0);
    EXPECT_EQ(frameAzimuth(1, 4, 360), 90.0);
    EXPECT_EQ(frameAzimuth(3, 4, 360), 270.0);
    EXPECT_EQ(frameAzimuth(2, 3, -90), -60.0);
}

TEST(Series, FrameNamesFromPatternsAndDirectories) {
    FrameOutput f = frameOutput("-o", "frames/f_%04d.png", 3);
    EXPECT_EQ(f.frame(0), fs::path("frames/f_0000.png"));
    EXPECT_EQ(f.frame(12345), fs::path("frames/f_12345.png"));
    EXPECT_EQ(f.directory, fs::path("frames"));
    EXPECT_EQ(f.manifest, fs::path("frames/f_manifest.json"));
    EXPECT_EQ(f.extension, ".png");
    f = frameOutput("-o", "100%%_%d.pfm", 2);  // a literal % in the name
    EXPECT_EQ(f.frame(7), fs::path("100%_7.pfm"));
    EXPECT_EQ(f.directory, fs::path("."));
    EXPECT_EQ(f.manifest, fs::path("./100%_manifest.json"));
    f = frameOutput("-o", "a%%b/x_%3d.exr", 2);  // a literal % in the directory
    EXPECT_EQ(f.frame(5), fs::path("a%b/x_  5.exr"));
    EXPECT_EQ(f.directory, fs::path("a%b"));
    f = frameOutput("--frames-dir", "movie 50%/", 9);
    EXPECT_EQ(f.pattern, "movie 50%%/frame_%04d.png");
    EXPECT_EQ(f.frame(3), fs::path("movie 50%/frame_0003.png"));
    EXPECT_EQ(f.manifest, fs::path("movie 50%/frame_manifest.json"));
    f = frameOutput("-o", "one.png", 1);  // one frame: a plain name is fine
    EXPECT_EQ(f.frame(0), fs::path("one.png"));
    EXPECT_EQ(f.manifest, fs::path("./one_manifest.json"));

    EXPECT_TRUE(hasFrameNumber("f_%d.png"));
    EXPECT_TRUE(hasFrameNumber("f_%04d.png"));
    EXPECT_TRUE(hasFrameNumber("f_%4d.png"));
    EXPECT_TRUE(hasFrameNumber("100%%_%d.png"));
    EXPECT_FALSE(hasFrameNumber("100%.png"));
    EXPECT_FALSE(hasFrameNumber("f_%%d.png"));
    EXPECT_FALSE(hasFrameNumber("f_%s.png"));
    EXPECT_FALSE(hasFrameNumber("f_%"));
    auto error = [](const std::string& text, uint32_t n) { return test::errorOf([&] { frameOutput("-o", text, n); }); };
    EXPECT_NE(error("movie.png", 3).find("-o movie.png: 3 frames need a numbered name with %d"), std::string::npos);
    EXPECT_NE(error("f_%s.png", 3).find("'%' starts a frame number only as %d"), std::string::npos);
    EXPECT_NE(error("f_%012d.png", 3).find("'%' starts a frame number only as %d"), std::string::npos);
    EXPECT_NE(error("f_%d_%d.png", 3).find("2 frame numbers"), std::string::npos);
    EXPECT_NE(error("d%d/f.png", 3).find("belongs in the file name"), std::string::npos);
    EXPECT_NE(error("f_%d.bmp", 3).find("unknown image type for frames"), std::string::npos);
}

TEST(Series, ManifestRoundTripAndDamage) {
    const fs::path dir = test::scratchDir();
    FrameManifest m;
    m.recipe = "{\"picture\": \"amrvk render INPUT --spp 4\"}";
    m.done = {0, 2, 7};
    m.tfRange = std::make_pair(-1.5f, 1029.25f);
    m.camera = {.eye = {1, 2, 3}, .target = {0.5, 0.25, 0.125}, .up = {0, 0, 1}, .fovYDegrees = 35};
    m.centre = {0.5, 0.5, 0.5};
    m.field = "Density";
    saveFrameManifest(dir / "m.json", m);
    const std::optional<FrameManifest> back = loadFrameManifest(dir / "m.json");
    ASSERT_TRUE(back.has_value());
    EXPECT_EQ(back->recipe, m.recipe);
    EXPECT_EQ(back->done, m.done);
    EXPECT_EQ(back->tfRange, m.tfRange);
    EXPECT_EQ(back->camera, m.camera);
    EXPECT_EQ(back->centre, m.centre);
    EXPECT_EQ(back->field, m.field);
    EXPECT_FALSE(back->tfPercentiles.has_value());
    // The percentiles the presets were fitted to, bit for bit.
    amr::Percentiles p;
    p.count = 12345;
    for (size_t k = 0; k < p.values.size(); ++k) p.values[k] = -1.5f + 0.1f * float(k) + 1e-7f * float(k * k);
    m.tfPercentiles = p;
    amr::VolumeHistogram h;
    h.lo = -1.5f;
    h.hi = 8.25f;
    h.boundsVolume = 4096;
    h.volume.assign(amr::VolumeHistogram::kBins, 0.0);
    for (size_t k = 0; k < h.volume.size(); ++k) h.volume[k] = 1.0 / 3.0 * double(k % 7);
    m.tfHistogram = h;
    saveFrameManifest(dir / "m.json", m);
    EXPECT_EQ(loadFrameManifest(dir / "m.json")->tfPercentiles, p);
    EXPECT_EQ(loadFrameManifest(dir / "m.json")->tfHistogram, h) << "bit for bit";
    m.tfHistogram.reset();
    m.tfRange.reset();
    m.tfPercentiles.reset();
    saveFrameManifest(dir / "m.json", m);
    EXPECT_FALSE(loadFrameManifest(dir / "m.json")->tfRange.has_value());
    // Percentiles that are not 101 finite non-descending values with a count: malformed.
    const std::string head =
        "{\"amrvk\": \"frames\", \"recipe\": \"r\", \"done\": [], \"tfRange\": null, "
        "\"camera\": {\"eye\": [0,0,1], \"target\": [0,0,0], \"up\": [0,1,0], \"fovYDegrees\": 30}, "
        "\"centre\": [0,0,0], \"field\": \"f\", \"tfPercentiles\": ";
    auto values = [](int n, float step) {
        std::string t = "[";
        for (int k = 0; k < n; ++k) t += (k ? ", " : "") + std::to_string(step * float(k));
        return t + "]";
    };
    for (const std::string& bad :
         {"{\"count\": 5, \"values\": " + values(100, 1) + "}", "{\"count\": 0, \"values\": " + values(101, 1) + "}",
          "{\"count\": 5, \"values\": " + values(101, -1) + "}", std::string("{\"count\": 5}")}) {
        std::ofstream(dir / "bad.json") << head << bad << "}";
        EXPECT_NE(test::errorOf([&] { loadFrameManifest(dir / "bad.json"); }).find("malformed frame manifest"),
                  std::string::npos)
            << bad;
    }
    std::ofstream(dir / "good.json") << head << "{\"count\": 5, \"values\": " << values(101, 1) << "}}";
    EXPECT_EQ(loadFrameManifest(dir / "good.json")->tfPercentiles->count, 5u);
    // A histogram that is not a finite range, boundsVolume above 0 and 1024 volumes >= 0: malformed.
    const std::string goodPercentiles = "{\"count\": 5, \"values\": " + values(101, 1) + "}";
    auto histogram = [&](const std::string& lo, const std::string& bounds, int n, float step) {
        return goodPercentiles + ", \"tfHistogram\": {\"lo\": " + lo + ", \"hi\": 2, \"boundsVolume\": " + bounds +
               ", \"volume\": " + values(n, step) + "}";
    };
    for (const std::string& bad : {histogram("0", "8", 1023, 1), histogram("3", "8", 1024, 1),
                                   histogram("0", "0", 1024, 1), histogram("0", "8", 1024, -1)}) {
        std::ofstream(dir / "bad.json") << head << bad << "}";
        EXPECT_NE(test::errorOf([&] { loadFrameManifest(dir / "bad.json"); }).find("malformed frame manifest"),
                  std::string::npos)
            << bad;
    }
    std::ofstream(dir / "good.json") << head << histogram("0", "8", 1024, 1) << "}";
    EXPECT_EQ(loadFrameManifest(dir / "good.json")->tfHistogram->boundsVolume, 8.0);

    EXPECT_FALSE(loadFrameManifest(dir / "absent.json").has_value());
    std::ofstream(dir / "other.json") << "{\"amrvk\": \"session\"}";
    EXPECT_NE(test::errorOf([&] { loadFrameManifest(dir / "other.json"); }).find("not an amrvk frame manifest"),
              std::string::npos);
    std::ofstream(dir / "broken.json") << "{\"amrvk\": \"frames\", \"recipe\": 3}";
    EXPECT_NE(test::errorOf([&] { loadFrameManifest(dir / "broken.json"); }).find("malformed frame manifest"),
              std::string::npos);
}

// One range for every output: a preset spans the series' range (PictureDescription::dataRange)
// instead of the volume's own, and --tf-range still wins over both.
TEST(Series, PresetsSpanTheSeriesRangeAndTfRangeWins) {
    const std::shared_ptr<const scene::Volume> v = scene::makeVolume(test::makeThreeLevelCloud());
    PictureDescription d;
    d.tfSource = TfSource{.name = "ramp"};
    auto span = [&] {
        const scene::TransferFunction tf = resolvePicture(d, *v, nullptr).tf.merged();
        return std::make_pair(tf.firstPosition(), tf.lastPosition());
    };
    EXPECT_EQ(span(), std::make_pair(v->valueLo(), v->valueHi()));
    ASSERT_LT(v->valueHi(), 7.0f);
    d.dataRange = std::make_pair(-3.0f, 7.0f);
    EXPECT_EQ(span(), std::make_pair(-3.0f, 7.0f));
    d.tfRange = std::make_pair(1.0f, 2.0f);
    EXPECT_EQ(span(), std::make_pair(1.0f, 2.0f));
}

// A series' percentiles (PictureDescription::dataPercentiles) stand for the volume's own: spiky and
// foggy are fitted to them, layers and ramp span their range; dataRange and --tf-range still win.
TEST(Series, PresetsFollowTheSeriesPercentiles) {
    const std::shared_ptr<const scene::Volume> v = scene::makeVolume(test::makeThreeLevelCloud());
    amr::Percentiles series = v->percentiles;  // another distribution: shifted and stretched
    for (float& x : series.values) x = 2.0f * x + 1.0f;
    PictureDescription d;
    auto tfOf = [&](const char* name) {
        d.tfSource = TfSource{.name = name};
        std::vector<std::string> notes;
        const scene::TfChannels tf = resolvePicture(d, *v, &notes).tf;
        return std::make_pair(tf, notes);
    };
    d.dataPercentiles = series;
    for (const char* name : {"spiky", "foggy"}) {
        const auto [tf, notes] = tfOf(name);
        EXPECT_EQ(tf, scene::TfChannels::split(scene::makePreset(name, series))) << name;
        EXPECT_NE(tf, scene::TfChannels::split(scene::makePreset(name, v->percentiles, v->volumeHistogram))) << name;
        ASSERT_EQ(notes.size(), 1u) << name;
        EXPECT_NE(notes[0].find("series' cell value"), std::string::npos) << notes[0];
    }
    for (const char* name : {"layers", "ramp"})
        EXPECT_EQ(tfOf(name).first, scene::TfChannels::split(scene::makePreset(name, series.lo(), series.hi())))
            << name;
    // With the series' histogram, layers is sized by it (here the volume's own, half as deep).
    amr::VolumeHistogram thin = v->volumeHistogram;
    for (double& x : thin.volume) x *= 0.5;
    d.dataHistogram = thin;
    EXPECT_EQ(tfOf("layers").first, scene::TfChannels::split(scene::makePreset("layers", series, thin)));
    EXPECT_NE(tfOf("layers").first, scene::TfChannels::split(scene::makePreset("layers", series.lo(), series.hi())));
    EXPECT_EQ(tfOf("ramp").first, scene::TfChannels::split(scene::makePreset("ramp", series.lo(), series.hi())));
    d.dataRange = std::make_pair(-3.0f, 7.0f);
    EXPECT_EQ(tfOf("spiky").first, scene::TfChannels::split(scene::makePreset("spiky", -3.0f, 7.0f)));
    d.tfRange = std::make_pair(1.0f, 2.0f);
    EXPECT_EQ(tfOf("spiky").first.opacityPositions.front(), 1.0f);
}
