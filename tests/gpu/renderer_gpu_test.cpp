// The incremental renderer: every edit redoes exactly what scene/invalidation.h says depends on it
// (counted by the renderer), accumulation is resumable, an edited renderer renders what a fresh
// one renders for the final state, the host's culling set equals the GPU majorants > 0, and a
// tracking call that reaches the step cap is counted, never silent.
#include <algorithm>

#include "amr/readers.h"
#include "gpu_fixture.h"
#include "image_compare.h"
#include "model_fixtures.h"
#include "render/renderer.h"
#include "render_fixtures.h"
#include "scene/camera.h"
#include "test_data.h"

using namespace amrvk;

namespace {

scene::RenderSettings smallSettings(const amr::Model& m) {
    const amr::ModelSummary sum = amr::summarize(m);
    scene::RenderSettings s;
    s.width = s.height = 24;
    s.mode = scene::Mode::Ms;
    s.camera = scene::defaultCamera(glm::dvec3(sum.bounds.lower), glm::dvec3(sum.bounds.upper));
    s.lights.push_back({false, {1.0, -1.0, 2.0}, glm::dvec3(2.0)});
    return s;
}

scene::TransferFunction rampOver(const scene::VolumeScene& scene) {
    return scene::makePreset("ramp", scene.valueLo, scene.valueHi);
}

// Largest relative difference between two images' means (same samples: equal up to rounding).
double maxRelativeDifference(const Image& a, const Image& b) {
    double worst = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double x = a.pixels[i][c], y = b.pixels[i][c];
            worst = std::max(worst, std::abs(x - y) / std::max({std::abs(x), std::abs(y), 1e-3}));
        }
    return worst;
}

bool holdsDeviceBuffer(gpu::Context& ctx, const std::string& name) {
    for (const auto& [n, usage] : ctx.memory().perResource())
        if (n == name && usage.current > 0) return true;
    return false;
}

}  // namespace

class RendererGpu : public test::GpuTest {};

