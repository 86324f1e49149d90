// Which picture is shown while the estimate converges (scene/preview_hold.h): the preview until
// the estimate's measured noise reaches the preview's (or the no-grain level), found with few
// readbacks on a 1/sqrt(spp) noise, never earlier, and the estimate at the spp asked for.
#include "scene/preview_hold.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using amrvk::scene::kNoVisibleNoise;
using amrvk::scene::PreviewHold;
using amrvk::scene::Shown;

namespace {

// An estimate of noise c / sqrt(spp), each measurement off by a factor in [1 - jitter, 1 + jitter],
// sampled one spp at a time as a front end does.
struct Convergence {
    uint32_t switchedAt = 0;          // the spp at which the estimate was first shown (0: never)
    uint32_t measures = 0;            // readbacks taken until then
    double worstShownNoise = 0;       // the true noise of the estimate when it was first shown
    bool shownAboveMeasured = false;  // shown although its last measurement was above the threshold
};
Convergence converge(PreviewHold& h, double c, uint32_t limit, double jitter, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(1.0 - jitter, 1.0 + jitter);
    Convergence r;
    for (uint32_t spp = 1; spp <= 1u << 20; ++spp) {
        if (h.wantsMeasure(spp)) {
            h.estimateMeasured(spp, c / std::sqrt(double(spp)) * u(rng));
            ++r.measures;
        }
        if (h.shown(spp, limit) == Shown::Estimate) {
            r.switchedAt = spp;
            r.worstShownNoise = c / std::sqrt(double(spp));
            r.shownAboveMeasured = !(limit > 0 && spp >= limit) && !(*h.estimateNoise() <= h.threshold());
            return r;
        }
    }
    return r;
}

}  // namespace

TEST(PreviewHold, WithoutAPreviewTheEstimateShowsFromItsFirstSample) {
    PreviewHold h;
    EXPECT_EQ(h.shown(0, 0), Shown::Nothing);
    EXPECT_EQ(h.shown(1, 0), Shown::Estimate);
    EXPECT_FALSE(h.wantsMeasure(2)) << "nothing to compare with: no readback";
}

TEST(PreviewHold, ThePreviewStaysUntilTheEstimateIsAsCleanFoundInFewReadbacks) {
    // A haze: 1.2 relative error per sample; a preview of noise 0.08 (above the no-grain level).
    const double c = 1.2, previewNoise = 0.08;
    const double crossing = (c / previewNoise) * (c / previewNoise);  // 225 spp
    for (uint32_t seed = 1; seed <= 20; ++seed) {
        PreviewHold h;
        h.previewReady(previewNoise);
        EXPECT_EQ(h.shown(1, 0), Shown::Preview);
        EXPECT_EQ(h.threshold(), previewNoise);
        const Convergence r = converge(h, c, 0, 0.1, seed);
        ASSERT_GT(r.switchedAt, 0u);
        EXPECT_FALSE(r.shownAboveMeasured);
        // Not before the estimate is about as clean (10% measurement jitter), and at most one
        // doubling late.
        EXPECT_GE(double(r.switchedAt), crossing / 1.1 / 1.1) << "seed " << seed;
        EXPECT_LE(double(r.switchedAt), 2.0 * crossing * 1.1 * 1.1) << "seed " << seed;
        // A readback every sample would be 224; doublings from 2 to 225 alone are 8.
        EXPECT_LE(r.measures, 12u) << "seed " << seed;
    }
}

TEST(PreviewHold, ACleanerPreviewThanTheNoGrainLevelWaitsOnlyForThatLevel) {
    PreviewHold h;
    h.previewReady(0.004);  // dvr of a smooth field: 0.004 would take the estimate 90000 spp
    EXPECT_EQ(h.threshold(), kNoVisibleNoise);
    const Convergence r = converge(h, 1.0, 0, 0.0, 1);
    EXPECT_GE(r.switchedAt, 400u);  // (1 / 0.05)^2
    EXPECT_LE(r.switchedAt, 800u);
}

TEST(PreviewHold, TheSppAskedForShowsTheEstimateAndAShownEstimateStays) {
    PreviewHold h;
    h.previewReady(0.02);
    const Convergence r = converge(h, 3.0, 16, 0.0, 1);
    EXPECT_EQ(r.switchedAt, 16u) << "the user's spp: the picture they asked for";
    // Replaced once: a later, noisier measurement (noise estimates scatter) does not bring the
    // preview back.
    PreviewHold g;
    g.previewReady(0.1);
    g.estimateMeasured(4, 0.09);
    EXPECT_EQ(g.shown(4, 0), Shown::Estimate);
    EXPECT_FALSE(g.wantsMeasure(8)) << "no readback once replaced";
    // And reset() (an edit) brings back the rule for the next picture.
    g.reset();
    EXPECT_EQ(g.shown(4, 0), Shown::Estimate) << "no preview yet for the new picture";
    g.previewReady(0.1);
    EXPECT_EQ(g.shown(4, 0), Shown::Preview);
}

TEST(PreviewHold, TheRuleRejectsAnEstimateNoisierThanThePreview) {
    // Power: an estimate measured just above the threshold is not shown; just below, it is.
    PreviewHold above, below;
    above.previewReady(0.08);
    below.previewReady(0.08);
    above.estimateMeasured(2, 0.0801);
    below.estimateMeasured(2, 0.0799);
    EXPECT_EQ(above.shown(2, 0), Shown::Preview);
    EXPECT_EQ(below.shown(2, 0), Shown::Estimate);
    EXPECT_TRUE(above.wantsMeasure(3)) << "measured again at the next sample: 0.0801 predicts 2.002 spp";
}
