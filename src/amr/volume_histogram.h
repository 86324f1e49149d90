#pragma once
// How much of space holds each value of a field: its cells' volumes summed per value bin. Where
// the percentiles (value_percentiles.h) count cells, this weighs them by the space they fill, so
// it tells how far a ray through the data travels at each value: the layers preset
// (scene/tf_presets.h) gives each value band the opacity that makes its expected optical
// depth along a chord a fixed share, whatever the resolution or how much of space the band fills.
// Volumes are in finest cells (cells of the data's finest level present, the unit of the TF's
// alpha), as doubles: a part of a data set held apart (an MPI rank's cells) bins its own cells
// over the whole field's range, and the parts' histograms sum to the whole's.
#include <cstdint>
#include <span>
#include <vector>

#include "amr/model.h"

namespace amrvk::amr {

struct VolumeHistogram {
    static constexpr int kBins = 1024;
    float lo = 0, hi = 0;       // the bins split [lo, hi] evenly; a value outside goes to the end bin
    std::vector<double> volume;  // kBins entries: summed cell volume, finest cells^3; empty = not made
    double boundsVolume = 0;     // the data's bounding box, finest cells^3 (the space the volumes share)

    bool empty() const { return volume.empty(); }
    // The bin of a value (NaN: -1).
    int binOf(float v) const;
    // The value at the centre of bin b.
    double binCentre(int b) const { return lo + (double(b) + 0.5) * (double(hi) - lo) / kBins; }
    // The typical chord through the data, finest cells: the cube root of the bounds' volume.
    double depth() const;
    bool operator==(const VolumeHistogram&) const = default;
};

// The histogram of `values` (one per cell of `cells`; NaN values are skipped) over [lo, hi] of a
// data set whose finest level is `minLevel` and whose bounding box holds boundsVolume voxels^3
// (voxel units, as ModelSummary::bounds). Parallel; throws for lo > hi, non-finite ends, a
// minLevel above a cell's level or sizes that differ.
VolumeHistogram volumeHistogramOf(const CellArray& cells, std::span<const float> values, float lo, float hi,
                                  int minLevel, double boundsVoxels);

// The typical histogram of several data sets (the outputs of a time series, one in memory at a
// time): over the union of their ranges, each bin the mean over the parts of the share of its
// bounds that the part's volume there fills (a part's bin spread evenly over the bins of the union
// range it overlaps; a part of one value puts it all in that value's bin), times the first part's
// boundsVolume (the units of the series' first frame). Each output counts once, so the layers
// preset over it gives a typical frame of the series the optical depth it gives one data set.
// Parts not made (empty) are skipped; one part is returned as it is; none: not made.
VolumeHistogram pooledVolumeHistograms(std::span<const VolumeHistogram> parts);

}  // namespace amrvk::amr