TEST_F(RendererGpu, EachEditRedoesOnlyWhatDependsOnIt) {
    amr::Model m = test::makeThreeLevelCloud();
    scene::StructureConfig cfg;
    cfg.grid = "8";
    scene::VolumeScene scene = scene::buildVolumeScene(m, m.fields[0], cfg);
    render::Renderer r(ctx(), scene);
    r.setTransferFunction(rampOver(scene));
    scene::RenderSettings s = smallSettings(m);
    r.setSettings(s);
    r.accumulate(2);
    render::UpdateCounts before = r.updateCounts();
    EXPECT_EQ(before.deviceScenes, 1u);
    EXPECT_EQ(before.majorantDispatches, 1u);
    EXPECT_EQ(before.pipelinesCompiled, 1u);
    EXPECT_EQ(r.accumulatedSpp(), 2u);

    // Equal settings: nothing happens, the image keeps its samples.
    r.setSettings(s);
    EXPECT_EQ(r.accumulatedSpp(), 2u);
    EXPECT_EQ(r.updateCounts().accumulationResets, before.accumulationResets);

    // Camera: only the accumulation.
    scene::Camera cam = s.camera;
    cam.eye += glm::dvec3(3.0, 0.0, 1.0);
    r.setCamera(cam);
    r.accumulate(1);
    render::UpdateCounts now = r.updateCounts();
    EXPECT_EQ(r.accumulatedSpp(), 1u) << "a camera move restarts the image";
    EXPECT_EQ(now.accumulationResets, before.accumulationResets + 1);
    EXPECT_EQ(now.majorantDispatches, before.majorantDispatches);
    EXPECT_EQ(now.deviceScenes, before.deviceScenes);
    EXPECT_EQ(now.pipelinesCompiled, before.pipelinesCompiled);

    // Lighting and density: the accumulation only.
    before = now;
    s = r.settings();
    s.ambient = glm::dvec3(0.2);
    s.densityScale = 2.0;
    r.setSettings(s);
    r.accumulate(1);
    now = r.updateCounts();
    EXPECT_EQ(now.majorantDispatches, before.majorantDispatches);
    EXPECT_EQ(now.pipelinesCompiled, before.pipelinesCompiled);
    EXPECT_EQ(now.accumulationResets, before.accumulationResets + 1);

    // Mode: a pipeline for the new mode, once; back to the old mode reuses the old one.
    before = now;
    s.mode = scene::Mode::Ae;
    r.setSettings(s);
    r.accumulate(1);
    s.mode = scene::Mode::Ms;
    r.setSettings(s);
    r.accumulate(1);
    now = r.updateCounts();
    EXPECT_EQ(now.pipelinesCompiled, before.pipelinesCompiled + 1);
    EXPECT_EQ(now.majorantDispatches, before.majorantDispatches);

    // TF: the majorants, not the device copy, not the pipelines.
    before = now;
    r.setTransferFunction(scene::makePreset("foggy", scene.valueLo, scene.valueHi));
    r.accumulate(1);
    now = r.updateCounts();
    EXPECT_EQ(now.majorantDispatches, before.majorantDispatches + 1);
    EXPECT_EQ(now.deviceScenes, before.deviceScenes);
    EXPECT_EQ(now.pipelinesCompiled, before.pipelinesCompiled);
    EXPECT_EQ(r.accumulatedSpp(), 1u);

    // Shaders: the pipeline, not the majorants.
    before = now;
    r.reloadShaders();
    now = r.updateCounts();
    EXPECT_EQ(now.pipelinesCompiled, before.pipelinesCompiled + 1);
    EXPECT_EQ(now.majorantDispatches, before.majorantDispatches);
    EXPECT_EQ(r.accumulatedSpp(), 0u);

    // Structure: a new device copy of only what the new combination uses, majorants for the
    // current TF, new pipelines; the old combination's buffers are freed.
    EXPECT_TRUE(holdsDeviceBuffer(ctx(), "macrocellRanges"));
    before = now;
    cfg.traversal = scene::TraversalKind::Abr;
    cfg.sampler = scene::SamplerKind::Abr;
    scene.configure(cfg);
    r.setStructure();
    r.accumulate(1);
    now = r.updateCounts();
    EXPECT_EQ(now.deviceScenes, before.deviceScenes + 1);
    EXPECT_EQ(now.majorantDispatches, before.majorantDispatches + 1);
    EXPECT_EQ(now.pipelinesCompiled, before.pipelinesCompiled + 1);
    EXPECT_TRUE(holdsDeviceBuffer(ctx(), "abrs"));
    EXPECT_FALSE(holdsDeviceBuffer(ctx(), "macrocellRanges"));
    EXPECT_FALSE(holdsDeviceBuffer(ctx(), "brickDomainSamplerBvh"));
}

TEST_F(RendererGpu, AccumulationResumesWhereItStopped) {
    amr::Model m = test::makeThreeLevelCloud();
    scene::VolumeScene scene = scene::buildVolumeScene(m, m.fields[0], scene::SamplerKind::ExtBrick, "8");
    render::Renderer r(ctx(), scene);
    r.setTransferFunction(rampOver(scene));
    const scene::RenderSettings s = smallSettings(m);
    const scene::RenderOutput once = r.render(s, 8);
    r.resetAccumulation();
    r.accumulate(3);
    r.accumulate(5);
    const scene::RenderOutput parts = r.output();
    EXPECT_EQ(parts.spp, 8u);
    EXPECT_EQ(parts.stats.paths, once.stats.paths);
    EXPECT_EQ(parts.stats.counter(shared::kCounterRealCollisions), once.stats.counter(shared::kCounterRealCollisions));
    EXPECT_LT(maxRelativeDifference(parts.mean, once.mean), 1e-5) << "3 + 5 samples are the samples 0..7";

    // Time-budgeted tiles of 5 rows (24 rows: uneven), then whole samples after a partial one.
    r.resetAccumulation();
    while (r.accumulatedSpp() < 3) r.accumulateRows(5);
    r.accumulateRows(7);
    EXPECT_EQ(r.rowsDone(), 7u);
    r.accumulate(5);  // completes the started sample, then 4 more
    EXPECT_EQ(r.rowsDone(), 0u);
    const scene::RenderOutput tiles = r.output();
    EXPECT_EQ(tiles.spp, 8u);
    EXPECT_EQ(tiles.stats.paths, once.stats.paths);
    EXPECT_LT(maxRelativeDifference(tiles.mean, once.mean), 1e-5) << "tiles trace every pixel once per sample";
}

