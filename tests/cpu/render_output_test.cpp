// Per-path histogram bins and percentiles (scene/render_output.h): the bins tile the counts, 4 per
// octave above 8 (exact below), and a quantile is the largest count of the bin that holds it. The
// image's noise (meanRelativeError) against values worked out by hand.
#include "scene/render_output.h"

#include <gtest/gtest.h>

#include <bit>

namespace amrvk {
namespace {

// The shader's bin of a count (passes/path_trace.comp, pathBin), as shared/render_params.h states it.
uint32_t specBin(uint64_t n) {
    if (n < 8) return uint32_t(n);
    const int e = 63 - std::countl_zero(n);
    return std::min<uint32_t>(uint32_t(4 * (e - 1)) + uint32_t((n >> (e - 2)) & 3), shared::kPathBins - 1);
}

TEST(PathStats, BinsTileTheCountsFourPerOctave) {
    EXPECT_EQ(scene::pathBinLow(0), 0u);
    for (uint32_t b = 0; b + 1 < shared::kPathBins; ++b) {
        EXPECT_LE(scene::pathBinLow(b), scene::pathBinHigh(b)) << b;
        EXPECT_EQ(scene::pathBinHigh(b) + 1, scene::pathBinLow(b + 1)) << b;
    }
    for (uint64_t n : {0ull, 1ull, 7ull, 8ull, 9ull, 10ull, 11ull, 12ull, 15ull, 16ull, 100ull, 1000ull, 65535ull,
                       65536ull, 1000000ull, 4294967295ull}) {
        const uint32_t b = specBin(n);
        EXPECT_LE(scene::pathBinLow(b), n) << n;
        EXPECT_GE(scene::pathBinHigh(b), n) << n;
    }
    EXPECT_EQ(scene::pathBinHigh(7), 7u);  // exact below 8
    // A bin above 8 spans at most a quarter of its lower end.
    for (uint32_t b = 8; b + 1 < shared::kPathBins; ++b)
        EXPECT_LE(scene::pathBinHigh(b) - scene::pathBinLow(b) + 1, scene::pathBinLow(b) / 4) << b;
}

TEST(PathStats, QuantileIsTheUpperEndOfTheBinHoldingIt) {
    std::array<uint64_t, shared::kPathBins> bins{};
    bins[specBin(2)] = 90;     // 90 paths with 2 lookups
    bins[specBin(100)] = 9;    // 9 with about 100
    bins[specBin(5000)] = 1;   // one with about 5000
    EXPECT_EQ(scene::pathQuantile(bins, 0.5), 2u);
    EXPECT_EQ(scene::pathQuantile(bins, 0.9), 2u);
    EXPECT_EQ(scene::pathQuantile(bins, 0.95), scene::pathBinHigh(specBin(100)));
    EXPECT_EQ(scene::pathQuantile(bins, 0.995), scene::pathBinHigh(specBin(5000)));
    EXPECT_EQ(scene::pathQuantile({}, 0.5), 0u);
    scene::PathStats p;
    std::array<uint32_t, shared::kPathStatsCount> gpu{};
    const uint32_t lookupBins = shared::kPathStatsBins + shared::kPathLookups * shared::kPathBins;
    const uint32_t stepBins = shared::kPathStatsBins + shared::kPathSteps * shared::kPathBins;
    gpu[lookupBins + 3] = 5;
    gpu[shared::kPathStatsBins + shared::kPathNulls * shared::kPathBins + 0] = 5;
    gpu[stepBins + 9] = 5;
    gpu[shared::kPathStatsMax + shared::kPathLookups] = 3;
    gpu[shared::kPathStatsMax + shared::kPathSteps] = 9;
    p.add(gpu);
    gpu[shared::kPathStatsMax + shared::kPathLookups] = 2;
    p.add(gpu);
    EXPECT_EQ(p.paths(), 10u);
    EXPECT_EQ(p.maxLookups(), 3u);  // the largest over dispatches, not a sum
    EXPECT_EQ(p.max[shared::kPathSteps], 9u);
    EXPECT_EQ(p.bins[shared::kPathSteps][9], 10u);  // each quantity in its own histogram
    EXPECT_EQ(p.bins[shared::kPathReal][0], 10u);   // paths of no real collision: every path, not counted
    EXPECT_EQ(p.bins[shared::kPathSteps][0], 0u);   // every path was counted with its steps
    const scene::PathDistribution d = scene::pathDistribution(p, shared::kPathSteps, 90);
    EXPECT_DOUBLE_EQ(d.mean, 9.0);
    EXPECT_EQ(d.max, 9u);
    EXPECT_EQ(d.p50, scene::pathBinHigh(9));
}



// An image of n spp whose pixels have the given means and per-channel sample variances.
scene::RenderOutput imageOf(const std::vector<glm::vec3>& means, const std::vector<float>& sampleVar, uint32_t n) {
    scene::RenderOutput o;
    o.spp = n;
    o.mean = Image(int(means.size()), 1);
    for (size_t i = 0; i < means.size(); ++i) {
        o.mean.pixels[i] = glm::vec4(means[i], 1.0f);
        // sumSq = (n - 1) s^2 + n m^2, so that varianceOfMean gives s^2 / n.
        const glm::vec3 sq = glm::vec3(float(n - 1) * sampleVar[i]) + float(n) * means[i] * means[i];
        o.sumSq.push_back(glm::vec4(sq, 0.0f));
    }
    return o;
}

TEST(ImageNoise, MeanOfEachVisiblePixelsStandardErrorOverItsValue) {
    // Two bright pixels (values 1 and 2, relative errors 0.1 and 0.05 at n = 16), one black pixel
    // and one below 1/256 of the 99th percentile: the dark ones do not count.
    const uint32_t n = 16;
    const scene::RenderOutput o = imageOf({glm::vec3(1.0f), glm::vec3(2.0f), glm::vec3(0.0f), glm::vec3(0.005f)},
                                          {0.01f * 16, 0.01f * 16, 0.0f, 1.0f}, n);
    EXPECT_NEAR(scene::meanRelativeError(o), (0.1 + 0.05) / 2, 1e-6);
    // rgb averaged: the variances' mean under the root, the values' mean below it.
    const scene::RenderOutput c = imageOf({glm::vec3(1.0f, 2.0f, 3.0f)}, {0.64f}, 4);  // var of mean 0.16
    EXPECT_NEAR(scene::meanRelativeError(c), std::sqrt(0.16) / 2.0, 1e-6);
    // A planted error: counting the black pixels would give a different (smaller) mean.
    EXPECT_GT(scene::meanRelativeError(o), 0.15 / 4 + 1e-3);
    EXPECT_EQ(scene::meanRelativeError(imageOf({glm::vec3(0.0f)}, {0.0f}, 4)), 0.0) << "nothing visible";
}

TEST(ImageNoise, TheScheduleChecksAtSixteenThenDoublesUpToTheCap) {
    // Noise of this image: 0.1 at n = 16 (one visible pixel, standard error 0.1 of its value 1).
    const scene::RenderOutput noisy = imageOf({glm::vec3(1.0f)}, {0.16f}, 16);
    EXPECT_EQ(scene::nextNoiseBatch({}, 4096, 0.05), scene::kFirstNoiseCheckSpp) << "an empty image";
    EXPECT_EQ(scene::nextNoiseBatch({}, 8, 0.05), 8u) << "the cap below the first check";
    EXPECT_EQ(scene::nextNoiseBatch(noisy, 4096, 0.05), 16u) << "above the target: double";
    EXPECT_EQ(scene::nextNoiseBatch(noisy, 4096, 0.2), 0u) << "at or below the target: stop";
    EXPECT_EQ(scene::nextNoiseBatch(noisy, 20, 0.05), 4u) << "doubling stops at the cap";
    EXPECT_EQ(scene::nextNoiseBatch(noisy, 16, 0.05), 0u) << "at the cap";
}

}  // namespace
}  // namespace amrvk
