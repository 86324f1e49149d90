// amrvk view end to end (the binary, validation on): a headless run and a run in a real window
// under Xvfb (swapchain present path) give the image `render` gives for the same session (tile
// z-test shown to reject a 10% density change); a script that orbits, edits the TF and switches
// traversal and mode resets the accumulation at every change and ends at the image of the final
// state; a scripted shader edit changes the picture and a syntax error keeps the previous pipeline
// and names file and line; a real mouse drag (xdotool) turns the camera and a key press quits;
// quitting during a 15 s rebuild hides the window at once; with no display, one line suggests
// --headless. The layout: at 800x600, 1024x720, 1280x800 and 1920x1080 the picture (a uniform
// colour) fills exactly the rectangle the viewer reports and no panel pixel covers it; a drag
// beside the picture does not turn the camera, one of the panel's edge widens it. The log scale: a
// scripted toggle reads the data again, keeps the camera, refits the TF (shape kept) and the
// histogram to log10 of the field's range (computed here from the file), the floor floors it,
// sessions record it, loading a session on another scale reads again, one with another NaN policy
// is refused with the reason, and a field with no positive value is refused with its reason; an
// unedited fitted spiky is fitted again on each scale (its peaks at the log's percentiles).
// The window tests drive the viewer with xdotool and wait only on the state it reports
// (--state-file, tests/viewer_drive.sh), never a fixed pause: they pass on a loaded machine.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "amr/readers.h"
#include "core/image_io.h"
#include "gpu_fixture.h"
#include "image_compare.h"
#include "picture/picture.h"
#include "render/renderer.h"
#include "scene/preview_hold.h"
#include "scene/tf_presets.h"
#include "session/session.h"
#include "test_data.h"
#include "viewer/logic/cut_handles.h"
#include "viewer/logic/data_change.h"

using namespace amrvk;
namespace fs = std::filesystem;