TEST_F(RendererGpu, AnEditedRendererRendersWhatAFreshOneRenders) {
    amr::Model m = test::makeThreeLevelCloud();
    scene::StructureConfig first, last;
    first.grid = "8";
    last.traversal = scene::TraversalKind::KdTree;
    last.kdLeaves = 64;
    scene::VolumeScene scene = scene::buildVolumeScene(m, m.fields[0], first);
    scene::RenderSettings s = smallSettings(m);
    render::Renderer edited(ctx(), scene);
    edited.setTransferFunction(scene::makePreset("foggy", scene.valueLo, scene.valueHi));
    edited.render(s, 2);
    // Edit everything, in an order a user might.
    s.camera.eye += glm::dvec3(-2.0, 4.0, 1.0);
    s.mode = scene::Mode::Ss;
    s.g = 0.4;
    edited.setSettings(s);
    edited.accumulate(1);
    const scene::TransferFunction tf = rampOver(scene);
    edited.setTransferFunction(tf);
    scene.configure(last);
    edited.setStructure();
    EXPECT_EQ(edited.traversalBoxes().size(), 64u) << "the kd-tree has the requested leaves";
    edited.accumulate(6);
    const scene::RenderOutput a = edited.output();

    scene::VolumeScene freshScene = scene::buildVolumeScene(m, m.fields[0], last);
    render::Renderer fresh(ctx(), freshScene);
    fresh.setTransferFunction(tf);
    const scene::RenderOutput b = fresh.render(s, 6);
    EXPECT_EQ(a.spp, b.spp);
    EXPECT_GT(a.stats.counter(shared::kCounterRealCollisions), 0u);
    EXPECT_LT(maxRelativeDifference(a.mean, b.mean), 1e-5);
}

TEST_F(RendererGpu, HostCullingSetEqualsTheGpuMajorants) {
    AMRVK_REQUIRE_DATA(test::kEnzoDataSet);
    amr::Model m = test::readEnzoDensity();
    for (scene::TraversalKind t : {scene::TraversalKind::GridBvh, scene::TraversalKind::Abr,
                                   scene::TraversalKind::Brick, scene::TraversalKind::ExtBrick,
                                   scene::TraversalKind::KdTree}) {
        scene::StructureConfig c;
        c.traversal = t;
        c.grid = "32";
        c.kdLeaves = 256;
        scene::VolumeScene scene = scene::buildVolumeScene(m, m.fields[0], c);
        render::Renderer r(ctx(), scene);
        for (const char* preset : {"spiky", "foggy", "ramp", "empty"}) {
            SCOPED_TRACE(testing::Message() << scene::traversalName(t) << " " << preset);
            r.setTransferFunction(scene::makePreset(preset, 0.0f, 3.0f));
            const std::vector<float> gpu =
                t == scene::TraversalKind::GridBvh ? r.downloadMajorants() : r.downloadDomainMajorants();
            const std::vector<uint8_t>& host = r.activeTraversalMask();
            ASSERT_EQ(host.size(), gpu.size());
            size_t mismatches = 0, active = 0;
            for (size_t i = 0; i < gpu.size(); ++i) {
                mismatches += (gpu[i] > 0.0f) != (host[i] != 0);
                active += host[i] != 0;
            }
            EXPECT_EQ(mismatches, 0u);
            EXPECT_EQ(active, r.activeTraversalBoxes());
            const std::string name = preset;
            if (name == "empty") {
                EXPECT_EQ(active, 0u);
            } else if (name == "foggy") {
                EXPECT_EQ(active, gpu.size()) << "foggy's alpha is > 0 everywhere";
            } else if (name == "spiky") {
                EXPECT_GT(active, 0u);
                EXPECT_LT(active, gpu.size()) << "a spiky TF culls boxes";
            }
        }
    }
}

