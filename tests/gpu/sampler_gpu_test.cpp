// GPU reconstruction (amr_sample.glsl, both samplers, sw and rq back-ends) against the CPU brute-force tent sum at
// 10^4 points, boundary points included, on Enzo and on a synthetic set with 3+ levels.
#include <random>

#include "accel/brick_sampler.h"
#include "amr/readers.h"
#include "amr/sampler.h"
#include "amr/synthetic.h"
#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu_fixture.h"
#include "kernels.h"
#include "model_fixtures.h"
#include "render/renderer.h"
#include "render_fixtures.h"
#include "scene/tf_presets.h"
#include "shared/render_params.h"
#include "test_data.h"

using namespace amrvk;

namespace {

class SamplerGpu : public test::GpuTest {
protected:
    void compare(const amr::Model& model, const amr::Field& field) {
        // The volume takes a copy (in brick order); the brute-force reference reads the original.
        const std::shared_ptr<const scene::Volume> volume = scene::makeVolume(model, field.name);
        for (auto [kind, backend] : test::samplerBackendCombos(ctx())) {
            SCOPED_TRACE(std::string(scene::samplerName(kind)) + "/" + scene::backendName(backend));
            scene::StructureConfig config;
            config.sampler = kind;
            config.backend = backend;
            config.grid = "16";
            render::Renderer renderer(ctx(), volume, config);
            renderer.setTransferFunction(scene::makePreset("ramp", volume->valueLo(), volume->valueHi()));
            const glm::dvec3 origin(volume->localOrigin);
            // Points in local voxel space (float): random inside cells, plus box features of bricks.
            std::vector<glm::vec4> pts;
            std::mt19937 rng(17);
            std::uniform_int_distribution<size_t> pick(0, model.cells.size() - 1);
            std::uniform_real_distribution<double> u(0.0, 1.0);
            while (pts.size() < 8000) {
                const amr::Cell& c = model.cells[pick(rng)];
                double w = double(amr::cellWidth(c.level));
                glm::dvec3 p = glm::dvec3(c.lower) + w * glm::dvec3(u(rng), u(rng), u(rng)) - origin;
                pts.emplace_back(glm::vec3(p), 0.0f);
            }
            auto boxes = accel::brickDomainBoxes(volume->bricks);
            for (size_t i = 0; pts.size() < 10000; i = (i + 1) % boxes.size()) {
                glm::dvec3 t(double(pts.size() % 3) * 0.5, double(pts.size() / 3 % 3) * 0.5, double(pts.size() / 9 % 3) * 0.5);
                glm::dvec3 p = boxes[i].lo + (boxes[i].hi - boxes[i].lo) * t - origin;
                pts.emplace_back(glm::vec3(p), 0.0f);
            }
            const uint32_t n = uint32_t(pts.size());
            const std::vector<float> got = test::sampleAt(ctx(), renderer.paramsAddress(), pts, kind, backend);
            amr::ReferenceSampler ref(model, field);
            size_t bad = 0;
            for (uint32_t i = 0; i < n && bad < 10; ++i) {
                glm::dvec3 p = glm::dvec3(glm::vec3(pts[i])) + origin;  // the exact point the GPU used
                amr::Sample s = ref.sample(p);
                float lo, hi;
                ref.contributingRange(p, lo, hi);
                double scale = std::max({std::abs(s.value), double(std::abs(lo)), double(std::abs(hi)), 1e-30});
                bool ok = std::abs(double(got[3 * i]) - s.value) <= 1e-5 * scale &&
                          std::abs(double(got[3 * i + 1]) - s.weightSum) <= 1e-5 * std::max(1.0, s.weightSum) &&
                          (got[3 * i + 2] != 0.0f) == (s.valid() && ref.insideLeafCell(p));
                if (!ok) {
                    ++bad;
                    ADD_FAILURE() << "point " << i << " (" << p.x << ", " << p.y << ", " << p.z << "): gpu value "
                                  << got[3 * i] << " weight " << got[3 * i + 1] << " inside " << got[3 * i + 2]
                                  << "; cpu value " << s.value << " weight " << s.weightSum << " inside "
                                  << ref.insideLeafCell(p);
                }
            }
        }
    }
};

}  // namespace

TEST_F(SamplerGpu, EqualsBruteForceOnEnzo) {
    AMRVK_REQUIRE_DATA(test::kEnzoDataSet);
    amr::Model m = test::readEnzoDensity();
    compare(m, m.field("Density"));
}

TEST_F(SamplerGpu, EqualsBruteForceOnASyntheticCloud) {
    amr::SyntheticParams p;
    p.kind = amr::SyntheticKind::Cloud;
    p.cells = 20000;
    p.seed = 3;
    amr::Model m = amr::makeSyntheticModel(p);
    ASSERT_GE(amr::summarize(m).maxLevel - amr::summarize(m).minLevel, 2);
    compare(m, m.defaultField());
}
