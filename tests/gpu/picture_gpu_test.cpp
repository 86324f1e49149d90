// The one entry from a picture description to pixels (src/picture): cells given in memory render
// exactly what the same cells read from a file render; what the description leaves open is fitted
// once and reported; and the amrvk render command line of a description (what the bench records for
// its references, and its cache key) renders the picture the description renders in process.
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "amr/readers.h"
#include "core/image_io.h"
#include "gpu_fixture.h"
#include "image_compare.h"
#include "model_fixtures.h"
#include "picture/first_frame.h"
#include "picture/picture.h"
#include "render_fixtures.h"
#include "scene/camera.h"
#include "test_data.h"

using namespace amrvk;
using test::maxRelativeDifference;
namespace fs = std::filesystem;

namespace {

class PictureGpu : public test::GpuTest {};

session::PictureDescription cloudDescription(const fs::path& input) {
    session::PictureDescription d;
    d.session.input = input.string();
    d.session.read.scale = amr::FieldScale::Linear;  // the cells' values as they are, as from memory
    d.session.settings.width = d.session.settings.height = 20;
    d.session.settings.mode = scene::Mode::Ss;
    d.session.settings.densityScale = 3;
    d.session.settings.lights.push_back({false, {1.0, -1.0, 2.0}, glm::dvec3(3.0)});
    d.session.spp = 6;
    d.session.structure = {.sampler = scene::SamplerKind::ExtBrick, .grid = "8"};
    d.tfSource = session::TfSource{.name = "foggy"};
    d.fitCamera = true;
    return d;
}

}  // namespace

TEST_F(PictureGpu, CellsFromMemoryRenderWhatTheSameCellsFromAFileRender) {
    const fs::path dir = test::scratchDir();
    const amr::Model cloud = test::makeThreeLevelCloud();
    amr::writeExaBrick(cloud, dir / "cloud", true);
    const session::PictureDescription d = cloudDescription(dir / "cloud.cells");
    picture::Picture fromFile = picture::makePicture(ctx(), session::loadVolume(d.session), d);
    // The caller's cells, validated as a reader's are (NaN policy, alignment, overlaps).
    amr::Model memory = cloud;
    memory.source = "memory";
    picture::Picture fromMemory =
        picture::makePicture(ctx(), scene::makeVolume(amr::checkedModel(std::move(memory), amr::NanPolicy::Reject)), d);
    const scene::RenderOutput a = fromFile.render(), b = fromMemory.render();
    EXPECT_EQ(a.stats.counter(shared::kCounterDensityLookups), b.stats.counter(shared::kCounterDensityLookups));
    EXPECT_GT(a.stats.counter(shared::kCounterRealCollisions), 0u);
    EXPECT_LT(maxRelativeDifference(a.mean, b.mean), 1e-6);
    EXPECT_TRUE(fromFile.session().settings == fromMemory.session().settings);
    // Bad cells from memory get the readers' one-line errors.
    amr::Model bad = cloud;
    amr::Cell misaligned = bad.cells[3];
    misaligned.lower.x += 1;
    bad.cells.set(3, misaligned);
    EXPECT_NE(test::errorOf([&] { amr::checkedModel(std::move(bad), amr::NanPolicy::Reject); }).find("aligned"),
              std::string::npos);
}

// The path tracer warmed on another thread while the structures are built (Options::warmTracer) is
// the one the render uses: one pipeline compiled in all, there before the first sample, and the
// same picture as without the warm-up. A warm-up of another mode is not used, and costs no second
// compile of the mode rendered.
TEST_F(PictureGpu, APathTracerWarmedWhileTheStructuresBuildIsTheOneUsed) {
    const fs::path dir = test::scratchDir();
    amr::writeExaBrick(test::makeThreeLevelCloud(), dir / "cloud", true);
    const session::PictureDescription d = cloudDescription(dir / "cloud.cells");
    picture::Picture cold = picture::makePicture(ctx(), session::loadVolume(d.session), d);
    EXPECT_EQ(cold.renderer->updateCounts().pipelinesCompiled, 0u);
    picture::Picture warm = picture::makePicture(ctx(), session::loadVolume(d.session), d,
                                                 {.warmTracer = render::TracerVariant{scene::Mode::Ss}});
    EXPECT_EQ(warm.renderer->updateCounts().pipelinesCompiled, 1u);  // adopted before the first sample
    const scene::RenderOutput a = cold.render(), b = warm.render();
    EXPECT_EQ(cold.renderer->updateCounts().pipelinesCompiled, 1u);
    EXPECT_EQ(warm.renderer->updateCounts().pipelinesCompiled, 1u);  // not compiled again
    EXPECT_EQ(a.stats.counter(shared::kCounterDensityLookups), b.stats.counter(shared::kCounterDensityLookups));
    EXPECT_EQ(maxRelativeDifference(a.mean, b.mean), 0.0);
    picture::Picture other = picture::makePicture(ctx(), session::loadVolume(d.session), d,
                                                  {.warmTracer = render::TracerVariant{scene::Mode::Dvr}});
    other.render();
    EXPECT_EQ(other.renderer->updateCounts().pipelinesCompiled, 2u);  // the dvr one, then ss's own
}

