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

VolumeHistogram pooledVolumeHistograms(std::span<const VolumeHistogram> parts) {
    std::vector<const VolumeHistogram*> used;
    for (const VolumeHistogram& p : parts)
        if (!p.empty() && p.boundsVolume > 0) used.push_back(&p);
    if (used.size() <= 1) return used.empty() ? VolumeHistogram{} : *used.front();
    VolumeHistogram out;
    out.lo = used.front()->lo;
    out.hi = used.front()->hi;
    for (const VolumeHistogram* p : used) {
        out.lo = std::min(out.lo, p->lo);
        out.hi = std::max(out.hi, p->hi);
    }
    out.boundsVolume = used.front()->boundsVolume;
    out.volume.assign(VolumeHistogram::kBins, 0.0);
    const int kBins = VolumeHistogram::kBins;
    const double width = (double(out.hi) - out.lo) / kBins;  // of the union's bins
    for (const VolumeHistogram* p : used) {
        const double scale = out.boundsVolume / (p->boundsVolume * double(used.size()));
        const double from = (double(p->hi) - p->lo) / kBins;  // of the part's bins
        for (int b = 0; b < kBins; ++b) {
            const double v = p->volume[size_t(b)] * scale;
            if (v == 0) continue;
            const double a0 = p->lo + b * from, a1 = a0 + from;
            // The union's bins [a0, a1) overlaps, each getting its share of the overlap (shares of
            // the overlaps found, so the part's volume is kept whatever the rounding at the ends).
            auto overlap = [&](int t) {
                const double t0 = out.lo + t * width, t1 = t0 + width;
                return std::max(0.0, std::min(a1, t1) - std::max(a0, t0));
            };
            int first = 0, last = -1;
            double total = 0;
            if (from > 0 && width > 0) {
                first = std::clamp(int(std::floor((a0 - out.lo) / width)), 0, kBins - 1);
                last = std::clamp(int(std::ceil((a1 - out.lo) / width)) - 1, first, kBins - 1);
                for (int t = first; t <= last; ++t) total += overlap(t);
            }
            if (!(total > 0)) {  // one value (a part or the union of one value): its bin
                out.volume[size_t(out.binOf(float(a0)))] += v;
                continue;
            }
            for (int t = first; t <= last; ++t) out.volume[size_t(t)] += v * overlap(t) / total;
        }
    }
    return out;
}

}  // namespace amrvk::amr
