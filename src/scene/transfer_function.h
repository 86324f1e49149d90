#pragma once
// Transfer function: a piecewise-linear map from a field value to a colour (rgb, in [0,1]) and
// alpha (>= 0, extinction per finest cell width before densityScale). Nodes sit at ascending
// positions in field units; two nodes may share a position (a step: the right node wins there);
// beyond the first/last node the colour is constant. GLSL twin: shaders/lib/tf.glsl.
// Colours are kept as given (display colours by default: what they mean is scene/tf_colors.h's
// TfColors); the TF a renderer gets is albedoOf's, whose colours are linear albedo.
#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "amr/value_percentiles.h"
#include "amr/volume_histogram.h"

namespace amrvk::scene {

// Magic of the owlExaStitcher / cuteeOwl / barney `.xf` format.
inline constexpr uint64_t kXfMagic = 0x0000001235abc000ull;

class TransferFunction {
public:
    // One node at 0 with albedo 1 and alpha 0: no extinction anywhere.
    TransferFunction();
    // Validates the nodes: same count (>= 1), finite, positions non-descending, rgb in [0,1],
    // alpha >= 0. Errors name `name`. Of three or more nodes at one position only the first and
    // last are kept (evaluate never reaches the others).
    TransferFunction(const std::vector<float>& positions, const std::vector<glm::vec4>& colors,
                     std::string name = "transfer function");

    // Albedo (rgb) and alpha at field value v, in float exactly as tf.glsl's evalTf computes it
    // (same binary search, same mix). NaN gives the first colour.
    glm::vec4 evaluate(float v) const;

    // Majorant of alpha over the value range [lo, hi]: max(alpha(lo), alpha(hi), alpha of every
    // node with lo <= position <= hi); 0 for an empty range (lo > hi), the maximum of all nodes
    // for a NaN end. For a continuous TF this is the exact maximum. Unlike a strictly-inside
    // node test it also counts both sides of a step sitting exactly on an end, so it bounds the
    // left limit at hi and values that round one ulp past an end. evaluate(v).a for v in
    // [lo, hi] exceeds it at most by the float rounding of mix (a few ulps). O(log nodes).
    float maxAlpha(float lo, float hi) const;
    // Minorant of alpha over [lo, hi]: min(alpha(lo), alpha(hi), alpha of every node with lo <=
    // position <= hi), the exact minimum of the piecewise-linear alpha there; +inf for an empty
    // range, the least node alpha for a NaN end. evaluate(v).a for v in [lo, hi] may fall below it
    // by the float rounding of mix (a few ulps of the larger alpha): a control extinction built on
    // it keeps a margin (kMinorantMargin). O(log nodes).
    float minAlpha(float lo, float hi) const;

    // The same nodes with positions mapped linearly from [firstPosition, lastPosition] onto
    // [lo, hi] (the ends exactly); with all nodes at one position they move to (lo + hi) / 2.
    TransferFunction rescaled(float lo, float hi) const;

