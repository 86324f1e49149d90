// The dense sampler on the GPU (amr_sample.glsl sampleDense, grid traversals): point values equal
// the CPU definition (accel/dense_grid.h, itself checked against brute force) at 10^4 points; on
// data whose leaves are all on the finest level the dense image equals the AMR sampler's image
// (same reconstruction there); on a 3-level cloud its majorants (from the dense samples) are never
// violated.
#include <random>

#include "accel/dense_grid.h"
#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu_fixture.h"
#include "image_compare.h"
#include "kernels.h"
#include "model_fixtures.h"
#include "render/renderer.h"
#include "render_fixtures.h"
#include "scene/tf_presets.h"

using namespace amrvk;

namespace {

class DenseGridGpu : public test::GpuTest {
protected:
    scene::RenderOutput renderWith(const amr::Model& m, scene::SamplerKind sampler, scene::TraversalKind t,
                                    const scene::TransferFunction& tf, const scene::RenderSettings& s, uint32_t spp) {
        scene::StructureConfig c;
        c.sampler = sampler;
        c.traversal = t;
        c.grid = "16";
        render::Renderer r(ctx(), scene::makeVolume(m), c);
        r.setTransferFunction(tf);
        scene::RenderOutput o = r.render(s, spp);
        EXPECT_EQ(o.stats.counter(shared::kCounterMajorantViolations), 0u) << c.label();
        EXPECT_EQ(o.stats.counter(shared::kCounterNanSamples), 0u) << c.label();
        return o;
    }
};

scene::RenderSettings smallSettings(const amr::Model& m, scene::Mode mode) {
    amr::ModelSummary sum = amr::summarize(m);
    scene::RenderSettings s;
    s.mode = mode;
    s.width = s.height = 24;
    s.camera = scene::defaultCamera(glm::dvec3(sum.bounds.lower), glm::dvec3(sum.bounds.upper));
    return s;
}

}  // namespace

TEST_F(DenseGridGpu, PointValuesEqualTheCpuDefinition) {
    amr::Model m = test::makeThreeLevelCloud();
    scene::StructureConfig c;
    c.sampler = scene::SamplerKind::Dense;
    c.grid = "16";
    render::Renderer renderer(ctx(), scene::makeVolume(std::move(m)), c);
    const scene::VolumeScene& scene = renderer.scene();
    ASSERT_TRUE(scene.dense.has_value());
    renderer.setTransferFunction(scene::makePreset("ramp", scene.volume().valueLo(), scene.volume().valueHi()));
    const glm::dvec3 origin(scene.volume().localOrigin);
    const glm::dvec3 size(scene.volume().bounds().size());
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-0.02, 1.02);  // a little outside too (clamping)
    std::vector<glm::vec4> pts;
    for (int i = 0; i < 10000; ++i) pts.emplace_back(glm::vec3(size * glm::dvec3(u(rng), u(rng), u(rng))), 0.0f);
    const uint32_t n = uint32_t(pts.size());
    const std::vector<float> got =
        test::sampleAt(ctx(), renderer.paramsAddress(), pts, scene::SamplerKind::Dense, scene::Backend::Sw);
    size_t bad = 0, inside = 0;
    for (uint32_t i = 0; i < n && bad < 10; ++i) {
        const glm::dvec3 p = glm::dvec3(glm::vec3(pts[i])) + origin;
        accel::DenseSample s = accel::sampleDense(*scene.dense, p);
        const bool gpuInside = got[3 * i + 2] != 0.0f;
        inside += gpuInside;
        bool ok = gpuInside == s.inside && (!s.inside || std::abs(got[3 * i] - s.value) <= 1e-5f * std::max(1.0f, std::abs(s.value)));
        if (!ok) {
            ++bad;
            ADD_FAILURE() << "point " << i << ": gpu " << got[3 * i] << " inside " << gpuInside << "; cpu " << s.value
                          << " inside " << s.inside;
        }
    }
    EXPECT_GT(inside, n / 10);  // the points do reach the medium
}

TEST_F(DenseGridGpu, FinestLevelDataGivesTheAmrImage) {
    // A full level-0 box with a smooth field: clamped trilinear at cell centres is the tent reconstruction.
    amr::Model m = test::makeUniformBox({24, 20, 16}, 0, 0.0f);
    for (size_t i = 0; i < m.cells.size(); ++i) {
        glm::dvec3 c = glm::dvec3(m.cells[i].lower) + 0.5;
        m.fields[0].values[i] = float(0.5 + 0.5 * std::sin(0.4 * c.x) * std::cos(0.3 * c.y + 0.2 * c.z));
    }
    const scene::TransferFunction tf = scene::makePreset("spiky", 0.0f, 1.0f);
    scene::RenderSettings s = smallSettings(m, scene::Mode::Ms);
    s.densityScale = 0.5;
    scene::RenderOutput amrImage = renderWith(m, scene::SamplerKind::ExtBrick, scene::TraversalKind::GridDda, tf, s, 24);
    s.seed = 99;  // independent samples
    for (scene::TraversalKind t : {scene::TraversalKind::GridDda, scene::TraversalKind::GridBvh}) {
        scene::RenderOutput dense = renderWith(m, scene::SamplerKind::Dense, t, tf, s, 24);
        test::expectSameImage(dense, amrImage, 4, std::string("dense-") + scene::traversalName(t));
    }
}

TEST_F(DenseGridGpu, MajorantsHoldOnAThreeLevelCloud) {
    amr::Model m = test::makeThreeLevelCloud();
    amr::FieldStats st = amr::computeFieldStats(m, m.fields[0]);
    const scene::TransferFunction tf = scene::makePreset("spiky", st.minValue, st.maxValue);
    scene::RenderSettings s = smallSettings(m, scene::Mode::Ae);
    s.densityScale = 4;
    for (scene::TraversalKind t : {scene::TraversalKind::GridDda, scene::TraversalKind::GridBvh}) {
        scene::RenderOutput o = renderWith(m, scene::SamplerKind::Dense, t, tf, s, 4);
        EXPECT_GT(o.stats.counter(shared::kCounterRealCollisions), 0u);
    }
}

TEST_F(DenseGridGpu, NeedsAGridTraversalAndRespectsTheMemoryLimit) {
    amr::Model m = test::makeThreeLevelCloud();
    scene::StructureConfig c;
    c.sampler = scene::SamplerKind::Dense;
    c.traversal = scene::TraversalKind::Abr;
    const std::shared_ptr<const scene::Volume> v = scene::makeVolume(std::move(m));
    EXPECT_NE(test::errorOf([&] { scene::VolumeScene(v, c); }).find("grid-dda or grid-bvh"), std::string::npos);
    c.traversal = scene::TraversalKind::GridDda;
    c.denseMaxBytes = 1024;
    EXPECT_NE(test::errorOf([&] { scene::VolumeScene(v, c); }).find("--dense-max-mib"), std::string::npos);
}
