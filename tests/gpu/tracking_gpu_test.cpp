// Delta and ratio tracking in a homogeneous medium against closed forms, for majorant
// overestimates 1, 4 and 32 and optical depths up to 50: the escape probability and the ratio
// estimate have mean exp(-tau), and delta tracking's first collision lies at an exponential
// distance (rate sigma) truncated to the chord. Every two-sided check states its power: its
// tolerance is below half the value (an estimator returning 0 fails) or below 10% of it. Where
// exp(-tau) is too small for 2^16 samples to see (tau 20 and 50: about 1e-4 escapes expected), the
// transmittance checks are one-sided (too much light fails) and the collision distance, which the
// same free-flight loop produces, carries the power.
#include <cmath>

#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu_fixture.h"
#include "render/renderer.h"
#include "render_fixtures.h"
#include "shared/render_params.h"
#include "shared/test_push.h"

using namespace amrvk;

class TrackingGpu : public test::GpuTest {};

TEST_F(TrackingGpu, HomogeneousTransmittanceIsExponential) {
    // 16^3 level-0 cells, value 1; TF alpha a, density scale 1: sigma = a per voxel unit.
    auto renderer = test::makeRenderer(ctx(), test::makeUniformBox({16, 16, 16}, 0, 1.0f),
                                       test::gridDda(scene::SamplerKind::ExtBrick, "4"));
    const uint32_t n = 1u << 16;
    gpu::Buffer out(ctx(), uint64_t(n) * 16, gpu::MemoryKind::HostRead, "tracking");
    gpu::ComputePipeline pipe(ctx(), gpu::loadShader("test_tracking"), "test_tracking",
                              sizeof(shared::TestTrackingPush));
    const double length = 16.0, entry = 3.0;  // along x through the box, from x = -3
    size_t powered = 0, oneSided = 0;
    for (double tau : {0.1, 1.0, 5.0, 20.0, 50.0}) {
        const float alpha = float(tau / length);
        const double sigma = double(alpha);
        renderer->setTransferFunction(test::constantTf(glm::vec3(1.0f), alpha));
        for (float over : {1.0f, 4.0f, 32.0f}) {
            SCOPED_TRACE(testing::Message() << "tau " << tau << " majorant x" << over);
            renderer->overrideMajorants(std::vector<float>(renderer->scene().grid->ranges.size(), alpha * over));
            shared::TestTrackingPush push{renderer->paramsAddress(), out.address(), {-3.0f, 8.3f, 7.6f, 0.0f},
                                          {1.0f, 0.0f, 0.0f, INFINITY}, n, uint32_t(scene::SamplerKind::ExtBrick),
                                          uint32_t(scene::TraversalKind::GridDda), 0};
            ctx().submitAndWait([&](VkCommandBuffer cmd) { pipe.dispatch(cmd, &push, n / 64); });
            auto v = out.download<float>();
            double escapes = 0, ratioSum = 0, ratioSq = 0, capped = 0, hits = 0, dSum = 0, dSq = 0;
            for (uint32_t i = 0; i < n; ++i) {
                const float r = v[4 * i + 1];
                ASSERT_TRUE(std::isfinite(r) && r >= 0.0f) << "ratio estimate " << r;
                escapes += v[4 * i];
                ratioSum += r;
                ratioSq += double(r) * r;
                capped += v[4 * i + 3];
                if (v[4 * i] == 0.0f) {
                    const double d = double(v[4 * i + 2]) - entry;  // collision distance into the box
                    ASSERT_TRUE(d >= -1e-4 && d <= length + 1e-4) << "collision outside the medium at " << d;
                    hits += 1;
                    dSum += d;
                    dSq += d * d;
                }
            }
            EXPECT_EQ(capped, 0.0) << "no tracking call may reach the step cap";
            const double T = std::exp(-tau);

            // Delta tracking: escapes ~ Binomial(n, T), 4.5 sigma from the binomial variance.
            const double tolEscape = 4.5 * std::sqrt(T * (1 - T) / n);
            const double pEscape = escapes / n;
            // Ratio tracking: mean T, tolerance from the sample variance.
            const double mean = ratioSum / n, var = std::max(0.0, ratioSq / n - mean * mean);
            const double tolRatio = 4.5 * std::sqrt(var / n);
            if (T * n >= 100) {
                // Power: a zero estimate (or one off by half) is outside the tolerance.
                ASSERT_LT(tolEscape, 0.5 * T);
                EXPECT_NEAR(pEscape, T, tolEscape);
                if (var > 0 && tolRatio < 0.5 * T) {
                    EXPECT_NEAR(mean, T, tolRatio);
                    ++powered;
                } else {
                    // Too few surviving ratio estimates for a two-sided test: one-sided.
                    EXPECT_LE(mean, T + std::max(tolRatio, 4.5 * std::sqrt(T / n)));
                    ++oneSided;
                }
            } else {
                // exp(-tau) n << 1: any escape is (essentially) too much light; mean <= T + 4.5 sigma.
                EXPECT_LE(escapes, 1.0);
                EXPECT_LE(mean, T + std::max(tolRatio, 4.5 * std::sqrt(T / n)));
                ++oneSided;
            }
            if (over == 1.0f) {
                // With an exact majorant every tentative collision is real: the estimate is 0 or 1.
                EXPECT_NEAR(mean, pEscape, tolEscape + 1e-12);
            }

            // Delta tracking's collision distance: Exp(sigma) truncated to [0, L], mean
            // 1/sigma - L e^{-sigma L} / (1 - e^{-sigma L}); tolerance 4.5 standard errors.
            ASSERT_GT(hits, 1000.0);
            const double expMean = 1.0 / sigma - length * T / (1.0 - T);
            const double dMean = dSum / hits, dVar = std::max(0.0, dSq / hits - dMean * dMean);
            const double tolDist = 4.5 * std::sqrt(dVar / hits);
            ASSERT_LT(tolDist, 0.1 * expMean) << "power: a 10% error in the extinction is caught";
            EXPECT_NEAR(dMean, expMean, tolDist);
        }
    }
    // The two-sided ratio check ran where the data can see it (tau <= 5), one-sided beyond.
    EXPECT_GE(powered, 8u);
    EXPECT_EQ(powered + oneSided, 15u);
}
