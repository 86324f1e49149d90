// Delta and ratio tracking in a homogeneous medium against closed forms, for majorant
// overestimates 1, 4 and 32 and optical depths up to 50: the escape probability and the ratio
// estimate have mean exp(-tau), and delta tracking's first collision lies at an exponential
// distance (rate sigma) truncated to the chord. Unbiased ray marching (lib/unbiased_march.glsl)
// has zero variance there: every estimate is exp(-tau) to float rounding, and past its roulette's
// depth (tau 20 and 50) either 0 or exp(-tau) / q, the latter for a share q of the rays. Every two-sided check states
// its power: its tolerance is below half the value (an estimator returning 0 fails) or below 10% of it. Where exp(-tau)
// is too small for 2^16 samples to see (tau 20 and 50: about 1e-4 escapes expected), the transmittance checks are
// one-sided (too much light fails) and the collision distance, which the same free-flight loop produces, carries the
// power.
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

namespace {

// test_tracking (tests/shaders/test_tracking.comp): n estimates along +x from `origin` (local
// voxel) to infinity through grid-dda, eight floats each.
struct TrackingKernel {
    gpu::Context& ctx;
    uint32_t n;
    gpu::Buffer out{ctx, uint64_t(n) * 32, gpu::MemoryKind::HostRead, "tracking"};
    // With the control extinction's code (constant 5): it runs where the renderer made minorants.
    gpu::ComputePipeline pipe{
        ctx, gpu::loadShader("test_tracking"), "test_tracking", sizeof(shared::TestTrackingPush), {{5, 1u}}};

    std::vector<float> run(render::Renderer& r, glm::vec3 origin, scene::SamplerKind sampler, bool withUbrm) {
        shared::TestTrackingPush push{r.paramsAddress(),
                                      out.address(),
                                      glm::vec4(origin, 0.0f),
                                      {1.0f, 0.0f, 0.0f, INFINITY},
                                      n,
                                      uint32_t(sampler),
                                      uint32_t(scene::TraversalKind::GridDda),
                                      withUbrm ? 1u : 0u};
        ctx.submitAndWait([&](VkCommandBuffer cmd) { pipe.dispatch(cmd, &push, n / 64); });
        return out.download<float>();
    }
};

}  // namespace

