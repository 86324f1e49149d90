#pragma once
// The histogram of a field's values under the TF editor's curve (ParaView's colour-map editor):
// `bins` equal bins over [lo, hi], counting leaf cells or their volume (a cell of level l weighs
// 8^l: the share of space), with what falls below, above or is NaN counted apart.
#include <cstdint>
#include <vector>

#include "amr/model.h"

namespace amrvk::viewer {

enum class HistogramWeight { Cells, Volume };

struct Histogram {
    float lo = 0, hi = 1;
    std::vector<double> counts;  // per bin: cells, or volume in finest-cell units
    double below = 0, above = 0, nan = 0;
    double maxCount() const;
};

// Throws for bins < 1 or an invalid range (lo < hi, both finite).
Histogram fieldHistogram(const amr::Model& model, const amr::Field& field, float lo, float hi, int bins,
                         HistogramWeight weight = HistogramWeight::Cells);

}  // namespace amrvk::viewer