    const std::vector<float>& positions() const { return mPositions; }
    const std::vector<glm::vec4>& colors() const { return mColors; }
    // Max tree of the node alphas (what maxAlpha reads, uploaded as MajorantsGpu::tfAlphaTree):
    // 2 L floats, L the power of two >= nodeCount(); [L + i] = alpha_i (padding 0), [k] =
    // max([2k], [2k + 1]); [0] unused.
    const std::vector<float>& alphaTree() const { return mAlphaTree; }
    // The same layout as a min tree (padding +inf): what minAlpha reads (MajorantsGpu::tfAlphaMinTree).
    const std::vector<float>& alphaMinTree() const { return mAlphaMinTree; }
    size_t nodeCount() const { return mPositions.size(); }
    float firstPosition() const { return mPositions.front(); }
    float lastPosition() const { return mPositions.back(); }
    const std::string& name() const { return mName; }

private:
    std::vector<float> mPositions;    // field units, non-descending
    std::vector<glm::vec4> mColors;   // rgb albedo, a = alpha per finest cell width
    std::vector<float> mAlphaTree;    // see alphaTree()
    std::vector<float> mAlphaMinTree;  // see alphaMinTree()
    std::string mName;
};

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

// ParaView colour-map preset JSON: an array of presets or one preset object with "Name",
// "RGBPoints" [x, r, g, b, ...] and optional "Points" [x, opacity, midpoint, sharpness, ...].
// Colour and opacity nodes are merged into the union of their positions (each channel evaluated
// there, which is exact since each is linear between its own nodes). Without "Points", opacity
// rises linearly 0 -> 1 over the colour range. Midpoint and sharpness are ignored: opacity is
// always linear between its nodes. An empty presetName picks the first preset in the file.
TransferFunction loadParaViewPreset(const std::filesystem::path& path,
                                    std::string_view presetName = {});

// A TF as ParaView keeps it: a colour function and an opacity function, each linear between its
// own nodes (positions ascending, field units; rgb in [0, 1], alpha >= 0). The TF editor edits
// them apart; merged() joins them into one TransferFunction at the union of their positions
// (steps kept), validated (errors name `name`).
struct TfChannels {
    std::string name;
    std::vector<float> colorPositions;
    std::vector<glm::vec3> colors;
    std::vector<float> opacityPositions;
    std::vector<float> alphas;
    bool operator==(const TfChannels&) const = default;
    TransferFunction merged() const;
    // Both channels with the TF's own nodes.
    static TfChannels split(const TransferFunction& tf);
};

// Every preset of a ParaView JSON file that amrvk can use; the others (e.g. indexed colour maps)
// are listed in `skipped` with the reason, one line each.
struct ParaViewPresets {
    std::vector<TfChannels> presets;
    std::vector<std::string> skipped;
};
ParaViewPresets loadParaViewPresets(const std::filesystem::path& path);
// One preset object given as JSON text (a session's "transferFunction"); errors name `where`.
TfChannels parseParaViewPreset(const std::string& jsonText, const std::string& where);
// A built-in preset's channels over [0, 1] (makePreset(name, 0, 1)).
TfChannels builtInChannels(std::string_view name);
// One preset as a ParaView JSON file's text (an array of one object; opacity midpoint 0.5 and
// sharpness 0, which is linear). loadParaViewPreset reads it back to the same TF.
std::string paraViewPresetJson(const TfChannels& channels);

// `.xf` transfer function, either format:
// - magic 0x1235abc000: uint64 magic, float opacityScale, float absDomain[2], float relDomain[2]
//   (percent), int32 N, float rgba[N][4]. The N nodes are spaced uniformly over
//   [absLo + relLo/100 (absHi - absLo), absLo + relHi/100 (absHi - absLo)]: relDomain is applied
//   once (exaStitcher's headless viewer applies it twice, a bug not reproduced here). Alpha is
//   multiplied by 1.1^(opacityScale - 100) as exaStitcher/cuteeOwl do (file value 100 => 1).
// - owlExaBrick: exactly 512 bytes, float alpha[128]; albedo grey 0.8, the nodes spaced
//   uniformly over [dataLo, dataHi].
TransferFunction loadXf(const std::filesystem::path& path, float dataLo, float dataHi);

// A preset name, or a file: `.xf` (by magic or extension) or ParaView JSON (by extension or a
// leading '[' / '{'). Presets are mapped onto [dataLo, dataHi] (makePreset(name, lo, hi)); files
// keep their own positions. presetName selects a preset inside a ParaView JSON file.
TransferFunction loadTransferFunction(std::string_view spec, float dataLo, float dataHi,
                                      std::string_view presetName = {});
// The same fitted to the data: presets through makePreset(name, percentiles, volumes), files as
// above over [P0, P100] (the field's range; an owlExaBrick alpha table spans it).
TransferFunction loadTransferFunction(std::string_view spec, const amr::Percentiles& data,
                                      const amr::VolumeHistogram& volumes, std::string_view presetName = {});

}  // namespace amrvk::scene
