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

struct RenderStats {
    uint64_t paths = 0;
    double gpuSeconds = 0;  // GPU time of the path-trace dispatches
    std::array<uint64_t, shared::kCounterCount> counters{};
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
// Those variances (3 per pixel) as a width x height image, alpha 1: what --variance and the
// bench's reference cache write.
Image varianceImage(const std::vector<float>& rgb, int width, int height);

}  // namespace amrvk::scene
