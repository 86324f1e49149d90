// Sub-majorants on the GPU (scene/sub_majorants.h, lib/sub_majorants.glsl), end to end. Delta
// tracking decides every collision as without them (the same random numbers, the same real
// collisions, the same picture) while the sub-boxes decide most null collisions without a lookup;
// looking those up anyway finds no extinction above its sub-majorant on Enzo and a cloud, under
// spiky, layers and ramp; with ratio-tracked shadows (thinned by the sub-majorants) the picture is
// the independent CPU reference integrator's. Power: sub-majorants planted far too low are caught
// by the check and change the picture beyond the z-test.
#include <gtest/gtest.h>

#include "amr/synthetic.h"
#include "gpu_fixture.h"
#include "image_compare.h"
#include "model_fixtures.h"
#include "render/renderer.h"
#include "render_fixtures.h"
#include "scene/reference_integrator.h"
#include "scene/tf_presets.h"
#include "test_data.h"

using namespace amrvk;

namespace {

class SubMajorantsGpu : public test::GpuTest {};

scene::RenderSettings settingsFor(const scene::Volume& v, int size) {
    scene::RenderSettings s;
    s.width = s.height = size;
    s.mode = scene::Mode::Ms;
    const amr::ModelSummary& sum = v.summary;
    s.camera = scene::defaultCamera(v.model.voxelToWorld.toWorld(glm::dvec3(sum.bounds.lower)),
                                     v.model.voxelToWorld.toWorld(glm::dvec3(sum.bounds.upper)));
    return s;
}

std::shared_ptr<const scene::Volume> enzoOrCloud() {
    if (std::filesystem::exists(test::dataDir() / test::kEnzoDataSet)) return scene::makeVolume(test::readEnzoDensity());
    amr::SyntheticParams p;
    p.cells = 100000;
    p.seed = 3;
    return scene::makeVolume(amr::makeSyntheticModel(p));
}

}  // namespace

// ms without lights is delta tracking alone: with sub-majorants the same random numbers make the
// same real collisions, so the picture is the one without them, and every null collision is either
// looked up or decided by its sub-box: nulls and lookups without them = nulls and lookups with
// them + the decided ones. grid-dda and grid-bvh (whose segments are macrocells too).
TEST_F(SubMajorantsGpu, TheSameCollisionsWithFewerLookups) {
    const std::shared_ptr<const scene::Volume> volume = enzoOrCloud();
    const scene::TransferFunction tf = scene::makePreset("spiky", volume->percentiles);
    for (scene::TraversalKind t : {scene::TraversalKind::GridDda, scene::TraversalKind::GridBvh}) {
        SCOPED_TRACE(scene::traversalName(t));
        scene::StructureConfig off;
        off.traversal = t;
        off.subMajorants = 0;
        scene::StructureConfig sub = off;
        sub.subMajorants = 8;
        auto render = [&](const scene::StructureConfig& c, bool check) {
            render::Renderer r(ctx(), volume, c);
            r.setTransferFunction(tf);
            r.setSubMajorantCheck(check);
            if (c.subMajorants > 0) {
                EXPECT_GT(r.majorantPass().subMajorants().refined, 100u);
            }
            return r.render(settingsFor(*volume, 24), 4);
        };
        const scene::RenderOutput a = render(off, false), b = render(sub, false), checked = render(sub, true);
        const auto& ca = a.stats.counters;
        const auto& cb = b.stats.counters;
        const uint64_t skips = cb[shared::kCounterSubMajorantSkips];
        EXPECT_EQ(ca[shared::kCounterSubMajorantSkips], 0u);
        EXPECT_GT(ca[shared::kCounterRealCollisions], 1000u);
        EXPECT_EQ(ca[shared::kCounterRealCollisions], cb[shared::kCounterRealCollisions]);
        EXPECT_EQ(ca[shared::kCounterNullCollisions], cb[shared::kCounterNullCollisions] + skips);
        EXPECT_EQ(ca[shared::kCounterDensityLookups], cb[shared::kCounterDensityLookups] + skips);
        EXPECT_GT(skips, cb[shared::kCounterDensityLookups]) << "most lookups are saved";
        EXPECT_LT(test::maxRelativeDifference(a.mean, b.mean), 1e-6) << "the same picture";
        // Looked up anyway: no extinction above any sub-majorant.
        EXPECT_EQ(checked.stats.counter(shared::kCounterMajorantViolations), 0u);
        EXPECT_EQ(checked.stats.counter(shared::kCounterDensityLookups), ca[shared::kCounterDensityLookups]);
        EXPECT_EQ(b.stats.counter(shared::kCounterMajorantViolations), 0u);
    }
}

