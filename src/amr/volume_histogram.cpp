#include "amr/volume_histogram.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"

namespace amrvk::amr {

namespace {
constexpr size_t kChunks = 64;  // fixed, so the sums' rounding is the same on every machine
}

int VolumeHistogram::binOf(float v) const {
    if (std::isnan(v)) return -1;
    if (!(hi > lo)) return 0;
    const double t = (double(v) - lo) / (double(hi) - lo) * kBins;
    return int(std::clamp(t, 0.0, double(kBins - 1)));
}

double VolumeHistogram::depth() const { return std::cbrt(boundsVolume); }

VolumeHistogram volumeHistogramOf(const CellArray& cells, std::span<const float> values, float lo, float hi,
                                  int minLevel, double boundsVoxels) {
    AMRVK_CHECK(cells.size() == values.size(), "internal: ", cells.size(), " cells but ", values.size(), " values");
    AMRVK_CHECK(std::isfinite(lo) && std::isfinite(hi) && lo <= hi, "internal: histogram range [", lo, ", ", hi,
                "] is not a finite ascending range");
    AMRVK_CHECK(minLevel >= 0 && minLevel <= kMaxLevel, "internal: finest level ", minLevel);
    VolumeHistogram h;
    h.lo = lo;
    h.hi = hi;
    h.boundsVolume = std::ldexp(boundsVoxels, -3 * minLevel);
    // A cell's volume in finest cells, per level: 8^(level - minLevel), exact in a double.
    double weight[kMaxLevel + 1] = {};
    for (int l = minLevel; l <= kMaxLevel; ++l) weight[l] = std::ldexp(1.0, 3 * (l - minLevel));
    using Bins = std::vector<double>;
    h.volume = parallelReduce<Bins>(
        0, cells.size(), kChunks,
        [&](size_t from, size_t to) {
            Bins b(VolumeHistogram::kBins, 0.0);
            for (size_t i = from; i < to; ++i) {
                const int bin = h.binOf(values[i]);
                if (bin < 0) continue;
                const int level = cells[i].level;
                AMRVK_CHECK(level >= minLevel, "internal: a cell of level ", level, " below the finest level ",
                            minLevel);
                b[size_t(bin)] += weight[level];
            }
            return b;
        },
        [](Bins& sum, Bins&& part) {
            for (size_t k = 0; k < sum.size(); ++k) sum[k] += part[k];
        });
    return h;
}

}  // namespace amrvk::amr
