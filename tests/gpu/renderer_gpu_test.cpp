// The incremental renderer: every edit redoes exactly what scene/invalidation.h says depends on it
// (counted by the renderer, checked against the rule for every kind of change), a failed structure
// change keeps the previous structures, accumulation is resumable, an edited renderer renders what a fresh
// one renders for the final state, the host's culling set equals the GPU majorants > 0, and a
// tracking call that reaches the step cap is counted, never silent.
#include <algorithm>
#include <functional>
#include <random>

#include "accel/dda.h"
#include "amr/readers.h"
#include "gpu_fixture.h"
#include "image_compare.h"
#include "model_fixtures.h"
#include "render/renderer.h"
#include "render_fixtures.h"
#include "scene/camera.h"
#include "scene/tf_files.h"
#include "scene/tf_presets.h"
#include "test_data.h"

using namespace amrvk;
using test::maxRelativeDifference;

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

scene::TransferFunction rampOver(const scene::Volume& v) { return scene::makePreset("ramp", v.valueLo(), v.valueHi()); }

bool holdsDeviceBuffer(gpu::Context& ctx, const std::string& name) {
    for (const auto& [n, usage] : ctx.memory().perResource())
        if (n == name && usage.current > 0) return true;
    return false;
}

}  // namespace

class RendererGpu : public test::GpuTest {};

// What an edit did, as counted by the renderer, against what scene::invalidatedBy says it must
// do: one line per disagreement (empty when the renderer followed the rule exactly).
std::string disagreements(const scene::Invalidation& rule, const render::UpdateCounts& a, const render::UpdateCounts& b) {
    std::string out;
    auto check = [&](const char* what, bool expected, uint64_t before, uint64_t after) {
        if ((after - before == 1) != expected || after - before > 1)
            out += std::string(what) + ": redone " + std::to_string(after - before) + " time(s), rule says " +
                   (expected ? "once" : "never") + "; ";
    };
    check("accumulation", rule.accumulation, a.accumulationResets, b.accumulationResets);
    check("accumulation buffer", rule.accumulationBuffer, a.accumulationBuffers, b.accumulationBuffers);
    check("view params", rule.viewParams, a.viewWrites, b.viewWrites);
    check("shading params", rule.shadingParams, a.shadingWrites, b.shadingWrites);
    check("pipelines", rule.pipelines, a.pipelineDrops, b.pipelineDrops);
    check("majorants", rule.majorants, a.majorantDispatches, b.majorantDispatches);
    check("device scene", rule.deviceScene, a.deviceScenes, b.deviceScenes);
    return out;
}

