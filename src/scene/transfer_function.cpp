#include "scene/transfer_function.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/strings.h"

namespace amrvk::scene {

// Throws unless the nodes form a valid transfer function; `where` starts every message.
void validateNodes(const std::vector<float>& positions, const std::vector<glm::vec4>& colors,
                   const std::string& where) {
    AMRVK_CHECK(!positions.empty(), where, ": no nodes");
    AMRVK_CHECK(positions.size() == colors.size(), where, ": ", positions.size(), " positions but ", colors.size(),
                " colours");
    for (size_t i = 0; i < positions.size(); ++i) {
        AMRVK_CHECK(std::isfinite(positions[i]), where, ": node ", i, " position is not finite (", positions[i], ")");
        AMRVK_CHECK(i == 0 || positions[i] >= positions[i - 1], where, ": positions not ascending at node ", i, " (",
                    positions[i], " after ", positions[i - 1], ")");
        const glm::vec4& c = colors[i];
        for (int k = 0; k < 4; ++k)
            AMRVK_CHECK(std::isfinite(c[k]), where, ": node ", i, " colour ", "rgba"[k], " is not finite (", c[k], ")");
        for (int k = 0; k < 3; ++k)
            AMRVK_CHECK(c[k] >= 0.0f && c[k] <= 1.0f, where, ": node ", i, " colour ", "rgb"[k], " = ",
                        formatDouble(c[k]), " is outside [0, 1]");
        AMRVK_CHECK(c.a >= 0.0f, where, ": node ", i, " alpha ", c.a, " is negative");
    }
}

void checkRange(float lo, float hi, const std::string& what) {
    AMRVK_CHECK(std::isfinite(lo) && std::isfinite(hi) && lo <= hi, what, ": range [", lo, ", ", hi,
                "] is not a finite ascending range");
}

namespace {

// One channel group of a ParaView preset (colour or opacity): nodes at float positions with
// values in double, linear in between and constant beyond the ends.
template <typename T>
struct Channel {
    std::vector<float> positions;
    std::vector<T> values;