TEST_F(PictureGpu, WhatTheDescriptionLeavesOpenIsFittedOnceAndReported) {
    // Four cells at the corners of a 4096-wide box: sparse (they fill 6e-11 of it), so the
    // data-fitted traversal is abr, with the abr sampler unless one was given; the TF (foggy) is
    // fitted to the field's percentiles and spans the field, the camera frames the data.
    amr::Model sparse;
    sparse.source = "sparse";
    sparse.cells = {{{0, 0, 0}, 0}, {{4095, 0, 0}, 0}, {{0, 4095, 0}, 0}, {{0, 0, 4095}, 0}};
    sparse.fields = {{"v", {1.0f, 2.0f, 3.0f, 4.0f}}};
    const std::shared_ptr<const scene::Volume> v =
        scene::makeVolume(amr::checkedModel(std::move(sparse), amr::NanPolicy::Reject));
    session::PictureDescription d = cloudDescription("sparse");
    d.fit = session::StructureFit::Data;
    d.session.structure.backend = scene::Backend::Auto;
    std::vector<std::string> noted;
    picture::Picture pic = picture::makePicture(ctx(), v, d, {.note = [&](const std::string& l) { noted.push_back(l); }});
    EXPECT_EQ(pic.session().structure.traversal, scene::TraversalKind::Abr);
    EXPECT_EQ(pic.session().structure.sampler, scene::SamplerKind::Abr);
    EXPECT_EQ(pic.renderer->config().traversal, scene::TraversalKind::Abr);
    EXPECT_EQ(pic.renderer->config().backend, scene::Backend::Sw) << "auto is sw until rq is measured faster";
    EXPECT_EQ(pic.session().structure.backend, scene::Backend::Auto) << "the session keeps what was asked";
    ASSERT_EQ(noted, pic.report.notes);
    ASSERT_EQ(noted.size(), 3u);
    EXPECT_EQ(noted[0].rfind("tf foggy: alpha 0 up to the median cell value (2)", 0), 0u) << noted[0];
    EXPECT_EQ(noted[1].rfind("traversal abr and sampler abr:", 0), 0u) << noted[1];
    EXPECT_EQ(noted[2].rfind("--backend auto: sw", 0), 0u) << noted[2];
    EXPECT_FALSE(pic.report.backendReason.empty());
    const scene::Camera framed = scene::defaultCamera(v->worldLo(), v->worldHi(), 40.0);
    EXPECT_TRUE(pic.session().settings.camera == framed);
    const scene::TransferFunction tf = pic.session().tf.merged();
    EXPECT_EQ(tf.firstPosition(), v->valueLo());
    EXPECT_EQ(tf.lastPosition(), v->valueHi());
    // A sampler given stays; nothing is fitted for a description that fixes everything.
    d.given.insert("sampler");
    EXPECT_EQ(picture::makePicture(ctx(), v, d).session().structure.sampler, scene::SamplerKind::ExtBrick);
    d.fit = session::StructureFit::None;
    d.session.structure.backend = scene::Backend::Sw;
    d.tfRange = std::make_pair(1.0f, 4.0f);
    EXPECT_TRUE(picture::makePicture(ctx(), v, d).report.notes.empty());
}