TEST_F(RendererGpu, EveryEditRedoesExactlyWhatTheInvalidationRuleSays) {
    // The rule (scene::invalidatedBy) is the specification; for every kind of change an edit that
    // makes exactly that change must redo exactly what the rule lists, counted by the renderer.
    scene::StructureConfig cfg;
    cfg.grid = "8";
    auto r = test::makeRenderer(ctx(), test::makeThreeLevelCloud(), cfg);
    const scene::Volume& v = r->volume();
    r->setTransferFunction(rampOver(v));
    scene::RenderSettings s = smallSettings(v.model);
    r->setSettings(s);
    r->accumulate(2);
    EXPECT_EQ(r->updateCounts().deviceScenes, 1u);
    EXPECT_EQ(r->updateCounts().majorantDispatches, 1u);
    EXPECT_EQ(r->updateCounts().pipelinesCompiled, 1u);

    // Equal settings and an equal structure: nothing happens, the image keeps its samples.
    render::UpdateCounts before = r->updateCounts();
    r->setSettings(s);
    r->setStructure(cfg);
    EXPECT_EQ(disagreements(scene::invalidatedBy(scene::ChangeSet()), before, r->updateCounts()), "");
    EXPECT_EQ(r->accumulatedSpp(), 2u);

    struct Edit {
        scene::Change change;
        std::function<void()> apply;
    };
    const std::vector<Edit> edits = {
        {scene::Change::Camera, [&] { s.camera.eye += glm::dvec3(3.0, 0.0, 1.0); r->setSettings(s); }},
        {scene::Change::ImageSize, [&] { s.width = 20; r->setSettings(s); }},
        {scene::Change::Seed, [&] { s.seed = 7; r->setSettings(s); }},
        {scene::Change::Mode, [&] { s.mode = scene::Mode::Ae; r->setSettings(s); }},
        {scene::Change::Lighting, [&] { s.ambient = glm::dvec3(0.2); r->setSettings(s); }},
        {scene::Change::Medium, [&] { s.densityScale = 2.0; r->setSettings(s); }},
        {scene::Change::DvrOptions, [&] { s.dvrStep = 0.25; r->setSettings(s); }},
        {scene::Change::TransferFunction, [&] { r->setTransferFunction(scene::makePreset("foggy", v.valueLo(), v.valueHi())); }},
        {scene::Change::Shaders, [&] { r->reloadShaders(); }},
        {scene::Change::Control, [&] { s.controlExtinction = scene::ControlExtinction::Minorant; r->setSettings(s); }},
        {scene::Change::Structure, [&] {
             cfg.traversal = scene::TraversalKind::Abr;
             cfg.sampler = scene::SamplerKind::Abr;
             r->setStructure(cfg);
         }},
    };
    for (const Edit& e : edits) {
        SCOPED_TRACE(scene::describe(e.change));
        before = r->updateCounts();
        e.apply();
        const render::UpdateCounts after = r->updateCounts();
        EXPECT_EQ(disagreements(scene::invalidatedBy(e.change), before, after), "");
        // The check has power: the rule of another kind of change disagrees with what was done.
        const scene::Change other = e.change == scene::Change::Camera ? scene::Change::TransferFunction : scene::Change::Camera;
        EXPECT_NE(disagreements(scene::invalidatedBy(other), before, after), "");
        EXPECT_EQ(r->accumulatedSpp(), 0u) << "every change restarts the image";
        r->accumulate(1);
        const uint64_t compiled = r->updateCounts().pipelinesCompiled - after.pipelinesCompiled;
        // A pipeline is compiled after a drop (structure, shaders: reloadShaders compiles at once)
        // and for a mode or control extinction not used before; never otherwise.
        const bool expectCompile = (e.change == scene::Change::Structure) || (e.change == scene::Change::Mode) ||
                                   (e.change == scene::Change::Control);  // its own specialization
        EXPECT_EQ(compiled, expectCompile ? 1u : 0u);
    }
    EXPECT_TRUE(holdsDeviceBuffer(ctx(), "abrs"));
    EXPECT_FALSE(holdsDeviceBuffer(ctx(), "macrocellRanges")) << "the old combination's buffers are freed";
    EXPECT_FALSE(holdsDeviceBuffer(ctx(), "gridSamplerBrickLists"));
}

TEST_F(RendererGpu, AFailedStructureChangeKeepsThePreviousStructures) {
    // A renderer never runs with structures that were not built for its configuration: a change
    // that fails (a dense grid over its limit) throws and leaves the previous combination, which
    // renders exactly what it rendered before.
    scene::StructureConfig cfg;
    cfg.grid = "8";
    auto r = test::makeRenderer(ctx(), test::makeThreeLevelCloud(), cfg);
    r->setTransferFunction(rampOver(r->volume()));
    const scene::RenderSettings s = smallSettings(r->volume().model);
    const scene::RenderOutput before = r->render(s, 3);
    scene::StructureConfig dense = cfg;
    dense.sampler = scene::SamplerKind::Dense;
    dense.denseMaxBytes = 1024;  // far below this cloud's dense grid
    EXPECT_NE(test::errorOf([&] { r->setStructure(dense); }).find("--dense-max-mib"), std::string::npos);
    EXPECT_TRUE(r->config() == cfg);
    EXPECT_TRUE(r->scene().brickGrid.has_value() && r->scene().grid.has_value());
    const scene::RenderOutput after = r->render(s, 3);
    EXPECT_LT(maxRelativeDifference(after.mean, before.mean), 1e-6);
    EXPECT_EQ(after.stats.counter(shared::kCounterDensityLookups), before.stats.counter(shared::kCounterDensityLookups));
    scene::StructureConfig invalid = cfg;  // refused before anything is freed
    invalid.traversal = scene::TraversalKind::Abr;
    invalid.sampler = scene::SamplerKind::Dense;
    EXPECT_NE(test::errorOf([&] { r->setStructure(invalid); }).find("grid-dda or grid-bvh"), std::string::npos);
    EXPECT_TRUE(r->config() == cfg);
}

