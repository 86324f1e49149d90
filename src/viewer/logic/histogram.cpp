#include "viewer/logic/histogram.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace amrvk::viewer {

double Histogram::maxCount() const { return counts.empty() ? 0.0 : *std::max_element(counts.begin(), counts.end()); }

Histogram fieldHistogram(const amr::Model& model, const amr::Field& field, float lo, float hi, int bins,
                         HistogramWeight weight) {
    AMRVK_CHECK(bins >= 1 && bins <= (1 << 20), "histogram: ", bins, " bins is outside [1, 2^20]");
    AMRVK_CHECK(std::isfinite(lo) && std::isfinite(hi) && lo < hi, "histogram: range [", lo, ", ", hi,
                "] needs finite lo < hi");
    AMRVK_CHECK(field.values.size() == model.cells.size(), "histogram: field '", field.name, "' has ",
                field.values.size(), " values for ", model.cells.size(), " cells");
    Histogram h;
    h.lo = lo;
    h.hi = hi;
    h.counts.assign(size_t(bins), 0.0);
    const double scale = double(bins) / (double(hi) - double(lo));
    for (size_t i = 0; i < field.values.size(); ++i) {
        const float v = field.values[i];
        const double w = weight == HistogramWeight::Cells ? 1.0 : amr::cellVolume(model.cells[i].level);
        if (std::isnan(v)) h.nan += w;
        else if (v < lo) h.below += w;
        else if (v > hi) h.above += w;
        else h.counts[std::min(size_t(bins) - 1, size_t((double(v) - double(lo)) * scale))] += w;
    }
    return h;
}

}  // namespace amrvk::viewer