    // Value at x, which must not be one of the positions.
    T between(float x) const {
        if (x < positions.front()) return values.front();
        if (x > positions.back()) return values.back();
        size_t k = size_t(std::upper_bound(positions.begin(), positions.end(), x) - positions.begin());
        double p0 = positions[k - 1], p1 = positions[k];
        double t = (static_cast<double>(x) - p0) / (p1 - p0);
        T v = values[k - 1] + t * (values[k] - values[k - 1]);
        return glm::clamp(v, glm::min(values[k - 1], values[k]), glm::max(values[k - 1], values[k]));
    }
};

// Merges colour and opacity nodes into the union of their positions. Where a channel has
// several nodes at one position (a step) the merged function gets as many nodes there, first
// with first and last with last, so the step survives.
void mergeChannels(const Channel<glm::dvec3>& rgb, const Channel<double>& alpha, std::vector<float>& positions,
                   std::vector<glm::vec4>& colors) {
    size_t i = 0, j = 0;
    const size_t nc = rgb.positions.size(), na = alpha.positions.size();
    while (i < nc || j < na) {
        float x = std::min(i < nc ? rgb.positions[i] : INFINITY, j < na ? alpha.positions[j] : INFINITY);
        size_t kc = 0, ka = 0;
        while (i + kc < nc && rgb.positions[i + kc] == x) ++kc;
        while (j + ka < na && alpha.positions[j + ka] == x) ++ka;
        for (size_t k = 0; k < std::max(kc, ka); ++k) {
            glm::dvec3 c = kc ? rgb.values[i + std::min(k, kc - 1)] : rgb.between(x);
            double a = ka ? alpha.values[j + std::min(k, ka - 1)] : alpha.between(x);
            positions.push_back(x);
            colors.emplace_back(glm::vec3(c), static_cast<float>(a));
        }
        i += kc;
        j += ka;
    }
}

}  // namespace

TransferFunction TfChannels::merged() const {
    AMRVK_CHECK(!colorPositions.empty() && colorPositions.size() == colors.size() && !opacityPositions.empty() &&
                    opacityPositions.size() == alphas.size(),
                name, ": colour and opacity need at least one node each");
    const Channel<glm::dvec3> rgb{colorPositions, {colors.begin(), colors.end()}};
    const Channel<double> alpha{opacityPositions, {alphas.begin(), alphas.end()}};
    std::vector<float> positions;
    std::vector<glm::vec4> merged;
    mergeChannels(rgb, alpha, positions, merged);
    return TransferFunction(positions, merged, name);  // validates the merged nodes
}

TfChannels TfChannels::split(const TransferFunction& tf) {
    TfChannels c;
    c.name = tf.name();
    c.colorPositions = c.opacityPositions = tf.positions();
    for (const glm::vec4& v : tf.colors()) {
        c.colors.emplace_back(v);
        c.alphas.push_back(v.a);
    }
    return c;
}

namespace {
// The max tree over node alphas (TransferFunction::alphaTree), or with `min` the min tree
// (alphaMinTree): padding that neither picks.
std::vector<float> nodeAlphaTree(const std::vector<glm::vec4>& colors, bool min) {
    size_t leaves = 1;
    while (leaves < colors.size()) leaves *= 2;
    std::vector<float> tree(2 * leaves, min ? std::numeric_limits<float>::infinity() : 0.0f);
    for (size_t i = 0; i < colors.size(); ++i) tree[leaves + i] = colors[i].a;
    for (size_t k = leaves - 1; k >= 1; --k)
        tree[k] = min ? std::min(tree[2 * k], tree[2 * k + 1]) : std::max(tree[2 * k], tree[2 * k + 1]);
    return tree;
}
}  // namespace

TransferFunction::TransferFunction()
    : mPositions{0.0f},
      mColors{glm::vec4(1.0f, 1.0f, 1.0f, 0.0f)},
      mAlphaTree(nodeAlphaTree(mColors, false)),
      mAlphaMinTree(nodeAlphaTree(mColors, true)),
      mName("empty") {}

TransferFunction::TransferFunction(const std::vector<float>& positions, const std::vector<glm::vec4>& colors,
                                   std::string name)
    : mName(std::move(name)) {
    validateNodes(positions, colors, mName);
    // Keep only the first and last of nodes sharing a position: evaluate never reaches the
    // others, and maxAlpha must not count them.
    for (size_t i = 0; i < positions.size(); ++i) {
        const bool hidden =
            i > 0 && i + 1 < positions.size() && positions[i - 1] == positions[i] && positions[i] == positions[i + 1];
        if (hidden) continue;
        mPositions.push_back(positions[i]);
        mColors.push_back(colors[i]);
    }
    mAlphaTree = nodeAlphaTree(mColors, false);
    mAlphaMinTree = nodeAlphaTree(mColors, true);
}

glm::vec4 TransferFunction::evaluate(float v) const {
    const int n = static_cast<int>(mPositions.size());
    const float* pos = mPositions.data();
    if (!(v > pos[0])) return mColors[0];  // also catches NaN
    if (v >= pos[n - 1]) return mColors[size_t(n - 1)];
    int lo = 0, hi = n - 1;  // invariant: pos[lo] <= v < pos[hi]
    while (hi - lo > 1) {
        int mid = (lo + hi) >> 1;
        if (pos[mid] <= v)
            lo = mid;
        else
            hi = mid;
    }
    float span = pos[hi] - pos[lo];
    float f = span > 0.0f ? (v - pos[lo]) / span : 1.0f;
    return glm::mix(mColors[size_t(lo)], mColors[size_t(hi)], f);
}

namespace {
// `pick` (std::max or std::min) of alpha(lo), alpha(hi) and the alphas of every node with lo <=
// position <= hi (a NaN end includes every node: conservative), the nodes' from `tree`, the max or
// min tree over them (tf.glsl's tfNodesMaxAlpha and tfMinAlpha). O(log nodes).
template <typename Pick>
float foldAlpha(const TransferFunction& tf, const std::vector<float>& tree, float lo, float hi, Pick pick) {
    const std::vector<float>& pos = tf.positions();
    float m = pick(tf.evaluate(lo).a, tf.evaluate(hi).a);
    const size_t first = size_t(std::lower_bound(pos.begin(), pos.end(), lo) - pos.begin());
    const size_t last = size_t(std::upper_bound(pos.begin(), pos.end(), hi) - pos.begin());
    const size_t leaves = tree.size() / 2;
    for (size_t l = first + leaves, r = last + leaves; l < r; l >>= 1, r >>= 1) {
        if (l & 1) m = pick(m, tree[l++]);
        if (r & 1) m = pick(m, tree[--r]);
    }
    return m;
}
}  // namespace

float TransferFunction::maxAlpha(float lo, float hi) const {
    if (lo > hi) return 0.0f;
    return foldAlpha(*this, mAlphaTree, lo, hi, [](float a, float b) { return std::max(a, b); });
}

float TransferFunction::minAlpha(float lo, float hi) const {
    if (lo > hi) return std::numeric_limits<float>::infinity();
    return foldAlpha(*this, mAlphaMinTree, lo, hi, [](float a, float b) { return std::min(a, b); });
}

TransferFunction TransferFunction::rescaled(float lo, float hi) const {
    checkRange(lo, hi, mName + ": rescaling");
    const double a = mPositions.front(), b = mPositions.back();
    // A single position (a == b) goes to the middle of [lo, hi].
    std::vector<float> positions(mPositions.size(), static_cast<float>(0.5 * (static_cast<double>(lo) + hi)));
    if (b > a) {
        for (size_t i = 0; i < positions.size(); ++i) {
            const double t = (static_cast<double>(mPositions[i]) - a) / (b - a);
            const double p = static_cast<double>(lo) + t * (static_cast<double>(hi) - lo);
            positions[i] = static_cast<float>(std::clamp(p, double(lo), double(hi)));
        }
        positions.front() = lo;
        positions.back() = hi;
    }
    return TransferFunction(positions, mColors, mName);
}

}  // namespace amrvk::scene