TEST_F(RendererGpu, AccumulationResumesWhereItStopped) {
    auto renderer = test::makeRenderer(ctx(), test::makeThreeLevelCloud(), test::gridDda(scene::SamplerKind::ExtBrick, "8"));
    render::Renderer& r = *renderer;
    r.setTransferFunction(rampOver(r.volume()));
    const scene::RenderSettings s = smallSettings(r.volume().model);
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
    const std::shared_ptr<const scene::Volume> volume = scene::makeVolume(test::makeThreeLevelCloud());
    scene::StructureConfig first, last;
    first.grid = "8";
    last.traversal = scene::TraversalKind::KdTree;
    last.kdLeaves = 64;
    scene::RenderSettings s = smallSettings(volume->model);
    render::Renderer edited(ctx(), volume, first);
    edited.setTransferFunction(scene::makePreset("foggy", volume->valueLo(), volume->valueHi()));
    edited.render(s, 2);
    // Edit everything, in an order a user might.
    s.camera.eye += glm::dvec3(-2.0, 4.0, 1.0);
    s.mode = scene::Mode::Ss;
    s.g = 0.4;
    edited.setSettings(s);
    edited.accumulate(1);
    const scene::TransferFunction tf = rampOver(*volume);
    edited.setTransferFunction(tf);
    edited.setStructure(last);
    EXPECT_EQ(edited.traversalBoxes().size(), 64u) << "the kd-tree has the requested leaves";
    edited.accumulate(6);
    const scene::RenderOutput a = edited.output();

    render::Renderer fresh(ctx(), volume, last);
    fresh.setTransferFunction(tf);
    const scene::RenderOutput b = fresh.render(s, 6);
    EXPECT_EQ(a.spp, b.spp);
    EXPECT_GT(a.stats.counter(shared::kCounterRealCollisions), 0u);
    EXPECT_LT(maxRelativeDifference(a.mean, b.mean), 1e-5);
}