TEST_F(PictureGpu, TheCommandLineOfADescriptionRendersItsPicture) {
    // What the bench records for a reference (and keys its cache by): run as a command, it must
    // render the image the description renders in process (same seed: the same samples).
    const std::string binary = std::string(AMRVK_BINARY_DIR) + "/bin/amrvk";
    if (!fs::exists(binary)) GTEST_SKIP() << "amrvk binary not built: " << binary;
    const fs::path dir = test::scratchDir();
    amr::writeExaBrick(test::makeThreeLevelCloud(), dir / "cloud", true);
    session::PictureDescription d = cloudDescription(dir / "cloud.cells");
    d.tfRange = std::make_pair(0.2f, 1.7f);
    d.session.settings.seed = 1000004;
    const std::string command =
        session::renderCommandLine(d, "", (dir / "command.pfm").string(), binary) + " 2>" + (dir / "command.err").string();
    ASSERT_EQ(std::system(command.c_str()), 0) << command << "\n" << test::readAll(dir / "command.err");
    const Image viaCommand = readPfm(dir / "command.pfm");
    const scene::RenderOutput inProcess = picture::makePicture(ctx(), session::loadVolume(d.session), d).render();
    ASSERT_EQ(viaCommand.pixels.size(), inProcess.mean.pixels.size());
    EXPECT_LT(maxRelativeDifference(viaCommand, inProcess.mean), 1e-5) << command;
    // Power: the comparison tells another seed's samples apart.
    d.session.settings.seed += 1;
    EXPECT_GT(maxRelativeDifference(viaCommand, picture::makePicture(ctx(), session::loadVolume(d.session), d).render().mean),
              1e-3);
}

// The first frame (picture/first_frame.h): the picture ray-marched at 2 spp, the step halved while
// it is noisier than kFirstFrameNoise and the next fits the budget; the renderer is left as given,
// with no sample. Checked against dvr renders of the same description at the steps it reports.
TEST_F(PictureGpu, TheFirstFrameHalvesTheStepWhileItIsNoisyAndLeavesTheRendererAsGiven) {
    const fs::path dir = test::scratchDir();
    amr::writeExaBrick(test::makeThreeLevelCloud(), dir / "cloud", true);
    session::PictureDescription d = cloudDescription(dir / "cloud.cells");
    d.session.settings.width = d.session.settings.height = 32;
    d.session.settings.mode = scene::Mode::Ms;
    d.tfSource = session::TfSource{.name = "spiky"};  // thin layers: aliasing at dt 0.5
    picture::Picture p = picture::makePicture(ctx(), session::loadVolume(d.session), d);
    const scene::RenderSettings given = p.renderer->settings();
    const picture::FirstFrame f = picture::renderFirstFrame(*p.renderer);
    EXPECT_TRUE(p.renderer->settings() == given);
    EXPECT_EQ(p.renderer->accumulatedSpp(), 0u);
    // dvr of the same description at a step: what a dvr renderer of it renders at 2 spp.
    auto dvrAt = [&](double dt) {
        scene::RenderSettings s = given;
        s.mode = scene::Mode::Dvr;
        s.dvrStep = dt;
        return p.renderer->render(s, picture::kFirstFrameSpp);
    };
    const scene::RenderOutput coarse = dvrAt(given.dvrStep);
    ASSERT_GT(scene::meanRelativeError(coarse), picture::kFirstFrameNoise) << "the case must need refining";
    ASSERT_GE(f.frames, 2u);
    int halvings = 0;  // dt = given / 2^halvings, at least one halving per frame after the first
    while (halvings < 16 && std::ldexp(given.dvrStep, -halvings) > f.dt) ++halvings;
    EXPECT_DOUBLE_EQ(f.dt, std::ldexp(given.dvrStep, -halvings));
    EXPECT_GE(halvings, int(f.frames) - 1);
    EXPECT_GE(f.dt, picture::kFirstFrameMinDt);
    // The budget follows the first frame's cost: 8x it, within [1 s, 8 s].
    EXPECT_DOUBLE_EQ(picture::firstFrameBudgetSeconds(0.01), picture::kFirstFrameGpuSeconds);
    EXPECT_DOUBLE_EQ(picture::firstFrameBudgetSeconds(0.5), 4.0);
    EXPECT_DOUBLE_EQ(picture::firstFrameBudgetSeconds(3.0), picture::kFirstFrameMaxGpuSeconds);
    const bool budgetLeft = f.gpuSeconds * 1.5 < picture::kFirstFrameGpuSeconds;  // this machine: far under
    EXPECT_TRUE(f.noise <= picture::kFirstFrameNoise || f.dt / 2 < picture::kFirstFrameMinDt || !budgetLeft)
        << "stopped early: noise " << f.noise << " at dt " << f.dt;
    EXPECT_LT(f.noise, scene::meanRelativeError(coarse));
    const scene::RenderOutput same = dvrAt(f.dt);
    EXPECT_LT(maxRelativeDifference(f.image, same.mean), 1e-6);
    EXPECT_NEAR(f.noise, scene::meanRelativeError(same), 1e-9);
    EXPECT_GT(maxRelativeDifference(f.image, coarse.mean), 1e-3) << "a finer step is another picture";
}

