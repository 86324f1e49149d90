#pragma once
// An accumulated Monte Carlo estimate of an image (GPU renderer or CPU reference integrator): the
// mean, the per-pixel sums of squares, the sample count and the counters of the paths behind it.
#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <vector>

#include "core/image_io.h"
#include "shared/render_params.h"

namespace amrvk::scene {

// How the work spreads over paths (one path = one sample: camera ray, bounces, shadow rays): per
// quantity (shared::kPath*: lookups, null and real collisions, traversal steps) a histogram over
// paths (shared/render_params.h: kPathBins, 4 bins per octave, exact below 8) and the largest
// count, summed over dispatches.
using PathHistogram = std::array<uint64_t, shared::kPathBins>;
struct PathStats {
    std::array<PathHistogram, shared::kPathQuantities> bins{};
    std::array<uint64_t, shared::kPathQuantities> max{};
    const PathHistogram& lookupBins() const { return bins[shared::kPathLookups]; }
    const PathHistogram& nullBins() const { return bins[shared::kPathNulls]; }
    uint64_t maxLookups() const { return max[shared::kPathLookups]; }
    uint64_t maxNulls() const { return max[shared::kPathNulls]; }
    // Adds one dispatch's GPU block (uint[kPathStatsCount]); a quantity's paths of count 0 are the
    // lookup histogram's paths less its own (the GPU does not count them).
    void add(const std::array<uint32_t, shared::kPathStatsCount>& gpu);
    uint64_t paths() const;  // paths recorded (0 where the pass keeps no path statistics)
};
// A quantity's distribution over paths: the mean (sum / paths) and quantiles of its histogram.
struct PathDistribution {
    double mean = 0;
    uint64_t p50 = 0, p90 = 0, p99 = 0, p999 = 0, max = 0;
};
// Quantity q of `stats` whose total over all paths is `sum` (a counter); zeros without paths.
PathDistribution pathDistribution(const PathStats& stats, uint32_t q, uint64_t sum);
// The smallest and largest count of histogram bin b.
uint64_t pathBinLow(uint32_t b);
uint64_t pathBinHigh(uint32_t b);
// The q-quantile (0 < q <= 1) of a per-path histogram as the largest count of the bin holding it
// (exact below 8, within 25% above); 0 for an empty histogram.
uint64_t pathQuantile(const PathHistogram& bins, double q);

struct RenderStats {
    uint64_t paths = 0;
    double gpuSeconds = 0;  // GPU time of the path-trace dispatches
    std::array<uint64_t, shared::kCounterCount> counters{};
    PathStats path;
    uint64_t counter(uint32_t k) const { return counters[k]; }
};

struct RenderOutput {
    Image mean;                      // linear radiance per pixel (rgb), a = 1
    std::vector<glm::vec4> sumSq;    // per-pixel sum of squared samples (rgb)
    uint32_t spp = 0;
    RenderStats stats;
};

// The raw sums behind a RenderOutput, in double: what sample-parallel ranks add up (their samples
// are disjoint, so the sum of their sums is the sum of one process over all of them).
struct AccumulatedSums {
    static constexpr size_t kPerPixel = 8;  // sum r, g, b, sample count, sum of squares r, g, b, 0
    int width = 0, height = 0;
    std::vector<double> values;  // kPerPixel per pixel, pixel (x, y) at y * width + x
};
// Mean = sum / count per pixel (0 where the count is 0), rounded to float once.
RenderOutput outputFromSums(const AccumulatedSums& sums, uint32_t spp, const RenderStats& stats);

// Per-pixel variance of the mean (3 per pixel, rgb) from the sums of squares; needs spp >= 2.
std::vector<float> varianceOfMean(const RenderOutput& out);
// The noise of an image as one number: the mean, over its visible pixels, of each pixel's standard
// error over its value, rgb averaged (sqrt(mean_c var_c) / mean_c m_c). Visible: a value of at
// least 1/256 of the 99th percentile of the pixels' values (above black in a PNG of the image
// scaled to that percentile). Needs spp >= 2; 0 where no pixel is visible.
double meanRelativeError(const RenderOutput& out);
// The fewest samples per pixel a noise check trusts: below it, pixels no sample has lit yet are
// not visible and the measure says less than the image's noise (on the bundled cloud at 32x24 ms
// it read 0.027 at 4 spp and 0.036 at 8).
inline constexpr uint32_t kFirstNoiseCheckSpp = 16;
// The schedule every noise-targeted render follows (render --until-error, Python's until=): the
// samples per pixel to add next to `out` so the image stops at `target` noise or at `cap` spp
// (0: stop). Below kFirstNoiseCheckSpp that many; then double the samples.
uint32_t nextNoiseBatch(const RenderOutput& out, uint32_t cap, double target);
// Those variances (3 per pixel) as a width x height image, alpha 1: what --variance and the
// bench's reference cache write.
Image varianceImage(const std::vector<float>& rgb, int width, int height);

}  // namespace amrvk::scene
