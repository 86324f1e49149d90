#pragma once
// Built-in transfer function presets: over a range the caller fixes, or fitted to the data's
// distribution (percentiles, volume histogram). The TF itself: scene/transfer_function.h.
#include <string>
#include <string_view>
#include <vector>

#include "amr/value_percentiles.h"
#include "amr/volume_histogram.h"
#include "scene/transfer_function.h"

namespace amrvk::scene {

// The grey preset's albedo (also an owlExaBrick .xf alpha table's, scene/tf_files.h).
inline constexpr float kGreyAlbedo = 0.8f;

// Names of the built-in presets: ramp, grey, spiky, foggy, constant, empty, layers (the default).
const std::vector<std::string>& presetNames();

// A built-in preset over a range the caller fixes (--tf-range, a time series' range, the viewer's
// editor, Python's preset(name, lo, hi)): defined over [0, 1] and mapped linearly onto [lo, hi],
// whatever the data:
//   ramp     viridis-like colours, alpha 0 -> 1 linearly over the range;
//   grey     constant colour 0.8, alpha 0 -> 1 linearly;
//   spiky    alpha 0 except one triangular peak of alpha 1 at the middle (half width 1% of the range);
//   foggy    alpha 0.05 -> 0.2, bright bluish colours;
//   constant alpha 1 and colour 1 everywhere (albedo 1 in either TfColors: furnace tests);
//   empty    alpha 0 everywhere;
//   layers   eight triangular layers, apexes at (k + 0.5) / 8 of the range, each a quarter of the
//            spacing wide on either side (alpha 0 in the gaps), albedo cool to warm (ColorBrewer
//            Spectral: 5e4fa2 ... f46d43); alpha 0.5 at the top layer, halving layer by layer below.
// Throws for an unknown name or a non-finite or reversed range.
TransferFunction makePreset(std::string_view name, float lo, float hi);

// Whether a preset follows the data's distribution in makePreset(name, percentiles, volumes):
// spiky, foggy, layers.
bool presetFollowsData(std::string_view name);

// A built-in preset fitted to the data (what render, view, bench, the Python module and the MPI
// renderer use when no range is given): spiky and foggy are laid over the field's percentiles by
// cell count (amr/value_percentiles.h; of the log values under --scale log), so they land where
// the data's values are; every node position is one of the percentiles, P_k below:
//   spiky    alpha 0 except three triangular peaks of alpha 1, apexes at P75, P90 and P97
//            (albedo light blue, orange, pale yellow), feet at the percentiles one below and one
//            above (each peak spans about 2% of the cells): opaque iso-surface-like shells where
//            the data has structure. Where 1% of the cells or more share an apex's value, that
//            side is 1e-4 of the range wide (at least one float step); sides never reach past the
//            range or halfway to the next apex; apexes of equal value are one peak.
//   foggy    alpha 0 up to the median, then 0.05 (k - 50) / 50 at P_k for k = 60, 70, 80, 90, 95,
//            99, 100 (linear in the value in between): haze that thickens with the value's rank,
//            none over the lower half of the cells (on AMR data, the coarse background); albedo
//            bluish to white. Of percentiles sharing a value only the lowest is kept.
//   layers   the range-fixed layers over the histogram's range (the field's), each layer's alpha
//            sized by the space its values fill (`volumes`, amr/volume_histogram.h): the share s_k
//            of the bounds' volume under layer k's triangle (1 at its apex), over a chord of
//            length D (the cube root of the bounds' volume, finest cells), gets alpha
//            min(1, 0.15 / (s_k D)): each layer's expected optical depth along a chord is 0.15,
//            about 1.2 for all eight, so the picture is semi-transparent at any resolution, and
//            values that fill little space (the dense structure) are drawn nearly opaque. yt's
//            default (ten Gaussian layers over the log range) is the model. Without a histogram
//            (`volumes` empty): the range-fixed shape over [P0, P100].
//   ramp, grey, constant, empty: makePreset(name, P0, P100), i.e. over the field's range.
// A field with one value (P0 == P100) gets makePreset(name, P0, P100). Throws for an unknown name
// or no values (percentiles.count == 0).
TransferFunction makePreset(std::string_view name, const amr::Percentiles& percentiles,
                            const amr::VolumeHistogram& volumes = {});

// A built-in preset's channels over [0, 1] (makePreset(name, 0, 1)).
TfChannels builtInChannels(std::string_view name);

// presetNames() joined with ", " (for messages).
std::string joinedPresetNames();

}  // namespace amrvk::scene