namespace {

std::string amrvkBinary() { return std::string(AMRVK_BINARY_DIR) + "/bin/amrvk"; }
std::string sample() { return std::string(AMRVK_SOURCE_DIR) + "/assets/samples/cloud.cells"; }

// A command line run on an X display of its own (tests/with_xvfb.sh: Xvfb picks a free display
// atomically, so concurrent window tests never share one, whatever ctest -j).
std::string onOwnDisplay(const std::string& commandLine, const std::string& screen = "800x600") {
    return "bash " + std::string(AMRVK_SOURCE_DIR) + "/tests/with_xvfb.sh " + screen + "x24 " + commandLine;
}

// A fresh scratch folder `name` holding a copy of shaders/ (for scripts that edit shaders).
fs::path scratchWithShaders(const std::string& name) {
    const fs::path dir = test::scratchDir() / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    fs::copy(fs::path(AMRVK_SOURCE_DIR) / "shaders", dir / "shaders", fs::copy_options::recursive);
    return dir;
}

// A driver script for a window test, run as `bash drive.sh AMRVK INPUT DIR` on a display of its
// own: `amrvk view INPUT viewArgs --state-file DIR/state.json` in the background under a
// `limitSeconds` timeout (a lost key fails the test, it does not hang it), then `body`, which
// drives it with tests/viewer_drive.sh: every wait on the state the viewer reports, never a sleep.
std::string driveScript(const std::string& viewArgs, const std::string& body, int limitSeconds = 300) {
    return "set -u\n"
           ". '" + std::string(AMRVK_SOURCE_DIR) + "/tests/viewer_drive.sh'\n"
           "STATE=\"$3/state.json\"\n"
           "rm -f \"$STATE\"\n"  // not a previous run's
           "timeout " + std::to_string(limitSeconds) + " \"$1\" view \"$2\" " + viewArgs +
           " --state-file \"$STATE\" --validation & VIEWER=$!\n" + body;
}

bool onPath(const char* tool) { return std::system((std::string("command -v ") + tool + " >/dev/null 2>&1").c_str()) == 0; }

// Runs a shell command line with stdout and stderr into files under dir; returns the exit status.
int run(const std::string& commandLine, const fs::path& dir, const std::string& tag) {
    const std::string cmd = commandLine + " >" + (dir / (tag + ".out")).string() + " 2>" + (dir / (tag + ".err")).string();
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The picture options every run here shares: small, quick, and sensitive to the density (an
// optically thin-to-medium cloud on black, so the comparison has power).
const std::string kPicture = " --size 48x32 --scale linear --tf ramp --tf-range 0 1.2 --density-scale 1 --grid 16 --mode ae"
                             " --background 0 0 0 --backend sw";

// `render` of a session in process, with another seed (independent samples) and a density factor.
scene::RenderOutput renderSession(gpu::Context& ctx, const session::Session& s, uint32_t seedOffset, double densityFactor) {
    session::PictureDescription d;
    d.session = s;
    d.session.settings.seed += seedOffset;
    d.session.settings.densityScale *= densityFactor;
    return picture::makePicture(ctx, session::loadVolume(d.session), d).render();
}

// The viewer's screenshot as a RenderOutput with the reference's per-pixel sample variance (same
// estimator and sample count, so the same variance), for the tile z-test.
scene::RenderOutput withVarianceOf(const Image& image, const scene::RenderOutput& ref) {
    scene::RenderOutput o;
    o.mean = image;
    o.spp = ref.spp;
    o.sumSq.resize(image.pixels.size());
    const double n = ref.spp;
    for (size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double m = image.pixels[i][c];
            o.sumSq[i][c] = float(test::sampleVariance(ref, i, c) * (n - 1) + n * m * m);
        }
    return o;
}

nlohmann::json readJson(const fs::path& p) { return nlohmann::json::parse(test::readAll(p)); }

// A rectangle of the viewer's layout (--stats, --state-file: framebuffer pixels, half-open).
struct Rect {
    int x, y, width, height;
    bool contains(int px, int py) const { return px >= x && py >= y && px < x + width && py < y + height; }
};
Rect rectOf(const nlohmann::json& j) {
    return {j["x"].get<int>(), j["y"].get<int>(), j["width"].get<int>(), j["height"].get<int>()};
}

class ViewerGpu : public test::GpuTest {
protected:
    void SetUp() override {
        test::GpuTest::SetUp();
        if (!fs::exists(amrvkBinary())) GTEST_SKIP() << "amrvk binary not built: " << amrvkBinary();
    }

    // The viewer's image of `dir`/final.pfm against render of `dir`/final.json: equal, and the
    // comparison rejects a 10% denser medium.
    void expectSameAsRender(const fs::path& dir, const std::string& tag) {
        const session::Session s = session::loadSession(dir / "final.json");
        const Image shot = readPfm(dir / "final.pfm");
        const scene::RenderOutput ref = renderSession(ctx(), s, 1000, 1.0);
        ASSERT_EQ(shot.width, ref.mean.width);
        ASSERT_EQ(shot.height, ref.mean.height);
        const scene::RenderOutput viewer = withVarianceOf(shot, ref);
        test::expectSameImage(viewer, ref, 16, tag, 1e-4);
        const scene::RenderOutput denser = renderSession(ctx(), s, 1000, 1.1);
        EXPECT_GT(test::countDifferingTiles(viewer, denser, 16, 1e-4, 1e-6), 0)
            << "the comparison must reject a 10% density change (power)";
    }
};

}  // namespace

TEST_F(ViewerGpu, HeadlessScreenshotEqualsRenderOfTheSameSession) {
    const fs::path dir = test::scratchDir() / "viewer-headless";
    fs::create_directories(dir);
    const int rc = run(amrvkBinary() + " view " + sample() + kPicture + " --spp 128 --headless --frames 400 --screenshot " +
                           (dir / "final.pfm").string() + " --save-session " + (dir / "final.json").string() +
                           " --validation",
                       dir, "view");
    ASSERT_EQ(rc, 0) << test::readAll(dir / "view.err");
    expectSameAsRender(dir, "viewer-headless");
}

// Never a worse picture than the one it replaces (scene/preview_hold.h): in a scattering haze the
// ray-marched preview stays on screen (a screenshot saves it, and says so) until the estimate's
// measured noise is as low, then the estimate shows. The preview is told from the estimate by its
// picture: dvr's (no scattered light) where the estimate converges to ms's, 15-50x apart here.
TEST_F(ViewerGpu, ThePreviewStaysUntilTheEstimateIsAsClean) {
    const fs::path dir = test::scratchDir() / "viewer-preview-hold";
    fs::create_directories(dir);
    test::writeAll(dir / "script.txt", "1 screenshot " + (dir / "early.pfm").string() + "\n");
    const std::string picture =
        " --size 48x32 --scale linear --tf ramp --tf-range 0 1.2 --grid 16 --mode ms"
        " --light-dir 1 -1 2 3 3 3 --background 0 0 0 --backend sw";
    const int rc =
        run(amrvkBinary() + " view " + sample() + picture + " --headless --frames 150 --script " +
                (dir / "script.txt").string() + " --stats " + (dir / "stats.json").string() + " --screenshot " +
                (dir / "final.pfm").string() + " --save-session " + (dir / "final.json").string() + " --validation",
            dir, "view");
    const std::string err = test::readAll(dir / "view.err");
    ASSERT_EQ(rc, 0) << err;
    EXPECT_NE(err.find("early.pfm: the ray-marched preview"), std::string::npos) << err;
    EXPECT_NE(err.find("final.pfm: the path-traced estimate"), std::string::npos) << err;
    const nlohmann::json stats = readJson(dir / "stats.json");
    ASSERT_EQ(stats["shown"], "estimate") << stats.dump();
    const nlohmann::json& shown = stats["estimateShown"];
    ASSERT_TRUE(shown.is_object()) << stats.dump();
    EXPECT_FALSE(shown["atLimit"].get<bool>());
    // It gave way only once measured as clean as the preview (and the preview was grainier than
    // the no-grain level, so the wait was the preview's).
    const double previewNoise = stats["previewNoise"].get<double>();
    EXPECT_GT(previewNoise, scene::kNoVisibleNoise);
    EXPECT_LE(shown["noise"].get<double>(), previewNoise);
    EXPECT_GT(shown["spp"].get<uint32_t>(), 16u) << "an ms estimate at a few spp is far grainier than the preview";

    session::Session s = session::loadSession(dir / "final.json");
    s.spp = 1024;
    const scene::RenderOutput ms = renderSession(ctx(), s, 1000, 1.0);
    s.settings.mode = scene::Mode::Dvr;
    s.spp = 64;
    const scene::RenderOutput dvr = renderSession(ctx(), s, 1000, 1.0);
    auto meanAbsDiff = [](const Image& a, const Image& b) {
        double sum = 0;
        for (size_t i = 0; i < a.pixels.size(); ++i)
            for (int c = 0; c < 3; ++c) sum += std::abs(double(a.pixels[i][c]) - double(b.pixels[i][c]));
        return sum / double(3 * a.pixels.size());
    };
    const Image early = readPfm(dir / "early.pfm"), final = readPfm(dir / "final.pfm");
    ASSERT_EQ(early.width, 48);
    ASSERT_EQ(early.height, 32);
    EXPECT_LT(meanAbsDiff(early, dvr.mean), 0.25 * meanAbsDiff(early, ms.mean))
        << "the early screenshot is the preview";
    EXPECT_LT(meanAbsDiff(final, ms.mean), 0.25 * meanAbsDiff(final, dvr.mean)) << "the final one is the estimate";
}

// A time series in the viewer (issue 53, point 3): stepping shows each step's picture (the
// screenshot at step k equals render of the session saved there, whose input is step k's; the
// z-test rejects another step's picture), the steps next to the shown one are read ahead, and the
// step says when it is (amrvk info's time of each Chombo output).
TEST_F(ViewerGpu, SteppingASeriesShowsEachStepsPicture) {
    const fs::path dir = test::scratchDir() / "viewer-series";
    fs::create_directories(dir);
    for (const auto& [name, time] :
         std::vector<std::pair<std::string, std::string>>{{"1", "0"}, {"2", "0.4"}, {"10", "0.8"}})
        ASSERT_EQ(run(amrvkBinary() + " gen cloud --cells 3000 --seed 3 --time " + time + " -o " +
                          (dir / ("out_" + name)).string(),
                      dir, "gen"),
                  0)
            << test::readAll(dir / "gen.err");
    auto at = [&](const std::string& f) { return (dir / f).string(); };
    test::writeAll(dir / "script.txt", "0 step 2\n40 screenshot " + at("s2.pfm") + "\n40 save-session " +
                                           at("s2.json") + "\n41 step 0\n80 screenshot " + at("s0.pfm") +
                                           "\n80 save-session " + at("s0.json") + "\n81 quit\n");
    const int rc =
        run(amrvkBinary() + " view '" + at("out_*.cells") + "'" + kPicture + " --spp 64 --headless --script " +
                at("script.txt") + " --stats " + at("stats.json") + " --validation",
            dir, "view");
    ASSERT_EQ(rc, 0) << test::readAll(dir / "view.err");
    const session::Session s2 = session::loadSession(dir / "s2.json"), s0 = session::loadSession(dir / "s0.json");
    EXPECT_EQ(fs::path(s2.input).filename(), "out_10.cells") << "step 2 in natural order";
    EXPECT_EQ(fs::path(s0.input).filename(), "out_1.cells");
    EXPECT_TRUE(s2.tf == s0.tf) << "one TF over the series";
    const scene::RenderOutput ref2 = renderSession(ctx(), s2, 1000, 1.0), ref0 = renderSession(ctx(), s0, 1000, 1.0);
    const scene::RenderOutput shot2 = withVarianceOf(readPfm(dir / "s2.pfm"), ref2);
    const scene::RenderOutput shot0 = withVarianceOf(readPfm(dir / "s0.pfm"), ref0);
    test::expectSameImage(shot2, ref2, 16, "series step 2", 1e-4);
    test::expectSameImage(shot0, ref0, 16, "series step 0", 1e-4);
    EXPECT_GT(test::countDifferingTiles(shot2, ref0, 16, 1e-4, 1e-6), 0) << "power: step 2 is not step 0's picture";
    // Step 0 came after step 2: its neighbour, read ahead meanwhile.
    const nlohmann::json stats = readJson(dir / "stats.json");
    ASSERT_EQ(stats["steps"].size(), 2u) << stats.dump();
    EXPECT_EQ(stats["steps"][1]["step"], 0);
    EXPECT_TRUE(stats["steps"][1]["wasAhead"].get<bool>()) << stats["steps"].dump();

    // When each step is: Chombo's two outputs of the mushy layer record their times.
    const fs::path chombo = test::dataDir() / "chombo_mushy_layer_2d";
    test::writeAll(dir / "when.txt", "1 step 1\n3 quit\n");
    ASSERT_EQ(run(amrvkBinary() + " view '" + (chombo / "plt*.2d.hdf5").string() +
                      "' --size 16x16 --headless --script " + at("when.txt") + " --state-file " + at("state.json"),
                  dir, "when"),
              0)
        << test::readAll(dir / "when.err");
    const nlohmann::json state = readJson(dir / "state.json");
    EXPECT_EQ(state["series"]["step"], 1);
    EXPECT_EQ(state["series"]["when"], "t = 0.0494106");  // plt025000's time attribute: 0.0494105884 (h5py)
}

TEST_F(ViewerGpu, WindowUnderXvfbEqualsRenderOfTheSameSession) {
    if (!onPath("Xvfb")) GTEST_SKIP() << "Xvfb is not installed (apt-get install xvfb)";
    const fs::path dir = test::scratchDir() / "viewer-window";
    fs::create_directories(dir);
    const int rc = run(onOwnDisplay(amrvkBinary() + " view " + sample() + kPicture) +
                           " --spp 128 --frames 300 --window 640x480 --screenshot " + (dir / "final.pfm").string() +
                           " --save-session " + (dir / "final.json").string() + " --validation",
                       dir, "view");
    ASSERT_EQ(rc, 0) << test::readAll(dir / "view.err");
    expectSameAsRender(dir, "viewer-window");
}

TEST_F(ViewerGpu, ScriptedEditsResetTheImageAndEndAtTheFinalState) {
    const fs::path dir = test::scratchDir() / "viewer-script";
    fs::create_directories(dir);
    test::writeAll(dir / "script.txt", "5 orbit 40 10\n"
                                       "10 tf-range 0 0.8\n"
                                       "15 traversal abr\n"
                                       "20 mode dvr\n"
                                       "25 zoom 1\n"
                                       "30 crop 0 0 0 512 512 460\n"
                                       "35 clip 420 420 256 1 1 0\n");
    const int rc = run(amrvkBinary() + " view " + sample() + kPicture + " --spp 128 --headless --frames 600 --script " +
                           (dir / "script.txt").string() + " --stats " + (dir / "stats.json").string() +
                           " --screenshot " + (dir / "final.pfm").string() + " --save-session " +
                           (dir / "final.json").string() + " --validation",
                       dir, "view");
    ASSERT_EQ(rc, 0) << test::readAll(dir / "view.err");
    const nlohmann::json stats = readJson(dir / "stats.json");
    const std::vector<std::pair<uint64_t, std::string>> expected = {
        {5, "camera"}, {10, "transfer function"}, {15, "structure"}, {20, "mode"}, {25, "camera"},
        {30, "medium"}, {35, "medium"}};
    for (const auto& [frame, what] : expected) {
        bool found = false;
        for (const auto& r : stats["resets"])
            if (r["frame"].get<uint64_t>() == frame && r["what"].get<std::string>() == what) {
                found = true;
                EXPECT_EQ(r["samplesLeft"].get<uint32_t>(), 0u) << what << " at frame " << frame;
            }
        EXPECT_TRUE(found) << "no reset for " << what << " at frame " << frame << ": " << stats["resets"].dump();
    }
    EXPECT_EQ(stats["spp"].get<uint32_t>(), 128u);
    // Previews (the first frame, and after each edit) are ray-marched whatever the picture's mode.
    ASSERT_TRUE(stats["previewFrames"].is_object()) << stats.dump();
    EXPECT_GE(stats["previewFrames"].value("dvr", uint64_t(0)), expected.size() + 1) << stats["previewFrames"].dump();
    EXPECT_EQ(stats["previewFrames"].size(), 1u) << stats["previewFrames"].dump();
    const session::Session s = session::loadSession(dir / "final.json");
    EXPECT_EQ(s.structure.traversal, scene::TraversalKind::Abr);
    EXPECT_EQ(s.settings.mode, scene::Mode::Dvr);
    EXPECT_FLOAT_EQ(s.tf.merged().lastPosition(), 0.8f);
    ASSERT_TRUE(s.settings.cut.crop.has_value());
    EXPECT_EQ(s.settings.cut.crop->hi, glm::dvec3(512, 512, 460));
    ASSERT_EQ(s.settings.cut.clips.size(), 1u);
    EXPECT_EQ(s.settings.cut.clips[0].normal, glm::dvec3(1, 1, 0));
    expectSameAsRender(dir, "viewer-script");
}

TEST_F(ViewerGpu, ShaderEditsReloadAndAnErrorKeepsThePreviousPipeline) {
    const fs::path dir = scratchWithShaders("viewer-reload");
    // ae with a camera looking past the data: every pixel is the background radiance (1, given).
    test::writeAll(dir / "script.txt",
                   "3 screenshot " + (dir / "before.pfm").string() + "\n"
                   "4 edit-shader ../lib/estimator.glsl \"? color : P.shading.background;\" \"? color : 2.0 * P.shading.background;\"\n"
                   "5 reload\n"
                   "30 screenshot " + (dir / "after.pfm").string() + "\n"
                   "31 edit-shader ../lib/tf.glsl \"if (lo > hi) return 0.0;\" \"if (lo > hi) return 0.0 +;\"\n"
                   "32 reload\n"
                   "60 screenshot " + (dir / "kept.pfm").string() + "\n"
                   "61 quit\n");
    const int rc = run(amrvkBinary() + " view " + sample() + " --size 8x8 --mode ae --spp 4 --background 1 1 1 --backend sw --camera 1000 0 0 "
                           "2000 0 0 0 0 1 --headless --shader-dir " + (dir / "shaders" / "passes").string() +
                           " --script " + (dir / "script.txt").string() + " --validation",
                       dir, "view");
    const std::string err = test::readAll(dir / "view.err");
    ASSERT_EQ(rc, 0) << err;
    EXPECT_FLOAT_EQ(readPfm(dir / "before.pfm").pixels[0].r, 1.0f);
    EXPECT_FLOAT_EQ(readPfm(dir / "after.pfm").pixels[0].r, 2.0f) << "the edited shader runs";
    EXPECT_FLOAT_EQ(readPfm(dir / "kept.pfm").pixels[0].r, 2.0f) << "a failed compile keeps the previous pipeline";
    EXPECT_NE(err.find("previous pipeline kept"), std::string::npos) << err;
    int line = 0;
    {
        std::ifstream in(dir / "shaders" / "lib" / "tf.glsl");
        std::string text;
        for (int n = 1; std::getline(in, text); ++n)
            if (text.find("return 0.0 +;") != std::string::npos) line = n;
    }
    EXPECT_NE(err.find("tf.glsl:" + std::to_string(line)), std::string::npos) << "file and line: " << err;
}

TEST_F(ViewerGpu, EveryScriptActionRunsAtFrameZeroAndAFailingLineIsNamed) {
    const fs::path dir = scratchWithShaders("viewer-all-actions");
    // Every documented action at frame 0 (docs/viewer.md), the same frame a script starts with.
    test::writeAll(dir / "script.txt",
                   "0 orbit 10 5\n0 pan 3 -2\n0 zoom 1\n0 tf-preset foggy\n0 tf-range 0.1 1.5\n0 density 2\n"
                   "0 mode ss\n0 traversal grid-bvh\n0 sampler abr\n0 backend sw\n0 grid 8\n"
                   "0 clip 1 2 3 0 0 1\n0 cut-off\n0 crop 0 0 0 512 512 400\n0 clip 256 256 256 0 1 0\n"
                   "0 edit-shader path_trace.comp \"void main() {\" \"void main() { // edited\"\n0 reload\n0 legend on\n0 tf-colors linear\n"
                   "0 keyframe-add 0\n0 keyframe-add 5\n0 keyframe-move 5 6\n0 keyframe-add 3\n0 keyframe-delete 3\n"
                   "0 path-fps 12\n0 path-frame 2\n0 path-play\n0 path-stop\n"
                   "0 screenshot " + (dir / "shot.pfm").string() + "\n0 save-session " + (dir / "s.json").string() +
                   "\n0 scale log\n0 log-floor 0.01\n0 load-session " + (dir / "s.json").string() +
                   "\n0 capture-window " + (dir / "w.png").string() + "\n1 quit\n");
    int rc = run(amrvkBinary() + " view " + sample() + kPicture + " --headless --shader-dir " +
                     (dir / "shaders" / "passes").string() + " --script " + (dir / "script.txt").string() +
                     " --validation",
                 dir, "view");
    ASSERT_EQ(rc, 0) << test::readAll(dir / "view.err");
    EXPECT_TRUE(fs::exists(dir / "shot.pfm"));
    EXPECT_FALSE(fs::exists(dir / "w.png")) << "capture-window is a no-op without a window";
    const session::Session s = session::loadSession(dir / "s.json");
    EXPECT_EQ(s.settings.mode, scene::Mode::Ss);
    EXPECT_EQ(s.settings.densityScale, 2.0);
    EXPECT_EQ(s.structure.traversal, scene::TraversalKind::GridBvh);
    EXPECT_EQ(s.structure.sampler, scene::SamplerKind::Abr);
    EXPECT_EQ(s.structure.grid, "8");
    EXPECT_TRUE(s.legend.show);
    EXPECT_EQ(s.tfColors, scene::TfColors::Linear);
    EXPECT_FLOAT_EQ(s.tf.merged().lastPosition(), 1.5f);
    ASSERT_EQ(s.cameraPath.keyframes().size(), 2u);
    EXPECT_EQ(s.cameraPath.keyframes()[1].frame, 6u) << "keyframe-move 5 6";
    EXPECT_EQ(s.cameraPath.fps(), 12.0);
    ASSERT_TRUE(s.settings.cut.crop.has_value());
    EXPECT_EQ(s.settings.cut.crop->hi.z, 400.0);
    ASSERT_EQ(s.settings.cut.clips.size(), 1u) << "cut-off removed the first plane";
    EXPECT_EQ(s.settings.cut.clips[0].point, glm::dvec3(256.0));
    EXPECT_NE(test::readAll(dir / "shaders/passes/path_trace.comp").find("// edited"), std::string::npos);

    // A line that passes every check before frame 0 but fails when it runs (the dense grid over
    // its limit) is an error naming the line; the session asked for at exit is not written.
    test::writeAll(dir / "fails.txt", "0 mode ae\n2 sampler dense\n");
    rc = run(amrvkBinary() + " view " + sample() + kPicture + " --dense-max-mib 1 --headless --frames 10 --script " +
                 (dir / "fails.txt").string() + " --save-session " + (dir / "never.json").string(),
             dir, "fails");
    const std::string err = test::readAll(dir / "fails.err");
    EXPECT_EQ(rc, 1) << err;
    EXPECT_NE(err.find("fails.txt:2: sampler:"), std::string::npos) << err;
    EXPECT_NE(err.find("--dense-max-mib"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(dir / "never.json"));
    // A combination that cannot run at all is refused before frame 0 (nothing rendered).
    test::writeAll(dir / "invalid.txt", "0 traversal abr\n0 sampler dense\n");
    rc = run(amrvkBinary() + " view " + sample() + kPicture + " --headless --frames 10 --script " +
                 (dir / "invalid.txt").string(),
             dir, "invalid");
    EXPECT_EQ(rc, 1);
    EXPECT_NE(test::readAll(dir / "invalid.err").find("invalid.txt:2: sampler: --sampler dense needs"), std::string::npos)
        << test::readAll(dir / "invalid.err");
}

TEST_F(ViewerGpu, RealMouseDragTurnsTheCameraAndAKeyQuits) {
    if (!onPath("Xvfb") || !onPath("xdotool")) GTEST_SKIP() << "Xvfb or xdotool is not installed";
    const fs::path dir = test::scratchDir() / "viewer-mouse";
    fs::create_directories(dir);
    // From 30 pixels left of the picture's centre, 60 then 110 pixels right and 20 then 30 down,
    // each step taken by the viewer before the next.
    test::writeAll(dir / "drive.sh",
                   driveScript("--size 64x48 --window 800x600 --backend sw --grid 32 --save-session \"$3/final.json\"",
                               "wait_first_frame\n"
                               "read -r x y <<<\"$(centre picture)\"\n"
                               "move $((x - 30)) $y\n"
                               "press\n"
                               "move $((x + 30)) $((y + 20))\n"
                               "move $((x + 80)) $((y + 30))\n"
                               "release\n"
                               "settle\n"
                               "quit\n"));
    const int rc = run(onOwnDisplay("bash " + (dir / "drive.sh").string() + " " + amrvkBinary()) +
                           " " + sample() + " " + dir.string(),
                       dir, "view");
    ASSERT_EQ(rc, 0) << test::readAll(dir / "view.err");
    const session::Session s = session::loadSession(dir / "final.json");
    const amr::Model m = amr::readModel(sample(), {});
    const amr::ModelSummary sum = amr::summarize(m);
    const scene::Camera start = scene::defaultCamera(m.voxelToWorld.toWorld(glm::dvec3(sum.bounds.lower)),
                                                     m.voxelToWorld.toWorld(glm::dvec3(sum.bounds.upper)));
    EXPECT_GT(glm::length(s.settings.camera.eye - start.eye), 1e-3 * glm::length(start.eye - start.target))
        << "the drag turned the camera";
    EXPECT_NEAR(glm::length(s.settings.camera.eye - s.settings.camera.target), glm::length(start.eye - start.target),
                1e-6 * glm::length(start.eye - start.target))
        << "an orbit keeps the distance";
}

TEST_F(ViewerGpu, DraggingACropHandleMovesItsFaceNotTheCamera) {
    if (!onPath("Xvfb") || !onPath("xdotool")) GTEST_SKIP() << "Xvfb or xdotool is not installed";
    const fs::path dir = test::scratchDir() / "viewer-crop-handle";
    fs::create_directories(dir);
    // The upper x face's handle is found as the viewer finds it (in the 64x48 image), the driver
    // puts it in the window through the picture rectangle the viewer reports, and the pointer
    // drags it 40 pixels along the face normal's screen direction.
    const amr::Model m = amr::readModel(sample(), {});
    const amr::ModelSummary sum = amr::summarize(m);
    const scene::Camera cam = scene::defaultCamera(m.voxelToWorld.toWorld(glm::dvec3(sum.bounds.lower)),
                                                   m.voxelToWorld.toWorld(glm::dvec3(sum.bounds.upper)));
    const scene::CropBox box{{100, 100, 100}, {400, 400, 400}};
    const auto handle = viewer::CutHandles::project(cam, 64, 48, viewer::CutHandles::faceCentre(box, 1));
    const auto further = viewer::CutHandles::project(cam, 64, 48, viewer::CutHandles::faceCentre(box, 1) + glm::dvec3(1, 0, 0));
    ASSERT_TRUE(handle && further);
    const glm::dvec2 along = glm::normalize(*further - *handle);
    const long dx = std::lround(40 * along.x), dy = std::lround(40 * along.y);
    test::writeAll(dir / "drive.sh",
                   driveScript("--size 64x48 --window 800x600 --backend sw --grid 32 --crop 100 100 100 400 400 400 "
                               "--save-session \"$3/final.json\" --stats \"$3/stats.json\"",
                               "wait_first_frame\n"
                               "read -r x y <<<\"$(to_window " + std::to_string(handle->x) + " " +
                                   std::to_string(handle->y) + ")\"\n"
                               "move $x $y\n"
                               "press\n"
                               "move $((x + " + std::to_string(dx) + " / 2)) $((y + " + std::to_string(dy) + " / 2))\n"
                               "move $((x + " + std::to_string(dx) + ")) $((y + " + std::to_string(dy) + "))\n"
                               "release\n"
                               "settle\n"
                               "quit\n"));
    const int rc = run(onOwnDisplay("bash " + (dir / "drive.sh").string() + " " + amrvkBinary()) + " " + sample() + " " +
                           dir.string(),
                       dir, "view");
    ASSERT_EQ(rc, 0) << test::readAll(dir / "view.err");
    const Rect picture = rectOf(readJson(dir / "stats.json")["layout"]["picture"]);
    const double scale = picture.width / 64.0;  // window pixels per image pixel
    const session::Session s = session::loadSession(dir / "final.json");
    EXPECT_EQ(s.settings.camera, cam) << "a press on a handle does not orbit";
    ASSERT_TRUE(s.settings.cut.crop.has_value());
    const scene::CropBox& got = *s.settings.cut.crop;
    // 40 pixels along the normal's screen direction: the world distance whose projection moves the
    // handle that far (the drag's own rule; perspective changes it a little as the face moves).
    const double expected = 40.0 / scale / glm::length(*further - *handle);
    EXPECT_NEAR(got.hi.x - 400.0, expected, 0.25 * expected + 1.0) << "the upper x face followed the pointer";
    EXPECT_EQ(got.lo, box.lo);
    EXPECT_EQ(got.hi.y, 400.0);
    EXPECT_EQ(got.hi.z, 400.0);
}

TEST_F(ViewerGpu, ClosingDuringALongRebuildHidesTheWindowAtOnce) {
    if (!onPath("Xvfb") || !onPath("xdotool")) GTEST_SKIP() << "Xvfb or xdotool is not installed";
    const fs::path dir = test::scratchDir() / "viewer-close-during-build";
    fs::create_directories(dir);
    // A kd-tree of 10^6 leaves over 2 * 10^6 cells: about 15 s of building on a 2-core CPU.
    ASSERT_EQ(run(amrvkBinary() + " gen cloud --cells 2000000 --seed 3 -o " + (dir / "big").string(), dir, "gen"), 0)
        << test::readAll(dir / "gen.err");
    // The key goes in once the window shows and the viewer reports the build running beside its
    // event loop (the state it writes as a rebuild starts).
    test::writeAll(dir / "drive.sh",
                   driveScript("--traversal kdtree --kd-leaves 1000000 --size 64x48 --backend sw",
                               "visible() { xdotool search --onlyvisible --name 'amrvk view' >/dev/null 2>&1; }\n"
                               "building() { [ \"$(state building)\" = true ]; }\n"
                               "wait_until 'the window' visible\n"
                               "wait_until 'the build running' building\n"
                               "xdotool key q\n"
                               // Hidden within 5 s, while the build (about 15 s) still runs.
                               "for i in $(seq 20); do visible || break; sleep 0.25; done\n"
                               "visible && echo visible || echo hidden\n"
                               "kill -0 $VIEWER 2>/dev/null && echo running || echo ended\n"
                               "wait $VIEWER\n",
                               600));
    const int rc = run(onOwnDisplay("bash " + (dir / "drive.sh").string() + " " + amrvkBinary()) +
                           " " + (dir / "big.cells").string() + " " + dir.string(),
                       dir, "view");
    const std::string out = test::readAll(dir / "view.out"), err = test::readAll(dir / "view.err");
    ASSERT_EQ(rc, 0) << err;
    EXPECT_NE(out.find("hidden"), std::string::npos) << "the window stays until the build ends: " << out;
    EXPECT_NE(out.find("running"), std::string::npos) << "the build ended before the check; no evidence: " << out;
    EXPECT_NE(err.find("closing when the build in progress returns"), std::string::npos) << err;
}

TEST_F(ViewerGpu, WithoutADisplayTheErrorSuggestsHeadless) {
    const fs::path dir = test::scratchDir() / "viewer-no-display";
    fs::create_directories(dir);
    const int rc = run("env -u DISPLAY -u WAYLAND_DISPLAY " + amrvkBinary() + " view " + sample() + " --frames 2", dir,
                       "view");
    const std::string err = test::readAll(dir / "view.err");
    EXPECT_EQ(rc, 1) << err;
    EXPECT_NE(err.find("--headless"), std::string::npos) << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << "one line: " << err;
}

// The picture looks past the data at a magenta background (ae: every pixel exactly sRGB 255, 0,
// 255 from the first sample), so the window capture shows where it is: every pixel of the
// reported picture rectangle is magenta, no other pixel is (the panel and the bars beside the
// picture are not), and the reported panel and picture do not overlap.
TEST_F(ViewerGpu, PanelAndPictureNeverOverlapAtCommonWindowSizes) {
    if (!onPath("Xvfb")) GTEST_SKIP() << "Xvfb is not installed (apt-get install xvfb)";
    const fs::path dir = test::scratchDir() / "viewer-layout";
    fs::remove_all(dir);
    fs::create_directories(dir);
    for (const auto& [w, h] : {std::pair{800, 600}, std::pair{1024, 720}, std::pair{1280, 800}, std::pair{1920, 1080}}) {
        const std::string size = std::to_string(w) + "x" + std::to_string(h);
        SCOPED_TRACE(size);
        const fs::path shot = dir / ("window-" + size + ".png"), stats = dir / ("stats-" + size + ".json");
        test::writeAll(dir / "script.txt", "12 capture-window " + shot.string() + "\n13 quit\n");
        const int rc = run(onOwnDisplay(amrvkBinary() + " view " + sample() +
                                            " --size 64x48 --mode ae --spp 1 --backend sw --grid 8 --background 1 0 1"
                                            " --camera 1000 0 0 2000 0 0 0 0 1 --window " + size + " --script " +
                                            (dir / "script.txt").string() + " --stats " + stats.string() +
                                            " --validation",
                                        "3840x2160"),  // the pointer starts at the centre, off the window
                           dir, "view-" + size);
        ASSERT_EQ(rc, 0) << test::readAll(dir / ("view-" + size + ".err"));
        const nlohmann::json layout = readJson(stats)["layout"];
        const Rect window = rectOf(layout["window"]), panel = rectOf(layout["panel"]),
                   picture = rectOf(layout["picture"]);
        EXPECT_EQ(window.width, w);
        EXPECT_EQ(window.height, h);
        EXPECT_GT(picture.width, 0);
        EXPECT_GT(picture.height, 0);
        EXPECT_GE(panel.width, 300) << "room for the labels";
        EXPECT_TRUE(picture.x + picture.width <= panel.x || panel.x + panel.width <= picture.x)
            << "the rectangles overlap: " << layout.dump();
        const Image8 png = readPng(shot);
        ASSERT_EQ(png.width, w);
        ASSERT_EQ(png.height, h);
        long magentaInside = 0, magentaOutside = 0, panelMagenta = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const uint8_t* p = &png.rgba[(size_t(y) * size_t(w) + size_t(x)) * 4];
                const bool magenta = p[0] == 255 && p[1] == 0 && p[2] == 255;
                if (picture.contains(x, y)) magentaInside += magenta;
                else magentaOutside += magenta;
                if (panel.contains(x, y)) panelMagenta += magenta;
            }
        EXPECT_EQ(magentaInside, long(picture.width) * picture.height) << "something covers the picture";
        EXPECT_EQ(magentaOutside, 0) << "the picture reaches outside its rectangle";
        EXPECT_EQ(panelMagenta, 0);
        // The picture keeps the image's aspect (64x48) to a pixel.
        EXPECT_NEAR(double(picture.width) * 48.0, double(picture.height) * 64.0, 64.0 + 48.0);
    }
}

// A drag and the wheel beside the picture leave the camera alone; a drag of the panel's left edge
// widens the panel, and the picture moves aside.
TEST_F(ViewerGpu, ADragBesideThePictureLeavesTheCamera) {
    if (!onPath("Xvfb") || !onPath("xdotool")) GTEST_SKIP() << "Xvfb or xdotool is not installed";
    const fs::path dir = test::scratchDir() / "viewer-drag-beside";
    fs::create_directories(dir);
    // The drag and the wheel start beside the picture: below it, halfway to the window's bottom
    // edge (the driver records the point and the layout it saw, start.json).
    test::writeAll(dir / "drive.sh",
                   driveScript("--size 64x48 --window 800x600 --backend sw --grid 32 --save-session \"$3/final.json\" "
                               "--stats \"$3/stats.json\"",
                               "wait_first_frame\n"
                               "cp \"$STATE\" \"$3/start.json\"\n"
                               "read -r x y <<<\"$(centre picture)\"\n"
                               "x=$((x - 30)) y=$((($(state picture y) + $(state picture height) + $(state window height)) / 2))\n"
                               "echo \"$x $y\" >\"$3/beside.txt\"\n"
                               "move $x $y\n"
                               "press\n"
                               "move $((x + 60)) $((y + 20))\n"
                               "move $((x + 110)) $((y + 30))\n"
                               "release\n"
                               "move $x $y\n"
                               "wheel_up 2\n"
                               // The panel's left edge dragged 100 pixels left, a step at a time:
                               // ImGui reads the pointer once a frame.
                               "x=$(($(state panel x) + 1)) y=$(($(state panel y) + $(state panel height) / 2))\n"
                               "move $x $y\n"
                               "settle\n"
                               "press\n"
                               "for dx in 31 61 100; do move $((x - dx)) $y; done\n"
                               "release\n"
                               "settle\n"
                               "quit\n"));
    const int rc = run(onOwnDisplay("bash " + (dir / "drive.sh").string() + " " + amrvkBinary()) + " " + sample() +
                           " " + dir.string(),
                       dir, "view");
    ASSERT_EQ(rc, 0) << test::readAll(dir / "view.err");
    const nlohmann::json seen = readJson(dir / "start.json")["layout"], layout = readJson(dir / "stats.json")["layout"];
    int bx = -1, by = -1;
    std::ifstream(dir / "beside.txt") >> bx >> by;
    ASSERT_TRUE(rectOf(seen["window"]).contains(bx, by)) << bx << " " << by << " " << seen.dump();
    ASSERT_FALSE(rectOf(seen["picture"]).contains(bx, by)) << "the drag must start beside the picture";
    ASSERT_FALSE(rectOf(seen["panel"]).contains(bx, by)) << "the drag must start beside the picture";
    const Rect picture = rectOf(layout["picture"]), panel = rectOf(layout["panel"]);
    // The panel took the drag of its edge (about 100 pixels wider) and the picture moved aside.
    EXPECT_NEAR(panel.width, rectOf(seen["panel"]).width + 100, 8) << layout.dump();
    EXPECT_EQ(panel.x + panel.width, 800);
    EXPECT_LE(picture.x + picture.width, panel.x);
    const session::Session s = session::loadSession(dir / "final.json");
    const amr::Model m = amr::readModel(sample(), {});
    const amr::ModelSummary sum = amr::summarize(m);
    const scene::Camera start = scene::defaultCamera(m.voxelToWorld.toWorld(glm::dvec3(sum.bounds.lower)),
                                                     m.voxelToWorld.toWorld(glm::dvec3(sum.bounds.upper)));
    EXPECT_LT(glm::length(s.settings.camera.eye - start.eye), 1e-6 * glm::length(start.eye - start.target))
        << "a drag or the wheel beside the picture moved the camera";
}

// "image size = picture area" (camera panel, clicked with xdotool at 1920x1080 where the viewer
// reports them: the camera header, then the checkbox it shows) makes the rendered image the area
// beside the panel, so the camera's aspect follows it.
TEST_F(ViewerGpu, TheImageCanFollowThePictureArea) {
    if (!onPath("Xvfb") || !onPath("xdotool")) GTEST_SKIP() << "Xvfb or xdotool is not installed";
    const fs::path dir = test::scratchDir() / "viewer-image-follows";
    fs::create_directories(dir);
    test::writeAll(dir / "drive.sh",
                   driveScript("--size 64x48 --window 1920x1080 --backend sw --grid 32 --spp 1 --save-session "
                               "\"$3/final.json\" --stats \"$3/stats.json\"",
                               "wait_first_frame\n"
                               "click 'camera header'\n"
                               "click 'image size = picture area'\n"
                               "quit\n"));
    const int rc = run(onOwnDisplay("bash " + (dir / "drive.sh").string() + " " + amrvkBinary(), "3840x2160") + " " +
                           sample() + " " + dir.string(),
                       dir, "view");
    ASSERT_EQ(rc, 0) << test::readAll(dir / "view.err");
    const nlohmann::json layout = readJson(dir / "stats.json")["layout"];
    const Rect area = rectOf(layout["area"]), picture = rectOf(layout["picture"]);
    const session::Session s = session::loadSession(dir / "final.json");
    EXPECT_EQ(s.settings.width, area.width) << "the checkbox was not reached? " << layout.dump();
    EXPECT_EQ(s.settings.height, area.height);
    EXPECT_EQ(picture.width, area.width);
    EXPECT_EQ(picture.height, area.height);
}

TEST_F(ViewerGpu, LogScaleReadsAgainKeepsTheCameraAndRefitsTheTf) {
    const fs::path dir = test::scratchDir() / "viewer-log-scale";
    fs::remove_all(dir);
    fs::create_directories(dir);
    auto at = [&](const char* name) { return (dir / name).string(); };
    test::writeAll(dir / "script.txt",
                   "3 orbit 40 10\n"
                   "5 save-session " + at("linear.json") + "\n"
                   "6 scale log\n"
                   "8 save-session " + at("log.json") + "\n"
                   "10 scale linear\n"
                   "12 save-session " + at("back.json") + "\n"
                   "14 load-session " + at("log.json") + "\n"  // another scale: read again, not refused
                   "16 save-session " + at("loaded.json") + "\n"
                   "18 log-floor 0.01\n"
                   "19 density 0.02\n");  // the log TF makes the cloud opaque: thinner, so the image test has power
    const int rc = run(amrvkBinary() + " view " + sample() + kPicture + " --spp 128 --headless --frames 400 --script " +
                           at("script.txt") + " --stats " + at("stats.json") + " --screenshot " + at("final.pfm") +
                           " --save-session " + at("final.json") + " --validation",
                       dir, "view");
    ASSERT_EQ(rc, 0) << test::readAll(dir / "view.err");

    // The field's range, independently: log10 of the smallest positive and the largest value.
    const amr::Model m = amr::readModel(sample(), {});
    float minPositive = INFINITY, maxValue = -INFINITY, minValue = INFINITY;
    for (float v : m.fields[0].values) {
        if (v > 0) minPositive = std::min(minPositive, v);
        maxValue = std::max(maxValue, v);
        minValue = std::min(minValue, v);
    }
    ASSERT_GT(maxValue, 0.5f);
    ASSERT_LT(minValue, 0.01f) << "the floor below must floor something";

    const session::Session linear = session::loadSession(dir / "linear.json");
    const session::Session log = session::loadSession(dir / "log.json");
    const session::Session back = session::loadSession(dir / "back.json");
    const session::Session loaded = session::loadSession(dir / "loaded.json");
    const session::Session last = session::loadSession(dir / "final.json");
    EXPECT_EQ(linear.read.scale, amr::FieldScale::Linear);
    EXPECT_EQ(log.read.scale, amr::FieldScale::Log);
    EXPECT_EQ(back.read.scale, amr::FieldScale::Linear);
    EXPECT_EQ(loaded.read.scale, amr::FieldScale::Log);
    EXPECT_EQ(last.read.scale, amr::FieldScale::Log);
    EXPECT_EQ(last.read.logFloor, 0.01);
    // The camera (turned before the toggle) is kept by every reload.
    for (const session::Session* s : {&log, &back, &loaded, &last}) EXPECT_EQ(s->settings.camera, linear.settings.camera);
    // The TF's range follows the field's; its shape (relative node positions, alphas) stays.
    auto range = [](const session::Session& s) {
        const scene::TransferFunction tf = s.tf.merged();
        return std::pair(tf.firstPosition(), tf.lastPosition());
    };
    EXPECT_FLOAT_EQ(range(linear).first, 0.0f);  // --tf-range 0 1.2
    EXPECT_FLOAT_EQ(range(linear).second, 1.2f);
    EXPECT_NEAR(range(log).first, std::log10(minPositive), 1e-5);
    EXPECT_NEAR(range(log).second, std::log10(maxValue), 1e-5);
    EXPECT_NEAR(range(back).first, minValue, 1e-5);
    EXPECT_NEAR(range(back).second, maxValue, 1e-5);
    EXPECT_EQ(loaded.tf, log.tf) << "a loaded session's TF is taken as saved";
    EXPECT_NEAR(range(last).first, std::log10(0.01), 1e-5) << "the floor is the field's lowest value now";
    EXPECT_NEAR(range(last).second, std::log10(maxValue), 1e-5);
    const scene::TransferFunction a = linear.tf.merged(), b = log.tf.merged();
    ASSERT_EQ(a.nodeCount(), b.nodeCount());
    for (size_t i = 0; i < a.nodeCount(); ++i) {
        const double ra = (a.positions()[i] - range(linear).first) / (range(linear).second - range(linear).first);
        const double rb = (b.positions()[i] - range(log).first) / (range(log).second - range(log).first);
        EXPECT_NEAR(ra, rb, 1e-5) << "node " << i;
        EXPECT_EQ(a.colors()[i], b.colors()[i]) << "node " << i;
    }
    // The histogram follows: over the final TF range, every cell in it.
    const nlohmann::json stats = readJson(dir / "stats.json");
    EXPECT_EQ(stats["scale"], "log");
    EXPECT_NEAR(stats["histogram"]["lo"].get<double>(), std::log10(0.01), 1e-5);
    EXPECT_NEAR(stats["histogram"]["hi"].get<double>(), std::log10(maxValue), 1e-5);
    EXPECT_EQ(stats["histogram"]["cells"].get<double>(), double(m.cells.size()));
    EXPECT_EQ(stats["histogram"]["inRange"].get<double>(), double(m.cells.size()));
    bool scaleReset = false;
    for (const auto& r : stats["resets"])
        if (r["what"] == "scale") {
            scaleReset = true;
            EXPECT_EQ(r["samplesLeft"].get<uint32_t>(), 0u);
        }
    EXPECT_TRUE(scaleReset) << stats["resets"].dump();
    // The picture is render's of the final (log) session.
    expectSameAsRender(dir, "viewer-log-scale");

    // A session of the same data read with another NaN policy is refused, with the reason.
    nlohmann::json drop = readJson(dir / "log.json");
    drop["read"]["nan"] = "drop";
    test::writeAll(dir / "drop.json", drop.dump(2));
    test::writeAll(dir / "refused.txt", "1 load-session " + at("drop.json") + "\n");
    const int refused = run(amrvkBinary() + " view " + sample() + kPicture + " --headless --frames 5 --script " +
                                at("refused.txt"),
                            dir, "refused");
    const std::string err = test::readAll(dir / "refused.err");
    EXPECT_EQ(refused, 1) << err;
    EXPECT_NE(err.find("refused.txt:1: load-session:"), std::string::npos) << err;
    EXPECT_NE(err.find("read.nan drop (this viewer read reject)"), std::string::npos) << err;

    // A field with no positive value cannot go to log scale: one line naming the script line and
    // the reason, and the session asked for at exit is not written.
    test::writeAll(dir / "zeros_4x4x4_uint8.raw", std::string(64, '\0'));
    test::writeAll(dir / "nolog.txt", "1 scale log\n");
    const int nolog = run(amrvkBinary() + " view " + at("zeros_4x4x4_uint8.raw") + kPicture +
                              " --headless --frames 5 --script " + at("nolog.txt") + " --save-session " + at("never.json"),
                          dir, "nolog");
    const std::string why = test::readAll(dir / "nolog.err");
    EXPECT_EQ(nolog, 1) << why;
    EXPECT_NE(why.find("nolog.txt:1: scale:"), std::string::npos) << why;
    EXPECT_NE(why.find("no positive value"), std::string::npos) << why;
    EXPECT_FALSE(fs::exists(dir / "never.json"));
}

TEST_F(ViewerGpu, LogScaleFitsAnUneditedPresetAgain) {
    const fs::path dir = test::scratchDir() / "viewer-log-preset";
    fs::remove_all(dir);
    fs::create_directories(dir);
    auto at = [&](const char* name) { return (dir / name).string(); };
    std::string script = "1 save-session " + at("linear.json") + "\n";
    script += "2 scale log\n";
    script += "4 save-session " + at("log.json") + "\n";
    script += "5 scale linear\n";
    script += "7 save-session " + at("back.json") + "\n";
    test::writeAll(dir / "script.txt", script);
    const int rc = run(amrvkBinary() + " view " + sample() +
                           " --size 32x24 --scale linear --tf spiky --grid 16 --mode ae --backend sw --headless"
                           " --frames 9 --validation --script " +
                           at("script.txt"),
                       dir, "view");
    ASSERT_EQ(rc, 0) << test::readAll(dir / "view.err");
    // spiky fitted to the field on each scale, independently of the viewer: the cells read here.
    auto fitted = [](amr::FieldScale scale) {
        amr::ReadOptions read;
        read.scale = scale;
        const std::shared_ptr<const scene::Volume> v = scene::makeVolume(amr::readModel(sample(), read));
        return scene::TfChannels::split(scene::makePreset("spiky", v->percentiles, v->volumeHistogram));
    };
    auto expectTf = [](const scene::TfChannels& got, const scene::TfChannels& want, const char* what) {
        ASSERT_EQ(got.opacityPositions.size(), want.opacityPositions.size()) << what;
        const double span = want.opacityPositions.back() - want.opacityPositions.front();
        for (size_t i = 0; i < want.opacityPositions.size(); ++i) {
            EXPECT_NEAR(got.opacityPositions[i], want.opacityPositions[i], 1e-6 * span) << what << ", node " << i;
            EXPECT_FLOAT_EQ(got.alphas[i], want.alphas[i]) << what << ", node " << i;
        }
    };
    const scene::TfChannels linear = fitted(amr::FieldScale::Linear), log = fitted(amr::FieldScale::Log);
    expectTf(session::loadSession(dir / "linear.json").tf, linear, "linear");
    // The peaks sit at the log's percentiles (the same cells), not at the linear shape moved onto the log range.
    expectTf(session::loadSession(dir / "log.json").tf, log, "log");
    const scene::TfChannels moved =
        viewer::refitTfRange(linear, log.opacityPositions.front(), log.opacityPositions.back());
    EXPECT_GT(std::abs(moved.opacityPositions[2] - log.opacityPositions[2]),
              0.01 * (log.opacityPositions.back() - log.opacityPositions.front()))
        << "the test has no power: moving the shape would put the first apex where fitting does";
    expectTf(session::loadSession(dir / "back.json").tf, linear, "back on the linear scale");
}

// Issue 54, point 2: a session load is one commit. A session with another structure, TF and
// control extinction costs the viewer one device copy and one majorant pass more than the same run
// without the load (three passes when structure, TF and settings were applied one after another).
TEST_F(ViewerGpu, ASessionLoadBuildsOnceAndRunsOneMajorantPass) {
    const fs::path dir = test::scratchDir() / "viewer-session-commit";
    fs::remove_all(dir);
    fs::create_directories(dir);
    auto at = [&](const char* name) { return (dir / name).string(); };
    test::writeAll(dir / "save.txt", "1 save-session " + at("saved.json") + "\n");
    ASSERT_EQ(run(amrvkBinary() + " view " + sample() + kPicture + " --headless --frames 3 --script " + at("save.txt"),
                  dir, "save"),
              0)
        << test::readAll(dir / "save.err");
    session::Session s = session::loadSession(dir / "saved.json");
    s.structure.traversal = scene::TraversalKind::GridBvh;
    s.structure.grid = "8";
    s.tf = viewer::refitTfRange(s.tf, 0.2f, 1.0f);
    s.settings.controlExtinction = scene::ControlExtinction::Minorant;
    session::saveSession(dir / "other.json", s);

    auto updates = [&](const std::string& script, const char* tag) {
        test::writeAll(dir / (std::string(tag) + ".txt"), script);
        const int rc = run(amrvkBinary() + " view " + sample() + kPicture + " --headless --frames 6 --script " +
                               at(tag) + ".txt --stats " + at(tag) + ".json --validation",
                           dir, tag);
        EXPECT_EQ(rc, 0) << test::readAll(dir / (std::string(tag) + ".err"));
        return readJson(dir / (std::string(tag) + ".json"))["updates"];
    };
    const nlohmann::json plain = updates("5 density 1\n", "plain");
    const nlohmann::json loaded = updates("2 load-session " + at("other.json") + "\n", "loaded");
    EXPECT_EQ(loaded["deviceScenes"].get<int>() - plain["deviceScenes"].get<int>(), 1) << loaded.dump();
    EXPECT_EQ(loaded["majorantPasses"].get<int>() - plain["majorantPasses"].get<int>(), 1) << loaded.dump();
}
