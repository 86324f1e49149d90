#include "scene/render_output.h"

#include <algorithm>

#include "core/error.h"

namespace amrvk::scene {

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

Image varianceImage(const std::vector<float>& rgb, int width, int height) {
    Image image(width, height);
    AMRVK_CHECK(rgb.size() == 3 * image.pixels.size(), "internal: ", rgb.size(), " variances for ", width, "x", height);
    for (size_t i = 0; i < image.pixels.size(); ++i)
        image.pixels[i] = glm::vec4(rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2], 1.0f);
    return image;
}

}  // namespace amrvk::scene