// Issue 54, point 2: edits are committed once. A session's structure, TF, colour meaning and
// settings (with minorants) committed together cost one device copy and one majorant pass (one at a
// time they cost three passes), and the edited picture renders what a fresh picture of the same
// description renders; a refused part leaves the whole picture as it was.
TEST_F(PictureGpu, ASessionsEditsAreCommittedOnceAndRenderWhatAFreshPictureRenders) {
    const fs::path dir = test::scratchDir();
    amr::writeExaBrick(test::makeThreeLevelCloud(), dir / "cloud", true);
    const session::PictureDescription d = cloudDescription(dir / "cloud.cells");
    picture::Picture p = picture::makePicture(ctx(), session::loadVolume(d.session), d);

    session::PictureDescription loaded = d;  // the session a user loads: another structure, TF and estimator
    loaded.session.structure = {
        .sampler = scene::SamplerKind::Grid, .traversal = scene::TraversalKind::GridBvh, .grid = "4"};
    loaded.tfSource = session::TfSource{.name = "spiky"};
    loaded.session.tfColors = scene::TfColors::Linear;
    loaded.session.settings.controlExtinction = scene::ControlExtinction::Minorant;
    loaded.session.settings.seed = 11;
    picture::Picture fresh = picture::makePicture(ctx(), session::loadVolume(loaded.session), loaded);
    const session::Session target = fresh.session();

    const scene::TfChannels original = p.session().tf;
    const render::UpdateCounts before = p.renderer->updateCounts();
    p.commit(
        {.tf = target.tf, .tfColors = target.tfColors, .structure = target.structure, .settings = target.settings});
    const render::UpdateCounts after = p.renderer->updateCounts();
    EXPECT_EQ(after.deviceScenes - before.deviceScenes, 1u);
    EXPECT_EQ(after.majorantDispatches - before.majorantDispatches, 1u);
    EXPECT_EQ(after.accumulationResets - before.accumulationResets, 1u);
    EXPECT_TRUE(p.session().settings == target.settings);
    EXPECT_TRUE(p.session().tf == target.tf);
    EXPECT_EQ(p.session().tfColors, scene::TfColors::Linear);
    EXPECT_EQ(p.renderer->config().label(), fresh.renderer->config().label());
    const scene::RenderOutput edited = p.render(), made = fresh.render();
    EXPECT_GT(made.stats.counter(shared::kCounterRealCollisions), 0u);
    EXPECT_EQ(edited.stats.counter(shared::kCounterDensityLookups), made.stats.counter(shared::kCounterDensityLookups));
    EXPECT_LT(maxRelativeDifference(edited.mean, made.mean), 1e-6);

    // The same parts one at a time: a pass each for the structure, the TF and the minorants.
    picture::Picture apart = picture::makePicture(ctx(), session::loadVolume(d.session), d);
    const render::UpdateCounts b2 = apart.renderer->updateCounts();
    apart.commit({.structure = target.structure});
    apart.commit({.tf = target.tf, .tfColors = target.tfColors});
    apart.commit({.settings = target.settings});
    EXPECT_EQ(apart.renderer->updateCounts().majorantDispatches - b2.majorantDispatches, 3u);

    // A refused part (a grid that is not one) refuses the commit: nothing of it is taken.
    const render::UpdateCounts c0 = p.renderer->updateCounts();
    scene::StructureConfig bad = target.structure;
    bad.grid = "0x0x0";
    scene::RenderSettings moved = target.settings;
    moved.seed = 12;
    EXPECT_THROW(p.commit({.tf = original, .structure = bad, .settings = moved}), Error);
    EXPECT_EQ(p.renderer->updateCounts().majorantDispatches, c0.majorantDispatches);
    EXPECT_EQ(p.renderer->settings().seed, 11u);
    EXPECT_TRUE(p.session().tf == target.tf);
    EXPECT_EQ(p.session().structure.grid, "4");
}
