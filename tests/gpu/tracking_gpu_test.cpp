// Delta and ratio tracking in a homogeneous medium against the analytic transmittance exp(-tau),
// for majorant overestimates 1, 4 and 32 and optical depths up to 50.
#include <cmath>

#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu_fixture.h"
#include "shared/test_push.h"
#include "render/renderer.h"
#include "render_fixtures.h"
#include "shared/render_params.h"

using namespace amrvk;

class TrackingGpu : public test::GpuTest {};

TEST_F(TrackingGpu, HomogeneousTransmittanceIsExponential) {
    // 16^3 level-0 cells, value 1; TF alpha a, density scale 1: sigma = a per voxel unit.
    amr::Model m = test::makeUniformBox({16, 16, 16}, 0, 1.0f);
    scene::VolumeScene scene = scene::buildVolumeScene(m, m.fields[0], scene::SamplerKind::ExtBrick, "4");
    render::Renderer renderer(ctx(), scene);
    const uint32_t n = 1u << 16;
    gpu::Buffer out(ctx(), uint64_t(n) * 8, gpu::MemoryKind::HostRead, "tracking");
    gpu::ComputePipeline pipe(ctx(), gpu::loadShader("test_tracking"), "test_tracking",
                              sizeof(shared::TestTrackingPush));
    const double length = 16.0;  // along x through the box
    for (double tau : {0.1, 1.0, 5.0, 20.0, 50.0}) {
        const float alpha = float(tau / length);
        renderer.setTransferFunction(test::constantTf(glm::vec3(1.0f), alpha));
        for (float over : {1.0f, 4.0f, 32.0f}) {
            SCOPED_TRACE(testing::Message() << "tau " << tau << " majorant x" << over);
            renderer.overrideMajorants(std::vector<float>(scene.grid->ranges.size(), alpha * over));
            shared::TestTrackingPush push{renderer.paramsAddress(), out.address(), {-3.0f, 8.3f, 7.6f, 0.0f},
                                          {1.0f, 0.0f, 0.0f, INFINITY}, n, uint32_t(scene::SamplerKind::ExtBrick),
                                          uint32_t(scene::TraversalKind::GridDda), 0};
            ctx().submitAndWait([&](VkCommandBuffer cmd) { pipe.dispatch(cmd, &push, n / 64); });
            auto v = out.download<float>();
            double escapes = 0, ratioSum = 0, ratioSq = 0;
            for (uint32_t i = 0; i < n; ++i) {
                escapes += v[2 * i];
                ratioSum += v[2 * i + 1];
                ratioSq += double(v[2 * i + 1]) * v[2 * i + 1];
            }
            const double T = std::exp(-tau);
            // Delta tracking: escapes ~ Binomial(n, T); 4.5 sigma, or none at all for tiny T.
            double sigma = std::sqrt(T * (1 - T) / n);
            if (T * n < 1e-6) {
                EXPECT_EQ(escapes, 0.0);
            } else {
                EXPECT_NEAR(escapes / n, T, 4.5 * sigma + 1e-12);
            }
            // Ratio tracking: mean T; tolerance from the sample standard error (4.5 sigma).
            double mean = ratioSum / n, var = std::max(0.0, ratioSq / n - mean * mean);
            EXPECT_NEAR(mean, T, 4.5 * std::sqrt(var / n) + 1e-7);
            if (over == 1.0f) {
                // With an exact majorant every tentative collision is real: the estimate is 0 or 1.
                EXPECT_NEAR(mean, escapes / n, 4.5 * sigma + 1e-7);
            }
        }
    }
}
