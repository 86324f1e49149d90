#include "viewer/logic/tf_editor.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "scene/tf_files.h"
#include "scene/tf_presets.h"

namespace amrvk::viewer {

namespace {

// Positions mapped from [first, last] onto [lo, hi] in double (all onto the middle when they
// coincide); the ends exactly on lo and hi.
std::vector<float> mapped(const std::vector<float>& p, double lo, double hi) {
    const double a = p.front(), b = p.back();
    std::vector<float> out;
    for (float x : p) out.push_back(float(b > a ? lo + (double(x) - a) / (b - a) * (hi - lo) : 0.5 * (lo + hi)));
    if (b > a) {
        out.front() = float(lo);
        out.back() = float(hi);
    }
    return out;
}

// The opacity curve of `c` mapped onto [lo, hi] with a node at each end.
void setOpacity(scene::TfChannels& out, const scene::TfChannels& c, float lo, float hi) {
    AMRVK_CHECK(!c.opacityPositions.empty() && c.opacityPositions.size() == c.alphas.size(), c.name,
                ": an opacity curve needs at least one node");
    out.opacityPositions = mapped(c.opacityPositions, lo, hi);
    out.alphas = c.alphas;
    if (out.opacityPositions.front() > lo) {  // one node: the curve spans [lo, hi] at its alpha
        out.opacityPositions.insert(out.opacityPositions.begin(), lo);
        out.alphas.insert(out.alphas.begin(), out.alphas.front());
    }
    if (out.opacityPositions.back() < hi) {
        out.opacityPositions.push_back(hi);
        out.alphas.push_back(out.alphas.back());
    }
}

void setColours(scene::TfChannels& out, const scene::TfChannels& c, float lo, float hi) {
    AMRVK_CHECK(!c.colorPositions.empty() && c.colorPositions.size() == c.colors.size(), c.name,
                ": a colour map needs at least one node");
    out.name = c.name;
    if (c.colorPositions.size() == 1) {  // one colour: across the whole range
        out.colorPositions = {lo, hi};
        out.colors = {c.colors[0], c.colors[0]};
        return;
    }
    out.colorPositions = mapped(c.colorPositions, lo, hi);
    out.colors = c.colors;
}

bool isEditable(const scene::TfChannels& c) {
    return c.opacityPositions.size() >= 2 && c.opacityPositions.size() == c.alphas.size() && !c.colorPositions.empty() &&
           c.colorPositions.size() == c.colors.size() && c.opacityPositions.front() < c.opacityPositions.back() &&
           c.colorPositions.front() == c.opacityPositions.front() && c.colorPositions.back() == c.opacityPositions.back();
}

}  // namespace

scene::TfChannels TfEditor::editable(const scene::TfChannels& tf) {
    if (isEditable(tf)) return tf;
    // Both channels on the merged nodes: the same TF, now with the same span.
    const scene::TransferFunction merged = tf.merged();
    scene::TfChannels split = scene::TfChannels::split(merged);
    split.name = tf.name;
    float lo = merged.firstPosition(), hi = merged.lastPosition();
    if (!(lo < hi)) {
        lo = merged.firstPosition() - 0.5f;
        hi = merged.firstPosition() + 0.5f;
    }
    scene::TfChannels out;
    setColours(out, split, lo, hi);
    setOpacity(out, split, lo, hi);
    return out;
}

scene::TfChannels TfEditor::preset(std::string_view name, float lo, float hi) {
    AMRVK_CHECK(std::isfinite(lo) && std::isfinite(hi) && lo < hi, "value range [", lo, ", ", hi,
                "]: needs finite lo < hi");
    const scene::TfChannels c = scene::builtInChannels(name);
    scene::TfChannels out;
    setColours(out, c, lo, hi);
    setOpacity(out, c, lo, hi);
    return out;
}

TfEditor::TfEditor(scene::TfChannels& tf) : mTf(tf) { mTf = editable(mTf); }

float TfEditor::toValue(float x) const {
    if (x <= 0.0f) return lo();
    if (x >= 1.0f) return hi();
    return float(double(lo()) + double(x) * (double(hi()) - double(lo())));
}

float TfEditor::toX(float v) const { return float((double(v) - double(lo())) / (double(hi()) - double(lo()))); }

std::vector<float> TfEditor::colorPositions() const {
    std::vector<float> out;
    for (float p : mTf.colorPositions) out.push_back(toX(p));
    return out;
}

std::vector<OpacityNode> TfEditor::opacity() const {
    std::vector<OpacityNode> out;
    for (size_t i = 0; i < mTf.alphas.size(); ++i) out.push_back({toX(mTf.opacityPositions[i]), mTf.alphas[i]});
    out.front().x = 0.0f;
    out.back().x = 1.0f;
    return out;
}

void TfEditor::setColorMap(const scene::TfChannels& c) { setColours(mTf, c, lo(), hi()); }

void TfEditor::setPreset(const scene::TfChannels& c) {
    const float a = lo(), b = hi();
    setColours(mTf, c, a, b);
    setOpacity(mTf, c, a, b);
}

size_t TfEditor::addNode(float x, float alpha) {
    AMRVK_CHECK(std::isfinite(x) && std::isfinite(alpha), "opacity node (", x, ", ", alpha, ") is not finite");
    const float v = toValue(std::clamp(x, 0.0f, 1.0f));
    auto& p = mTf.opacityPositions;
    size_t at = size_t(std::upper_bound(p.begin(), p.end(), v) - p.begin());
    at = std::clamp<size_t>(at, 1, p.size() - 1);  // between the end nodes
    p.insert(p.begin() + std::ptrdiff_t(at), v);
    mTf.alphas.insert(mTf.alphas.begin() + std::ptrdiff_t(at), std::max(alpha, 0.0f));
    return at;
}

void TfEditor::removeNode(size_t i) {
    const size_t n = mTf.alphas.size();
    AMRVK_CHECK(i < n, "opacity node ", i, " does not exist (", n, " nodes)");
    AMRVK_CHECK(i > 0 && i + 1 < n, "the end nodes of the opacity curve cannot be removed");
    mTf.opacityPositions.erase(mTf.opacityPositions.begin() + std::ptrdiff_t(i));
    mTf.alphas.erase(mTf.alphas.begin() + std::ptrdiff_t(i));
}

void TfEditor::moveNode(size_t i, float x, float alpha) {
    const size_t n = mTf.alphas.size();
    AMRVK_CHECK(i < n, "opacity node ", i, " does not exist (", n, " nodes)");
    AMRVK_CHECK(std::isfinite(x) && std::isfinite(alpha), "opacity node (", x, ", ", alpha, ") is not finite");
    auto& p = mTf.opacityPositions;
    if (i > 0 && i + 1 < n) p[i] = std::clamp(toValue(std::clamp(x, 0.0f, 1.0f)), p[i - 1], p[i + 1]);
    mTf.alphas[i] = std::max(alpha, 0.0f);
}

std::optional<size_t> TfEditor::nodeNear(float x, float alpha, float tolX, float tolA) const {
    std::optional<size_t> best;
    double bestD = INFINITY;
    const std::vector<OpacityNode> nodes = opacity();
    for (size_t i = 0; i < nodes.size(); ++i) {
        const double dx = (nodes[i].x - x) / tolX, da = (nodes[i].alpha - alpha) / tolA;
        const double d = dx * dx + da * da;
        if (d <= 1.0 && d < bestD) {
            bestD = d;
            best = i;
        }
    }
    return best;
}

void TfEditor::setRange(float newLo, float newHi) {
    AMRVK_CHECK(std::isfinite(newLo) && std::isfinite(newHi) && newLo < newHi, "value range [", newLo, ", ", newHi,
                "]: needs finite lo < hi");
    mTf.colorPositions = mapped(mTf.colorPositions, newLo, newHi);
    mTf.opacityPositions = mapped(mTf.opacityPositions, newLo, newHi);
}

std::string TfEditor::toParaViewJson(const std::string& name) const {
    scene::TfChannels c = mTf;
    c.name = name;
    return scene::paraViewPresetJson(c);
}

void TfHistory::push(const scene::TfChannels& state) {
    mStates.erase(mStates.begin() + std::ptrdiff_t(mAt) + 1, mStates.end());  // a new edit drops the redo branch
    mStates.push_back(state);
    if (mStates.size() > kMaxStates) mStates.erase(mStates.begin());
    mAt = mStates.size() - 1;
}

const scene::TfChannels& TfHistory::undo() {
    if (mAt > 0) --mAt;
    return mStates[mAt];
}

const scene::TfChannels& TfHistory::redo() {
    if (mAt + 1 < mStates.size()) ++mAt;
    return mStates[mAt];
}

}  // namespace amrvk::viewer
