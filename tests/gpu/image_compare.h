#pragma once
// Statistical image comparison for Monte Carlo renders (correctness.md, "How render tests
// compare images"): per-tile means against a reference with a z-test whose variance comes from the
// per-pixel sums of squares, Sidak-corrected for the number of tiles and channels. On failure the
// images are written under build/test-artifacts/<test>/.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "core/image_io.h"
#include "render/renderer.h"
#include "test_data.h"

namespace amrvk::test {

// Per-sample variance estimate of pixel i (unbiased), channel c.
inline double sampleVariance(const scene::RenderOutput& o, size_t i, int c) {
    const double n = o.spp, mean = o.mean.pixels[i][c], sumSq = o.sumSq[i][c];
    return n > 1 ? std::max(0.0, (sumSq - n * mean * mean) / (n - 1)) : 0.0;
}

// Two-sided z threshold for family-wise error `alpha` over `tests` comparisons (Sidak).
inline double sidakZ(double alpha, size_t tests) {
    double perTest = 1.0 - std::pow(1.0 - alpha, 1.0 / double(tests));
    // Inverse of the two-sided normal tail by bisection on erfc.
    double lo = 0, hi = 40;
    for (int i = 0; i < 200; ++i) {
        double mid = 0.5 * (lo + hi);
        if (std::erfc(mid / std::sqrt(2.0)) > perTest) lo = mid;
        else hi = mid;
    }
    return hi;
}

// Largest relative difference between two images (RGB; values below 1e-3 compare absolutely): for
// renders of the same samples, which agree up to rounding.
inline double maxRelativeDifference(const Image& a, const Image& b) {
    double worst = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double x = a.pixels[i][c], y = b.pixels[i][c];
            worst = std::max(worst, std::abs(x - y) / std::max({std::abs(x), std::abs(y), 1e-3}));
        }
    return worst;
}

inline void writeArtifacts(const std::string& tag, const Image& a, const Image& b) {
    auto dir = scratchDir();
    writeImage(dir / (tag + "-actual.pfm"), a);
    writeImage(dir / (tag + "-reference.pfm"), b);
    Image diff(a.width, a.height);
    for (size_t i = 0; i < diff.pixels.size(); ++i)
        diff.pixels[i] = glm::vec4(glm::abs(glm::vec3(a.pixels[i]) - glm::vec3(b.pixels[i])), 1.0f);
    writeImage(dir / (tag + "-difference.pfm"), diff);
}

// Tiles (x channels) whose means differ beyond |mean_a - mean_b| <= z * sqrt(var_a + var_b) + absTol,
// z Sidak-corrected for family-wise false-failure probability `alpha`. `report` gets one line per
// differing tile.
inline int countDifferingTiles(const scene::RenderOutput& a, const scene::RenderOutput& b, int tile,
                               double alpha, double absTol,
                               const std::function<void(const std::string&)>& report = {}) {
    const int w = a.mean.width, h = a.mean.height;
    const int tx = (w + tile - 1) / tile, ty = (h + tile - 1) / tile;
    const double z = sidakZ(alpha, size_t(tx) * size_t(ty) * 3);
    int failures = 0;
    for (int by = 0; by < ty; ++by)
        for (int bx = 0; bx < tx; ++bx)
            for (int c = 0; c < 3; ++c) {
                double ma = 0, mb = 0, va = 0, vb = 0;
                int count = 0;
                for (int y = by * tile; y < std::min(h, (by + 1) * tile); ++y)
                    for (int x = bx * tile; x < std::min(w, (bx + 1) * tile); ++x) {
                        size_t i = size_t(y) * size_t(w) + size_t(x);
                        ma += a.mean.pixels[i][c];
                        mb += b.mean.pixels[i][c];
                        va += sampleVariance(a, i, c) / a.spp;
                        vb += sampleVariance(b, i, c) / b.spp;
                        ++count;
                    }
                ma /= count;
                mb /= count;
                double sd = std::sqrt((va + vb) / (double(count) * count));
                if (std::abs(ma - mb) > z * sd + absTol) {
                    ++failures;
                    if (report)
                        report("tile (" + std::to_string(bx) + ", " + std::to_string(by) + ") channel " +
                               std::to_string(c) + ": " + std::to_string(ma) + " vs " + std::to_string(mb) +
                               " (|diff| " + std::to_string(std::abs(ma - mb)) + " > " + std::to_string(z) + " x " +
                               std::to_string(sd) + ")");
                }
            }
    return failures;
}

// Compares tile means of two renders (both with variance information). alpha: family-wise
// false-failure probability. A tile passes when |mean_a - mean_b| <= z * sqrt(var_a + var_b) + absTol.
inline void expectSameImage(const scene::RenderOutput& a, const scene::RenderOutput& b, int tile,
                            const std::string& tag, double alpha = 1e-4, double absTol = 1e-6) {
    ASSERT_EQ(a.mean.width, b.mean.width);
    ASSERT_EQ(a.mean.height, b.mean.height);
    const int failures =
        countDifferingTiles(a, b, tile, alpha, absTol, [&](const std::string& m) { ADD_FAILURE() << tag << ": " << m; });
    if (failures) writeArtifacts(tag, a.mean, b.mean);
}

}  // namespace amrvk::test