TEST_F(RendererGpu, TrackingCapIsCountedNotSilent) {
    // Two halves in one macrocell: value 0 (alpha 0) in front, value 1 (alpha 1) behind. The
    // majorant is the back half's, so the front half costs density x length null collisions.
    amr::Model m = test::makeUniformBox({16, 16, 16}, 0, 1.0f);
    for (size_t i = 0; i < m.cells.size(); ++i)
        if (m.cells[i].lower.x < 8) m.fields[0].values[i] = 0.0f;
    scene::VolumeScene scene = scene::buildVolumeScene(m, m.fields[0], scene::SamplerKind::ExtBrick, "1");
    render::Renderer r(ctx(), scene);
    r.setTransferFunction(scene::makePreset("grey", 0.0f, 1.0f));
    scene::RenderSettings s;
    s.mode = scene::Mode::Ae;
    s.width = s.height = 8;
    s.camera.eye = {-20.0, 8.0, 8.0};
    s.camera.target = {8.0, 8.0, 8.0};
    s.camera.up = {0.0, 0.0, 1.0};
    s.camera.fovYDegrees = 10.0;
    s.densityScale = 1e3;  // about 8000 null collisions across the front half
    const scene::RenderOutput fine = r.render(s, 2);
    EXPECT_EQ(fine.stats.counter(shared::kCounterTrackingCapHits), 0u) << "the default cap is far away";
    EXPECT_GT(fine.stats.counter(shared::kCounterRealCollisions), 0u);
    s.maxTrackingSteps = 1000;
    const scene::RenderOutput capped = r.render(s, 2);
    EXPECT_EQ(capped.stats.counter(shared::kCounterTrackingCapHits), capped.stats.paths)
        << "every camera ray stops at the cap and each one is counted";
    EXPECT_EQ(capped.stats.counter(shared::kCounterRealCollisions), 0u);
    EXPECT_EQ(capped.stats.counter(shared::kCounterMajorantViolations), 0u) << "a cap is not a violation";
}

// Samples per invocation only regroups the same samples (each is seeded by its own number): 1 and
// 8 per invocation give the same counters and the same means up to float rounding, at 13 spp (not
// a multiple of 8, so the last dispatch takes 5); another seed does not (the check has power).
TEST_F(RendererGpu, SamplesPerInvocationRegroupTheSameSamples) {
    amr::Model m = test::makeThreeLevelCloud();
    scene::StructureConfig cfg;
    cfg.grid = "8";
    scene::VolumeScene scene = scene::buildVolumeScene(m, m.fields[0], cfg);
    auto renderOn = [&](uint32_t perInvocation, uint32_t seed) {
        gpu::ContextOptions o;
        o.validation = true;
        o.samplesPerInvocation = perInvocation;
        gpu::Context c(o);
        EXPECT_EQ(c.samplesPerInvocation(), perInvocation);
        scene::RenderOutput out;
        {
            render::Renderer r(c, scene);
            r.setTransferFunction(rampOver(scene));
            scene::RenderSettings s = smallSettings(m);
            s.seed = seed;
            out = r.render(s, 13);
        }
        EXPECT_EQ(c.validationErrors(), 0u) << c.lastValidationMessage();
        return out;
    };
    const scene::RenderOutput one = renderOn(1, 3), eight = renderOn(8, 3), other = renderOn(8, 4);
    EXPECT_EQ(eight.spp, 13u);
    for (uint32_t k = 0; k < shared::kCounterCount; ++k) EXPECT_EQ(one.stats.counters[k], eight.stats.counters[k]) << k;
    EXPECT_GT(one.stats.counters[shared::kCounterRealCollisions], 1000u);
    EXPECT_LT(maxRelativeDifference(one.mean, eight.mean), 1e-5);
    EXPECT_GT(maxRelativeDifference(one.mean, other.mean), 1e-2);
    EXPECT_NE(one.stats.counters[shared::kCounterDensityLookups], other.stats.counters[shared::kCounterDensityLookups]);
}