// Every sub-box a collision falls in bounds its extinction, on every data set of the majorant
// test, under the presets whose macrocells get loose (spiky fitted and range-fixed, layers, ramp),
// with the grid sampler and the paper's ext-brick sampler, at the auto grid and a coarse one.
TEST_F(SubMajorantsGpu, NoViolationOnEveryDataSetAndPreset) {
    std::vector<std::pair<std::filesystem::path, const char*>> sets = {
        {std::filesystem::path(AMRVK_SOURCE_DIR) / "assets/samples/cloud.cells", ""}};
    for (auto [path, field] : {std::pair{test::kEnzoDataSet, "Density"}, std::pair{"amrex_pelelm_3d/example_plt_3d", "temp"},
                               std::pair{"ramses_galaxy_3d/output_00010", "density"}})
        if (std::filesystem::exists(test::dataDir() / path)) sets.emplace_back(test::dataDir() / path, field);
    for (const auto& [path, field] : sets) {
        SCOPED_TRACE(path.string());
        amr::ReadOptions ro;
        if (*field) ro.fields = {field};
        const std::shared_ptr<const scene::Volume> volume = scene::makeVolume(amr::readModel(path, ro));
        scene::RenderSettings s = settingsFor(*volume, 24);
        s.mode = scene::Mode::Ss;
        s.densityScale = 4.0;
        for (const auto& [sampler, grid] : {std::pair{scene::SamplerKind::Grid, "auto"}, std::pair{scene::SamplerKind::ExtBrick, "16"}}) {
            scene::StructureConfig c = test::gridDda(sampler, grid);
            c.subMajorants = 16;
            render::Renderer r(ctx(), volume, c);
            r.setSubMajorantCheck(true);
            for (const scene::TransferFunction& tf :
                 {scene::makePreset("spiky", volume->percentiles), scene::makePreset("spiky", volume->valueLo(), volume->valueHi()),
                  scene::makePreset("layers", volume->valueLo(), volume->valueHi()),
                  scene::makePreset("ramp", volume->valueLo(), volume->valueHi())}) {
                SCOPED_TRACE(tf.name() + " " + scene::samplerName(sampler) + " grid " + grid);
                r.setTransferFunction(tf);
                const scene::RenderOutput o = r.render(s, 2);
                EXPECT_EQ(o.stats.counter(shared::kCounterMajorantViolations), 0u);
                EXPECT_EQ(o.stats.counter(shared::kCounterNanSamples), 0u);
            }
        }
    }
}

