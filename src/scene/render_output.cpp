#include "scene/render_output.h"

#include <algorithm>

#include "core/error.h"

namespace amrvk::scene {

void PathStats::add(const std::array<uint32_t, shared::kPathStatsCount>& gpu) {
    // The GPU counts a path of count 0 in the lookup histogram only: the other quantities' bin 0
    // is every path less those counted above 0.
    std::array<uint64_t, shared::kPathQuantities> counted{};
    for (uint32_t q = 0; q < shared::kPathQuantities; ++q) {
        for (uint32_t b = 0; b < shared::kPathBins; ++b) {
            const uint32_t n = gpu[shared::kPathStatsBins + q * shared::kPathBins + b];
            bins[q][b] += n;
            counted[q] += n;
        }
        max[q] = std::max<uint64_t>(max[q], gpu[shared::kPathStatsMax + q]);
    }
    for (uint32_t q = 0; q < shared::kPathQuantities; ++q)
        if (q != shared::kPathLookups && counted[q] <= counted[shared::kPathLookups])
            bins[q][0] += counted[shared::kPathLookups] - counted[q];
}

uint64_t PathStats::paths() const {
    uint64_t n = 0;
    for (uint64_t c : bins[shared::kPathLookups]) n += c;
    return n;
}

PathDistribution pathDistribution(const PathStats& stats, uint32_t q, uint64_t sum) {
    const uint64_t paths = stats.paths();
    if (paths == 0) return {};
    const PathHistogram& h = stats.bins[q];
    return {.mean = double(sum) / double(paths),
            .p50 = pathQuantile(h, 0.5),
            .p90 = pathQuantile(h, 0.9),
            .p99 = pathQuantile(h, 0.99),
            .p999 = pathQuantile(h, 0.999),
            .max = stats.max[q]};
}

uint64_t pathBinLow(uint32_t b) {
    if (b < 8) return b;
    const uint32_t e = b / 4 + 1, sub = b % 4;  // inverse of pathBin in path_trace.comp
    return uint64_t(4 + sub) << (e - 2);
}

uint64_t pathBinHigh(uint32_t b) { return b + 1 < shared::kPathBins ? pathBinLow(b + 1) - 1 : UINT32_MAX; }

uint64_t pathQuantile(const PathHistogram& bins, double q) {
    uint64_t total = 0;
    for (uint64_t c : bins) total += c;
    if (total == 0) return 0;
    // The smallest bin whose cumulative count reaches q of all paths.
    const double want = std::clamp(q, 0.0, 1.0) * double(total);
    uint64_t cumulative = 0;
    for (uint32_t b = 0; b < shared::kPathBins; ++b) {
        cumulative += bins[b];
        if (bins[b] > 0 && double(cumulative) >= want) return pathBinHigh(b);
    }
    return pathBinHigh(shared::kPathBins - 1);
}

RenderOutput outputFromSums(const AccumulatedSums& sums, uint32_t spp, const RenderStats& stats) {
    constexpr size_t k = AccumulatedSums::kPerPixel;
    AMRVK_CHECK(sums.values.size() == size_t(sums.width) * size_t(sums.height) * k,
                "internal: accumulated sums of ", sums.values.size(), " values for ", sums.width, "x", sums.height);
    RenderOutput o;
    o.spp = spp;
    o.stats = stats;
    o.mean = Image(sums.width, sums.height);
    o.sumSq.resize(o.mean.pixels.size());
    for (size_t i = 0; i < o.mean.pixels.size(); ++i) {
        const double* v = &sums.values[i * k];
        const double count = v[3] > 0 ? v[3] : 1.0;
        o.mean.pixels[i] = glm::vec4(float(v[0] / count), float(v[1] / count), float(v[2] / count), 1.0f);
        o.sumSq[i] = glm::vec4(float(v[4]), float(v[5]), float(v[6]), 0.0f);
    }
    return o;
}

std::vector<float> varianceOfMean(const RenderOutput& o) {
    AMRVK_CHECK(o.sumSq.size() == o.mean.pixels.size() && o.spp >= 2,
                "internal: variance needs sums of squares and >= 2 spp");
    std::vector<float> out(o.mean.pixels.size() * 3);
    const double n = o.spp;
    for (size_t i = 0; i < o.mean.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double m = o.mean.pixels[i][c];
            const double sampleVar = std::max(0.0, (double(o.sumSq[i][c]) - n * m * m) / (n - 1.0));
            out[3 * i + size_t(c)] = float(sampleVar / n);
        }
    return out;
}

double meanRelativeError(const RenderOutput& o) {
    const std::vector<float> var = varianceOfMean(o);
    const size_t n = o.mean.pixels.size();
    std::vector<double> value(n);
    for (size_t i = 0; i < n; ++i) value[i] = (double(o.mean.pixels[i].r) + o.mean.pixels[i].g + o.mean.pixels[i].b) / 3.0;
    if (n == 0) return 0;
    std::vector<double> sorted = value;
    const size_t k = std::min(n - 1, size_t(0.99 * double(n)));
    std::nth_element(sorted.begin(), sorted.begin() + ptrdiff_t(k), sorted.end());
    const double floor = sorted[k] / 256.0;
    double sum = 0;
    size_t visible = 0;
    for (size_t i = 0; i < n; ++i) {
        if (!(value[i] > 0 && value[i] >= floor)) continue;
        const double meanVar = (double(var[3 * i]) + var[3 * i + 1] + var[3 * i + 2]) / 3.0;
        sum += std::sqrt(meanVar) / value[i];
        ++visible;
    }
    return visible ? sum / double(visible) : 0.0;
}

uint32_t nextNoiseBatch(const RenderOutput& out, uint32_t cap, double target) {
    if (out.spp >= cap) return 0;
    if (out.spp < kFirstNoiseCheckSpp) return std::min(kFirstNoiseCheckSpp, cap) - out.spp;
    return meanRelativeError(out) > target ? std::min(out.spp, cap - out.spp) : 0;
}

Image varianceImage(const std::vector<float>& rgb, int width, int height) {
    Image image(width, height);
    AMRVK_CHECK(rgb.size() == 3 * image.pixels.size(), "internal: ", rgb.size(), " variances for ", width, "x", height);
    for (size_t i = 0; i < image.pixels.size(); ++i)
        image.pixels[i] = glm::vec4(rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2], 1.0f);
    return image;
}

}  // namespace amrvk::scene