TEST_F(RendererGpu, HostCullingSetEqualsTheGpuMajorants) {
    AMRVK_REQUIRE_DATA(test::kEnzoDataSet);
    const std::shared_ptr<const scene::Volume> volume = scene::makeVolume(test::readEnzoDensity());
    for (scene::TraversalKind t : {scene::TraversalKind::GridBvh, scene::TraversalKind::Abr,
                                   scene::TraversalKind::Brick, scene::TraversalKind::ExtBrick,
                                   scene::TraversalKind::KdTree}) {
        scene::StructureConfig c;
        c.traversal = t;
        c.grid = "32";
        c.kdLeaves = 256;
        render::Renderer r(ctx(), volume, c);
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

TEST_F(RendererGpu, ATfOfManyNodesCostsItsMeaningNotItsSize) {
    // 200,000 nodes in a ParaView JSON file (issue 23: 10^5 nodes took 70 s in the majorant pass,
    // a scan of every node per macrocell): the majorants, now O(log nodes) each, still equal the
    // CPU's exact maxAlpha over every macrocell range, and the kd-tree (built per TF from
    // thousands of maxAlpha calls) is built too.
    const std::shared_ptr<const scene::Volume> v = scene::makeVolume(test::makeThreeLevelCloud());
    const size_t n = 200000;
    scene::TfChannels c;
    c.name = "many";
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (size_t i = 0; i < n; ++i) {
        const float x = v->valueLo() + (v->valueHi() - v->valueLo()) * float(i) / float(n - 1);
        c.colorPositions.push_back(x);
        c.colors.emplace_back(u(rng), u(rng), u(rng));
        c.opacityPositions.push_back(x);
        c.alphas.push_back(u(rng) < 0.99f ? 0.0f : u(rng));
    }
    const std::filesystem::path file = test::scratchDir() / "many-nodes.json";
    test::writeAll(file, scene::paraViewPresetJson(c));
    const scene::TransferFunction tf = scene::loadTransferFunction(file.string(), 0.0f, 1.0f);
    ASSERT_GE(tf.nodeCount(), n);
    for (scene::TraversalKind t : {scene::TraversalKind::GridDda, scene::TraversalKind::KdTree}) {
        scene::StructureConfig cfg;
        cfg.traversal = t;
        cfg.grid = "32";
        cfg.kdLeaves = 512;
        render::Renderer r(ctx(), v, cfg);
        r.setTransferFunction(tf);
        SCOPED_TRACE(scene::traversalName(t));
        const std::vector<float> gpu = t == scene::TraversalKind::GridDda ? r.downloadMajorants() : r.downloadDomainMajorants();
        const std::vector<accel::ValueRange>& ranges =
            t == scene::TraversalKind::GridDda ? r.scene().grid->ranges : std::vector<accel::ValueRange>{};
        if (t == scene::TraversalKind::GridDda) {
            ASSERT_EQ(gpu.size(), ranges.size());
            size_t bad = 0, positive = 0;
            for (size_t i = 0; i < gpu.size(); ++i) {
                const float cpu = tf.maxAlpha(ranges[i].lo, ranges[i].hi);
                positive += cpu > 0.0f;
                if (std::abs(gpu[i] - cpu) > 1e-6f * std::max(1.0f, cpu) && bad++ < 5)
                    ADD_FAILURE() << "macrocell " << i << ": gpu " << gpu[i] << ", cpu " << cpu;
            }
            EXPECT_EQ(bad, 0u);
            EXPECT_GT(positive, gpu.size() / 2) << "1% of 2e5 nodes are opaque: most macrocells see one";
        } else {
            EXPECT_EQ(r.traversalBoxes().size(), 512u);
            EXPECT_GT(r.activeTraversalBoxes(), 0u);
        }
    }
}

TEST_F(RendererGpu, TrackingCapIsCountedNotSilent) {
    // Two halves in one macrocell: value 0 (alpha 0) in front, value 1 (alpha 1) behind. The
    // majorant is the back half's, so the front half costs density x length null collisions.
    amr::Model m = test::makeUniformBox({16, 16, 16}, 0, 1.0f);
    for (size_t i = 0; i < m.cells.size(); ++i)
        if (m.cells[i].lower.x < 8) m.fields[0].values[i] = 0.0f;
    render::Renderer r(ctx(), scene::makeVolume(std::move(m)), test::gridDda(scene::SamplerKind::ExtBrick, "1"));
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
// a multiple of 8, so the last dispatch takes 5); so does path regeneration (the workgroup's
// samples taken from a pool, at 8 per invocation: pools of 8, then of 5), whose sums are added in
// the same order; another seed does not (the check has power).
TEST_F(RendererGpu, SamplesPerInvocationRegroupTheSameSamples) {
    const std::shared_ptr<const scene::Volume> volume = scene::makeVolume(test::makeThreeLevelCloud());
    scene::StructureConfig cfg;
    cfg.grid = "8";
    auto renderOn = [&](uint32_t perInvocation, uint32_t seed, bool regeneration = false) {
        gpu::ContextOptions o;
        o.validation = true;
        o.samplesPerInvocation = perInvocation;
        o.pathRegeneration = regeneration;
        gpu::Context c(o);
        EXPECT_EQ(c.samplesPerInvocation(), perInvocation);
        scene::RenderOutput out;
        {
            render::Renderer r(c, volume, cfg);
            r.setTransferFunction(rampOver(*volume));
            scene::RenderSettings s = smallSettings(volume->model);
            s.seed = seed;
            out = r.render(s, 13);
        }
        EXPECT_EQ(c.validationErrors(), 0u) << c.lastValidationMessage();
        return out;
    };
    const scene::RenderOutput one = renderOn(1, 3), eight = renderOn(8, 3), other = renderOn(8, 4);
    const scene::RenderOutput pooled = renderOn(8, 3, true);
    EXPECT_EQ(eight.spp, 13u);
    // The same samples: the same counters and per-path statistics; only the lane slots (the SIMD
    // occupancy of invocations, which now hold 8 samples each) change.
    for (uint32_t k = 0; k < shared::kCounterCount; ++k) {
        if (k != shared::kCounterLookupLaneSlots) {
            EXPECT_EQ(one.stats.counters[k], eight.stats.counters[k]) << k;
        }
    }
    EXPECT_EQ(one.stats.path.bins, eight.stats.path.bins);
    EXPECT_EQ(one.stats.path.max, eight.stats.path.max);
    for (uint32_t k = 0; k < shared::kCounterCount; ++k) {
        if (k != shared::kCounterLookupLaneSlots) {
            EXPECT_EQ(eight.stats.counters[k], pooled.stats.counters[k]) << k;
        }
    }
    EXPECT_EQ(eight.stats.path.bins, pooled.stats.path.bins);
    EXPECT_LT(maxRelativeDifference(eight.mean, pooled.mean), 1e-6) << "the same sums in the same order";
    EXPECT_GT(one.stats.counters[shared::kCounterRealCollisions], 1000u);
    EXPECT_LT(maxRelativeDifference(one.mean, eight.mean), 1e-5);
    EXPECT_GT(maxRelativeDifference(one.mean, other.mean), 1e-2);
    EXPECT_NE(one.stats.counters[shared::kCounterDensityLookups], other.stats.counters[shared::kCounterDensityLookups]);
}

// Per-path statistics (render --json's perPath): one histogram entry per path and quantity, each
// quantity's bins bracket its counter's total (each path's count lies between its bin's ends), the
// percentiles are ordered and reach the maximum, the lane utilisation is a share of the lookup
// slots, and shadow rays' lookups are a part of all lookups (none without lights in ms).
TEST_F(RendererGpu, PathStatisticsAddUpToTheCounters) {
    const std::shared_ptr<const scene::Volume> volume = scene::makeVolume(test::makeThreeLevelCloud());
    scene::StructureConfig cfg;
    cfg.grid = "8";
    render::Renderer r(ctx(), volume, cfg);
    r.setTransferFunction(rampOver(*volume));
    scene::RenderSettings s = smallSettings(volume->model);
    const scene::RenderOutput out = r.render(s, 9);
    const scene::PathStats& p = out.stats.path;
    ASSERT_EQ(p.paths(), out.stats.paths);
    const auto& c = out.stats.counters;
    const uint32_t counterOf[shared::kPathQuantities] = {shared::kCounterDensityLookups, shared::kCounterNullCollisions,
                                                        shared::kCounterRealCollisions, shared::kCounterTraversalSteps};
    for (uint32_t q = 0; q < shared::kPathQuantities; ++q) {
        SCOPED_TRACE(q);
        uint64_t paths = 0, lo = 0, hi = 0;
        uint32_t top = 0;
        for (uint32_t b = 0; b < shared::kPathBins; ++b) {
            paths += p.bins[q][b];
            lo += p.bins[q][b] * scene::pathBinLow(b);
            hi += p.bins[q][b] * scene::pathBinHigh(b);
            if (p.bins[q][b] > 0) top = b;
        }
        EXPECT_EQ(paths, out.stats.paths);
        EXPECT_LE(lo, c[counterOf[q]]);
        EXPECT_GE(hi, c[counterOf[q]]);
        EXPECT_GE(p.max[q], scene::pathBinLow(top));
        EXPECT_LE(p.max[q], scene::pathBinHigh(top));
        const scene::PathDistribution d = scene::pathDistribution(p, q, c[counterOf[q]]);
        EXPECT_LE(d.p50, d.p90);
        EXPECT_LE(d.p90, d.p99);
        EXPECT_LE(d.p99, d.p999);
        EXPECT_GE(scene::pathQuantile(p.bins[q], 1.0), d.max);
        EXPECT_DOUBLE_EQ(d.mean, double(c[counterOf[q]]) / double(out.stats.paths));
    }
    EXPECT_GT(p.maxLookups(), 8u);  // paths that scatter take many lookups: the bins above 8 are used
    EXPECT_GT(p.max[shared::kPathReal], 1u);  // and collide more than once
    const uint64_t slots = c[shared::kCounterLookupLaneSlots];
    EXPECT_GE(slots, c[shared::kCounterDensityLookups]);
    EXPECT_GT(c[shared::kCounterDensityLookups], 0u);
    // The light's shadow rays take some of the lookups, free flight the others.
    EXPECT_GT(c[shared::kCounterShadowLookups], 0u);
    EXPECT_LT(c[shared::kCounterShadowLookups], c[shared::kCounterDensityLookups]);
    s.lights.clear();
    const scene::RenderOutput unlit = r.render(s, 2);
    EXPECT_EQ(unlit.stats.counter(shared::kCounterShadowLookups), 0u);
    EXPECT_GT(unlit.stats.counter(shared::kCounterDensityLookups), 0u);
}

// grid-dda's walk across empty blocks renders what the macrocell walk renders (tile z-test, two
// seeds), in fewer steps, with no majorant violation; the automatic choice follows the share of
// empty blocks under the TF (accel::kMinEmptyBlockFraction), and Always / Never override it.
TEST_F(RendererGpu, GridDdaAcrossEmptyBlocksRendersWhatTheMacrocellWalkRenders) {
    const std::shared_ptr<const scene::Volume> volume = scene::makeVolume(test::makeThreeLevelCloud());
    const scene::TransferFunction tf = test::zeroBelowMiddleTf(*volume, 2.0f, {0.8f, 0.9f, 1.0f});
    scene::StructureConfig c;
    c.grid = "32";
    render::Renderer r(ctx(), volume, c);
    r.setTransferFunction(tf);
    const render::MajorantPass& m = r.majorantPass();
    ASSERT_GT(m.blockCount(), 0u);
    ASSERT_GT(m.emptyBlocks(), 0u) << "the TF should empty some blocks";
    EXPECT_EQ(m.gridBlocksUsed(), double(m.emptyBlocks()) >= accel::kMinEmptyBlockFraction * double(m.blockCount()));
    scene::RenderSettings s = smallSettings(volume->model);
    using Use = render::MajorantPass::GridBlockUse;
    r.setGridBlockUse(Use::Never);
    EXPECT_FALSE(m.gridBlocksUsed());
    const scene::RenderOutput plain = r.render(s, 96);
    r.setGridBlockUse(Use::Always);
    EXPECT_TRUE(m.gridBlocksUsed());
    s.seed = 2;
    r.resetAccumulation();
    const scene::RenderOutput blocks = r.render(s, 96);
    EXPECT_GT(plain.stats.counter(shared::kCounterRealCollisions), 1000u);
    EXPECT_LT(blocks.stats.counter(shared::kCounterTraversalSteps), plain.stats.counter(shared::kCounterTraversalSteps));
    EXPECT_EQ(blocks.stats.counter(shared::kCounterMajorantViolations), 0u);
    test::expectSameImage(plain, blocks, 4, "grid-blocks");
}