// Shadow rays thin their ratio tracking with the sub-majorants (another estimator of the same
// transmittance): ss and ms with a light and the environment, under spiky on a small cloud with
// coarse macrocells (most of them refined), match the CPU reference integrator (one global
// majorant, brute-force reconstruction) tile by tile. Power: the same render with every
// sub-majorant planted at 1/255 of its macrocell's is caught (violations) and fails the z-test.
TEST_F(SubMajorantsGpu, ShadowsMatchTheReferenceIntegrator) {
    const amr::Model m = test::makeThreeLevelCloud();
    const std::shared_ptr<const scene::Volume> volume = scene::makeVolume(amr::Model(m));
    const scene::TransferFunction tf = scene::makePreset("spiky", volume->percentiles);
    const scene::ReferenceIntegrator cpu(m, m.fields[0], tf);
    scene::StructureConfig c = test::gridDda(scene::SamplerKind::Grid, "4");
    c.subMajorants = 8;
    render::Renderer r(ctx(), volume, c);
    r.setTransferFunction(tf);
    ASSERT_GT(r.majorantPass().subMajorants().refined, 10u);
    for (scene::Mode mode : {scene::Mode::Ss, scene::Mode::Ms}) {
        SCOPED_TRACE(scene::modeName(mode));
        scene::RenderSettings s = settingsFor(*volume, 16);
        s.mode = mode;
        s.densityScale = 0.5;
        s.ambient = glm::dvec3(0.6, 0.7, 0.9);
        s.background = glm::dvec3(0.05);
        s.lights.push_back({false, {1.0, 0.5, 2.0}, {2.0, 1.8, 1.5}});
        const scene::RenderOutput gpu = r.render(s, 1024);
        EXPECT_GT(gpu.stats.counter(shared::kCounterSubMajorantSkips), 0u);
        EXPECT_EQ(gpu.stats.counter(shared::kCounterMajorantViolations), 0u);
        const scene::RenderOutput ref = cpu.render(s, 512);
        test::expectSameImage(gpu, ref, 4, std::string("sub-majorants-") + scene::modeName(mode));
        if (mode == scene::Mode::Ss) {
            r.setSubMajorantCheck(true);
            r.overrideSubMajorants(1);
            const scene::RenderOutput low = r.render(s, 1024);
            EXPECT_GT(low.stats.counter(shared::kCounterMajorantViolations), 0u);
            EXPECT_GT(test::countDifferingTiles(low, ref, 4, 1e-3, 0.0, nullptr), 0) << "the z-test sees the planted error";
            r.setSubMajorantCheck(false);
            r.setTransferFunction(tf);  // sub-majorants built again
        }
    }
}

// The viewer's way (Renderer::setSubMajorantsInBackground): a TF edit returns before the
// sub-majorants are built, the accumulation goes on with the macrocell majorants, takes them when
// the build has finished, without a reset, and makes the very picture the synchronous renderer
// makes (delta tracking decides alike with and without them). A structure change or another TF
// edit while a build runs stops it first (nothing read after the scene changed).
TEST_F(SubMajorantsGpu, ABackgroundBuildIsTakenWithoutAReset) {
    const std::shared_ptr<const scene::Volume> volume = enzoOrCloud();
    const scene::TransferFunction spiky = scene::makePreset("spiky", volume->percentiles);
    const scene::TransferFunction foggy = scene::makePreset("foggy", volume->percentiles);
    scene::RenderSettings s = settingsFor(*volume, 24);
    render::Renderer sync(ctx(), volume, scene::StructureConfig{});
    sync.setTransferFunction(spiky);
    const scene::RenderOutput expected = sync.render(s, 4);

    render::Renderer r(ctx(), volume, scene::StructureConfig{});
    r.setSubMajorantsInBackground(true);
    r.setTransferFunction(foggy);
    r.setTransferFunction(spiky);  // stops foggy's build (none: foggy refines nothing) and starts spiky's
    r.setSettings(s);
    EXPECT_EQ(r.majorantPass().subMajorants().refined, 0u) << "not waited for";
    r.accumulate(1);
    const uint64_t resets = r.updateCounts().accumulationResets;
    r.waitForSubMajorants();
    EXPECT_GT(r.majorantPass().subMajorants().refined, 100u);
    r.accumulate(3);
    EXPECT_EQ(r.updateCounts().accumulationResets, resets) << "taken without a reset";
    const scene::RenderOutput out = r.output();
    EXPECT_EQ(out.spp, 4u);
    EXPECT_LT(test::maxRelativeDifference(out.mean, expected.mean), 1e-6);
    EXPECT_GT(out.stats.counter(shared::kCounterSubMajorantSkips), 0u);
    EXPECT_EQ(out.stats.counter(shared::kCounterMajorantViolations), 0u);

    // A structure change and a TF edit in the middle of builds: each stops the one running.
    for (int k = 0; k < 3; ++k) {
        r.setTransferFunction(k % 2 ? spiky : foggy);
        r.setTransferFunction(spiky);
        scene::StructureConfig c;
        c.traversal = k % 2 ? scene::TraversalKind::GridBvh : scene::TraversalKind::GridDda;
        r.setStructure(c);
    }
    r.waitForSubMajorants();
    EXPECT_GT(r.majorantPass().subMajorants().refined, 100u);
    EXPECT_EQ(r.render(s, 2).stats.counter(shared::kCounterMajorantViolations), 0u);
}
