#pragma once
// Transfer function: a piecewise-linear map from a field value to a colour (rgb, in [0,1]) and
// alpha (>= 0, extinction per finest cell width before densityScale). Nodes sit at ascending
// positions in field units; two nodes may share a position (a step: the right node wins there);
// beyond the first/last node the colour is constant. GLSL twin: shaders/lib/tf.glsl.
// Colours are kept as given (display colours by default: what they mean is scene/tf_colors.h's
// TfColors); the TF a renderer gets is albedoOf's, whose colours are linear albedo.
// Presets (built-in and fitted to the data): scene/tf_presets.h; files (ParaView JSON, .xf):
// scene/tf_files.h.
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace amrvk::scene {

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
    std::vector<float> mPositions;     // field units, non-descending
    std::vector<glm::vec4> mColors;    // rgb albedo, a = alpha per finest cell width
    std::vector<float> mAlphaTree;     // see alphaTree()
    std::vector<float> mAlphaMinTree;  // see alphaMinTree()
    std::string mName;
};
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

// Throws unless the nodes form a valid transfer function (as the constructor requires); `where`
// starts every message.
void validateNodes(const std::vector<float>& positions, const std::vector<glm::vec4>& colors, const std::string& where);
// Throws unless [lo, hi] is a finite ascending range (lo <= hi); `what` starts the message.
void checkRange(float lo, float hi, const std::string& what);

}  // namespace amrvk::scene
