#include "scene/render_output.h"

#include <algorithm>

#include "core/error.h"

namespace amrvk::scene {

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

}  // namespace amrvk::scene