TEST_F(TrackingGpu, HomogeneousTransmittanceIsExponential) {
    // 16^3 level-0 cells, value 1; TF alpha a, density scale 1: sigma = a per voxel unit.
    auto renderer = test::makeRenderer(ctx(), test::makeUniformBox({16, 16, 16}, 0, 1.0f),
                                       test::gridDda(scene::SamplerKind::ExtBrick, "4"));
    const uint32_t n = 1u << 16;
    TrackingKernel kernel{ctx(), n};
    const double length = 16.0, entry = 3.0;  // along x through the box, from x = -3
    size_t powered = 0, oneSided = 0;
    for (double tau : {0.1, 1.0, 5.0, 20.0, 50.0}) {
        const float alpha = float(tau / length);
        const double sigma = double(alpha);
        renderer->setTransferFunction(test::constantTf(glm::vec3(1.0f), alpha));
        for (float over : {1.0f, 4.0f, 32.0f}) {
            SCOPED_TRACE(testing::Message() << "tau " << tau << " majorant x" << over);
            // Unbiased ray marching at the exact majorant, and below its roulette at the loosest.
            const bool withUbrm = over == 1.0f || (over == 32.0f && tau < 10);
            renderer->overrideMajorants(std::vector<float>(renderer->scene().grid->ranges.size(), alpha * over));
            const std::vector<float> v =
                kernel.run(*renderer, {-3.0f, 8.3f, 7.6f}, scene::SamplerKind::ExtBrick, withUbrm);
            // Past the roulette's depth a ray is kept with probability q, weighted 1 / q.
            const double kept = tau > 8.0 ? 0.1 : 1.0;
            double escapes = 0, ratioSum = 0, ratioSq = 0, capped = 0, hits = 0, dSum = 0, dSq = 0, ubrmErr = 0,
                   ubrmKept = 0;
            for (uint32_t i = 0; i < n; ++i) {
                const float r = v[8 * i + 1];
                ASSERT_TRUE(std::isfinite(r) && r >= 0.0f) << "ratio estimate " << r;
                const double u = v[8 * i + 7];
                if (withUbrm && (u != 0.0 || kept == 1.0)) {
                    ubrmErr = std::max(ubrmErr, std::abs(u * kept / std::exp(-tau) - 1.0));
                    ++ubrmKept;
                }
                escapes += v[8 * i];
                ratioSum += r;
                ratioSq += double(r) * r;
                capped += v[8 * i + 3];
                if (v[8 * i] == 0.0f) {
                    const double d = double(v[8 * i + 2]) - entry;  // collision distance into the box
                    ASSERT_TRUE(d >= -1e-4 && d <= length + 1e-4) << "collision outside the medium at " << d;
                    hits += 1;
                    dSum += d;
                    dSq += d * d;
                }
            }
            EXPECT_EQ(capped, 0.0) << "no tracking call may reach the step cap";
            const double T = std::exp(-tau);
            EXPECT_LT(ubrmErr, 1e-3) << "unbiased ray marching is exact in a constant medium";
            if (withUbrm) {
                EXPECT_NEAR(ubrmKept / n, kept, 4.5 * std::sqrt(kept * (1 - kept) / n));
            }

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

namespace {

// The extinction along x of the ramp below (value = x between the first and last cell centres,
// density scale 1, level-0 cells): the TF's alpha at the clamped value.
double rampSigma(const scene::TransferFunction& tf, double x) { return tf.evaluate(float(std::clamp(x, 0.5, 63.5))).a; }

}  // namespace

// Sub-majorants (scene/sub_majorants.h) on a field whose answer is known: level-0 cells 64 x 4 x 4
// with value x (the reconstruction is x itself between the first and last centres), two narrow
// TF peaks inside macrocells 16 voxels long, so those macrocells are split into sub-boxes. Along x,
// delta tracking takes exactly the decisions it takes without them (the same collision, or escape,
// for every random sequence) with far fewer lookups; ratio tracking, which thins its collisions
// with them, has mean exp(-tau); the escape probability is exp(-tau) and the mean collision depth
// that of the density sigma(x) e^(-tau(x)); unbiased ray marching, whose combs skip the sub-boxes
// of majorant 0, has mean exp(-tau) too. 2^19 estimates: each check's tolerance (4.5 standard
// errors) is below 2% of its answer, so a 2% error in the extinction or the transmittance fails.
TEST_F(TrackingGpu, SubMajorantsTrackARampExactly) {
    amr::Model m = test::makeUniformBox({64, 4, 4}, 0, 0.0f);
    for (size_t i = 0; i < m.cells.size(); ++i) m.fields[0].values[i] = float(m.cells[i].lower.x) + 0.5f;
    const scene::TransferFunction tf({0.0f, 19.5f, 20.25f, 21.0f, 41.2f, 41.6f, 42.0f, 64.0f},
                                     {glm::vec4(1, 1, 1, 0), glm::vec4(1, 1, 1, 0), glm::vec4(1, 1, 1, 1),
                                      glm::vec4(1, 1, 1, 0), glm::vec4(1, 1, 1, 0), glm::vec4(1, 1, 1, 0.8f),
                                      glm::vec4(1, 1, 1, 0), glm::vec4(1, 1, 1, 0)},
                                     "two peaks");
    scene::StructureConfig sub = test::gridDda(scene::SamplerKind::Grid, "4");
    sub.subMajorants = 8;
    scene::StructureConfig off = sub;
    off.subMajorants = 0;
    auto renderer = test::makeRenderer(ctx(), std::move(m), off);
    renderer->setTransferFunction(tf);
    const uint32_t n = 1u << 19;
    TrackingKernel kernel{ctx(), n};
    auto run = [&](bool withUbrm) {
        return kernel.run(*renderer, {-3.0f, 2.1f, 1.9f}, scene::SamplerKind::Grid, withUbrm);
    };
    const std::vector<float> plain = run(false);  // (UnbiasedRayMarchingMatchesASmoothFieldsDepth: without sub-boxes)
    renderer->setStructure(sub);
    renderer->setSubMajorantCheck(true);
    ASSERT_GT(renderer->majorantPass().subMajorants().refined, 0u);
    const std::vector<float> v = run(true);

    // The answers: tau = the two triangles' areas (1 x 0.75 + 0.8 x 0.4); the mean collision depth
    // from the density sigma(x) e^(-tau(x)) over the hits (midpoint rule at 2^20 steps).
    const double tau = 0.75 + 0.32, T = std::exp(-tau), entry = 3.0;
    double depth = 0, acc = 0;
    const int steps = 1 << 20;
    for (int k = 0; k < steps; ++k) {
        const double x = 64.0 * (k + 0.5) / steps, s = rampSigma(tf, x);
        depth += x * s * std::exp(-acc) * (64.0 / steps);
        acc += s * (64.0 / steps);
    }
    ASSERT_NEAR(acc, tau, 1e-6);
    depth /= 1.0 - T;

    double escapes = 0, ratio = 0, ratioSq = 0, hits = 0, dSum = 0, dSq = 0, lookups = 0, lookupsPlain = 0, skips = 0,
           violations = 0, same = 0, capped = 0, ubrm = 0, ubrmSq = 0;
    for (uint32_t i = 0; i < n; ++i) {
        const float* r = &v[8 * size_t(i)];
        const float* p = &plain[8 * size_t(i)];
        same += r[0] == p[0] && r[2] == p[2];  // the same escape, or the same collision point
        escapes += r[0];
        ratio += r[1];
        ratioSq += double(r[1]) * r[1];
        ubrm += r[7];
        ubrmSq += double(r[7]) * r[7];
        capped += r[3] + p[3];
        lookups += r[4];
        lookupsPlain += p[4];
        skips += r[5];
        violations += r[6] + p[6];
        if (r[0] == 0.0f) {
            const double d = double(r[2]) - entry;
            hits += 1;
            dSum += d;
            dSq += d * d;
        }
    }
    EXPECT_EQ(same, double(n)) << "delta tracking decides as without sub-majorants";
    EXPECT_EQ(violations, 0.0);
    EXPECT_EQ(capped, 0.0);
    // Under the check every decided collision is looked up too: lookups - skips are the tracker's own.
    EXPECT_GT(skips, lookups - skips) << "the sub-boxes decide most collisions";
    EXPECT_LT(lookups - skips, 0.5 * lookupsPlain);
    const double tolEscape = 4.5 * std::sqrt(T * (1 - T) / n);
    ASSERT_LT(tolEscape, 0.02 * T) << "power: a 2% error in the transmittance is caught";
    EXPECT_NEAR(escapes / n, T, tolEscape);
    const double mean = ratio / n, tolRatio = 4.5 * std::sqrt(std::max(0.0, ratioSq / n - mean * mean) / n);
    ASSERT_LT(tolRatio, 0.02 * T);
    EXPECT_NEAR(mean, T, tolRatio);
    const double ubrmMean = ubrm / n, tolUbrm = 4.5 * std::sqrt(std::max(0.0, ubrmSq / n - ubrmMean * ubrmMean) / n);
    ASSERT_LT(tolUbrm, 0.02 * T);
    EXPECT_NEAR(ubrmMean, T, tolUbrm);
    const double dMean = dSum / hits, tolDepth = 4.5 * std::sqrt(std::max(0.0, dSq / hits - dMean * dMean) / hits);
    ASSERT_LT(tolDepth, 0.02 * depth);
    EXPECT_NEAR(dMean, depth, tolDepth);

    // The check's own power: sub-majorants far too low (q = 1 of 255) are caught as violations,
    // and the transmittance they give is then wrong (too much light).
    renderer->overrideSubMajorants(1);
    const std::vector<float> low = run(false);
    double lowViolations = 0, lowEscapes = 0;
    for (uint32_t i = 0; i < n; ++i) {
        lowViolations += low[8 * size_t(i) + 6];
        lowEscapes += low[8 * size_t(i)];
    }
    EXPECT_GT(lowViolations, 1000.0);
    EXPECT_GT(lowEscapes / n, T + tolEscape);
}

// Unbiased ray marching (lib/unbiased_march.glsl) on a field whose optical depth is known and
// varies along the ray: level-0 cells 64 x 4 x 4 with value x and a TF whose alpha rises linearly
// from 0 to 0.06 over the values, then falls to 0.02, on a grid of 16 macrocells (their majorants
// differ, so the comb's density does too). tau is the integral of the TF's alpha along x (2^20
// midpoint steps). 2^19 estimates of each estimator along x: unbiased ray marching has mean
// exp(-tau) within 4.5 standard errors, a tolerance below 2% of the answer (a 2% error fails), and
// a lower variance than ratio tracking on this smooth field; a transmittance of exp(-1.02 tau),
// the answer with 2% more extinction, is rejected.
TEST_F(TrackingGpu, UnbiasedRayMarchingMatchesASmoothFieldsDepth) {
    amr::Model m = test::makeUniformBox({64, 4, 4}, 0, 0.0f);
    for (size_t i = 0; i < m.cells.size(); ++i) m.fields[0].values[i] = float(m.cells[i].lower.x) + 0.5f;
    const scene::TransferFunction tf({0.0f, 40.0f, 64.0f},
                                     {glm::vec4(1, 1, 1, 0), glm::vec4(1, 1, 1, 0.06f), glm::vec4(1, 1, 1, 0.02f)},
                                     "rise and fall");
    auto renderer = test::makeRenderer(ctx(), std::move(m), test::gridDda(scene::SamplerKind::Grid, "16"));
    renderer->setTransferFunction(tf);
    const uint32_t n = 1u << 19;
    const std::vector<float> v =
        TrackingKernel{ctx(), n}.run(*renderer, {-3.0f, 2.1f, 1.9f}, scene::SamplerKind::Grid, true);
    double tau = 0;
    const int steps = 1 << 20;
    for (int k = 0; k < steps; ++k) tau += rampSigma(tf, 64.0 * (k + 0.5) / steps) * (64.0 / steps);
    const double T = std::exp(-tau);
    double ubrm = 0, ubrmSq = 0, ratio = 0, ratioSq = 0, capped = 0, violations = 0;
    for (uint32_t i = 0; i < n; ++i) {
        const float* r = &v[8 * size_t(i)];
        ASSERT_TRUE(std::isfinite(r[7])) << "estimate " << i;
        ubrm += r[7];
        ubrmSq += double(r[7]) * r[7];
        ratio += r[1];
        ratioSq += double(r[1]) * r[1];
        capped += r[3];
        violations += r[6];
    }
    EXPECT_EQ(capped, 0.0);
    EXPECT_EQ(violations, 0.0);
    const double mean = ubrm / n, var = std::max(0.0, ubrmSq / n - mean * mean), tol = 4.5 * std::sqrt(var / n);
    const double ratioMean = ratio / n, ratioVar = std::max(0.0, ratioSq / n - ratioMean * ratioMean);
    SCOPED_TRACE(testing::Message() << "tau " << tau << " ubrm " << mean << " +- " << tol << " (variance " << var
                                    << ") ratio " << ratioMean << " (variance " << ratioVar << ")");
    ASSERT_GT(tau, 1.0);
    ASSERT_LT(tol, 0.02 * T) << "power: a 2% error in the transmittance is caught";
    EXPECT_NEAR(mean, T, tol);
    EXPECT_GT(std::abs(mean - std::exp(-1.02 * tau)), tol) << "2% more extinction is rejected";
    EXPECT_LT(var, ratioVar) << "on a smooth field the comb's variance is below ratio tracking's";
}

// The control extinction (--control-extinction minorant, lib/tracking.glsl) on a field whose
// answer is known: level-0 cells 64 x 4 x 4 with value x and a TF with an alpha floor of 0.01, a
// narrow peak of 1 near x = 20 and a rise to 0.02, on 4 macrocells (their minorants are the floor
// or more), with and without sub-majorants. Along x, 2^19 estimates each: decomposition tracking's
// escape share and mean collision depth, and residual ratio tracking's mean, equal exp(-tau) and
// the analytic depth within 4.5 standard errors, tolerances below 2% of the answers (a 2% error
// fails; exp(-1.02 tau) is rejected); no extinction lies below its minorant or above its
// (sub-)majorant. Residual ratio tracking's variance is under half ratio tracking's (measured 0.029
// against 0.087: the floor's share is exact, where ratio tracking's weight 1 - sigma / M is 0 in
// the floor's macrocell, sigma = M), and sub-majorants cut the residual's lookups (measured 4x).
TEST_F(TrackingGpu, ControlExtinctionTracksAFieldWithAFloorExactly) {
    amr::Model m = test::makeUniformBox({64, 4, 4}, 0, 0.0f);
    for (size_t i = 0; i < m.cells.size(); ++i) m.fields[0].values[i] = float(m.cells[i].lower.x) + 0.5f;
    const scene::TransferFunction tf({0.0f, 19.5f, 20.25f, 21.0f, 64.0f},
                                     {glm::vec4(1, 1, 1, 0.01f), glm::vec4(1, 1, 1, 0.01f), glm::vec4(1, 1, 1, 1),
                                      glm::vec4(1, 1, 1, 0.01f), glm::vec4(1, 1, 1, 0.02f)},
                                     "floor and peak");
    scene::StructureConfig off = test::gridDda(scene::SamplerKind::Grid, "4");
    off.subMajorants = 0;
    scene::StructureConfig sub = off;
    sub.subMajorants = 8;
    auto renderer = test::makeRenderer(ctx(), std::move(m), off);
    renderer->setTransferFunction(tf);
    const uint32_t n = 1u << 19;
    TrackingKernel kernel{ctx(), n};
    auto run = [&] { return kernel.run(*renderer, {-3.0f, 2.1f, 1.9f}, scene::SamplerKind::Grid, false); };
    const std::vector<float> plain = run();
    scene::RenderSettings s;
    s.controlExtinction = scene::ControlExtinction::Minorant;
    renderer->setSettings(s);
    ASSERT_EQ(renderer->controlExtinctionOff(), "");
    const std::vector<float> minorants = renderer->downloadMinorants();
    ASSERT_EQ(minorants.size(), 4u);
    for (size_t i = 0; i < minorants.size(); ++i) {
        const accel::ValueRange& r = renderer->scene().grid->ranges[i];
        EXPECT_NEAR(minorants[i], tf.minAlpha(r.lo, r.hi) - shared::kMinorantMargin * tf.maxAlpha(r.lo, r.hi), 1e-7f);
        EXPECT_GE(minorants[i], 0.0099f) << "at least the floor";
    }
    const std::vector<float> control = run();
    renderer->setStructure(sub);
    renderer->setSubMajorantCheck(true);
    ASSERT_GT(renderer->majorantPass().subMajorants().refined, 0u);
    ASSERT_EQ(renderer->controlExtinctionOff(), "") << "kept across a structure change";
    const std::vector<float> controlSub = run();

    double tau = 0, depth = 0;
    const int steps = 1 << 20;
    for (int k = 0; k < steps; ++k) {
        const double x = 64.0 * (k + 0.5) / steps, sg = rampSigma(tf, x);
        depth += x * sg * std::exp(-tau) * (64.0 / steps);
        tau += sg * (64.0 / steps);
    }
    const double T = std::exp(-tau), entry = 3.0;
    depth /= 1.0 - T;
    auto lookupsOf = [&](const std::vector<float>& v) {
        double l = 0;
        for (uint32_t i = 0; i < n; ++i) l += v[8 * size_t(i) + 4] - v[8 * size_t(i) + 5];  // less the checks' own
        return l;
    };
    for (const auto* v : {&control, &controlSub}) {
        SCOPED_TRACE(v == &control ? "without sub-majorants" : "with sub-majorants");
        double escapes = 0, ratio = 0, ratioSq = 0, hits = 0, dSum = 0, dSq = 0, violations = 0, capped = 0;
        for (uint32_t i = 0; i < n; ++i) {
            const float* r = &(*v)[8 * size_t(i)];
            escapes += r[0];
            ratio += r[1];
            ratioSq += double(r[1]) * r[1];
            capped += r[3];
            violations += r[6];
            if (r[0] == 0.0f) {
                const double d = double(r[2]) - entry;
                hits += 1;
                dSum += d;
                dSq += d * d;
            }
        }
        EXPECT_EQ(violations, 0.0);
        EXPECT_EQ(capped, 0.0);
        const double tolEscape = 4.5 * std::sqrt(T * (1 - T) / n);
        ASSERT_LT(tolEscape, 0.02 * T) << "power: a 2% error in the transmittance is caught";
        EXPECT_NEAR(escapes / n, T, tolEscape) << "decomposition tracking";
        const double mean = ratio / n, tolRatio = 4.5 * std::sqrt(std::max(0.0, ratioSq / n - mean * mean) / n);
        ASSERT_LT(tolRatio, 0.02 * T);
        EXPECT_NEAR(mean, T, tolRatio) << "residual ratio tracking";
        EXPECT_GT(std::abs(mean - std::exp(-1.02 * tau)), tolRatio) << "2% more extinction is rejected";
        const double dMean = dSum / hits, tolDepth = 4.5 * std::sqrt(std::max(0.0, dSq / hits - dMean * dMean) / hits);
        ASSERT_LT(tolDepth, 0.02 * depth);
        EXPECT_NEAR(dMean, depth, tolDepth) << "decomposition tracking's collision depth";
    }
    auto ratioVariance = [&](const std::vector<float>& v) {
        double sum = 0, sq = 0;
        for (uint32_t i = 0; i < n; ++i) {
            sum += v[8 * size_t(i) + 1];
            sq += double(v[8 * size_t(i) + 1]) * v[8 * size_t(i) + 1];
        }
        return sq / n - (sum / n) * (sum / n);
    };
    SCOPED_TRACE(testing::Message() << "lookups: plain " << lookupsOf(plain) << ", control " << lookupsOf(control)
                                    << ", with sub-majorants " << lookupsOf(controlSub) << "; ratio variance: plain "
                                    << ratioVariance(plain) << ", control " << ratioVariance(control));
    EXPECT_LT(ratioVariance(control), 0.5 * ratioVariance(plain)) << "the control's share is exact";
    EXPECT_LT(lookupsOf(controlSub), lookupsOf(control)) << "sub-majorants cut the residual's lookups";
}
