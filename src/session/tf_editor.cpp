#include "session/tf_editor.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace amrvk::session {

namespace {

// Positions mapped from [first, last] onto [0, 1] (all onto 0.5 when they coincide).
std::vector<float> normalised(const std::vector<float>& p) {
    const double a = p.front(), b = p.back();
    std::vector<float> out;
    for (float x : p) out.push_back(b > a ? float((double(x) - a) / (b - a)) : 0.5f);
    out.front() = b > a ? 0.0f : 0.5f;
    out.back() = b > a ? 1.0f : 0.5f;
    return out;
}

std::vector<OpacityNode> opacityOf(const scene::TfChannels& c) {
    std::vector<OpacityNode> out;
    const std::vector<float> x = normalised(c.opacityPositions);
    for (size_t i = 0; i < x.size(); ++i) out.push_back({x[i], c.alphas[i]});
    // The curve spans [0, 1] with a node at each end.
    if (out.front().x > 0.0f) out.insert(out.begin(), {0.0f, out.front().alpha});
    if (out.back().x < 1.0f) out.push_back({1.0f, out.back().alpha});
    return out;
}

}  // namespace

TfEditor::TfEditor(std::string_view preset, float lo, float hi) {
    setPreset(scene::builtInChannels(preset));
    setRange(lo, hi);
}

TfEditor::TfEditor(const scene::TransferFunction& tf) {
    setPreset(scene::TfChannels::split(tf));
    if (tf.firstPosition() < tf.lastPosition()) setRange(tf.firstPosition(), tf.lastPosition());
    else setRange(tf.firstPosition() - 0.5f, tf.firstPosition() + 0.5f);
}

void TfEditor::setColorMap(const scene::TfChannels& c) {
    AMRVK_CHECK(!c.colorPositions.empty() && c.colorPositions.size() == c.colors.size(), c.name,
                ": a colour map needs at least one node");
    mColorMap = {};
    mColorMap.name = c.name;
    mColorMap.colorPositions = normalised(c.colorPositions);
    mColorMap.colors = c.colors;
}

void TfEditor::setPreset(const scene::TfChannels& c) {
    AMRVK_CHECK(!c.opacityPositions.empty() && c.opacityPositions.size() == c.alphas.size(), c.name,
                ": an opacity curve needs at least one node");
    setColorMap(c);
    mOpacity = opacityOf(c);
}

scene::TfChannels TfEditor::channels() const {
    scene::TfChannels c = mColorMap;
    const double span = double(mHi) - double(mLo);
    auto toValue = [&](float x) { return float(double(mLo) + double(x) * span); };
    for (float& p : c.colorPositions) p = toValue(p);
    for (const OpacityNode& n : mOpacity) {
        c.opacityPositions.push_back(toValue(n.x));
        c.alphas.push_back(n.alpha);
    }
    // The ends exactly on the range (x = 1 may round past hi).
    c.colorPositions.front() = c.opacityPositions.front() = mLo;
    c.colorPositions.back() = c.opacityPositions.back() = mHi;
    return c;
}

scene::TransferFunction TfEditor::transferFunction() const { return channels().merged(); }

size_t TfEditor::addNode(float x, float alpha) {
    AMRVK_CHECK(std::isfinite(x) && std::isfinite(alpha), "opacity node (", x, ", ", alpha, ") is not finite");
    const OpacityNode n{std::clamp(x, 0.0f, 1.0f), std::max(alpha, 0.0f)};
    auto at = std::upper_bound(mOpacity.begin(), mOpacity.end(), n.x,
                               [](float v, const OpacityNode& o) { return v < o.x; });
    if (at == mOpacity.end()) --at;  // x == 1: before the end node
    if (at == mOpacity.begin()) ++at;
    const auto inserted = mOpacity.insert(at, n);
    return size_t(inserted - mOpacity.begin());
}

void TfEditor::removeNode(size_t i) {
    AMRVK_CHECK(i < mOpacity.size(), "opacity node ", i, " does not exist (", mOpacity.size(), " nodes)");
    AMRVK_CHECK(i > 0 && i + 1 < mOpacity.size(), "the end nodes of the opacity curve cannot be removed");
    mOpacity.erase(mOpacity.begin() + std::ptrdiff_t(i));
}

void TfEditor::moveNode(size_t i, float x, float alpha) {
    AMRVK_CHECK(i < mOpacity.size(), "opacity node ", i, " does not exist (", mOpacity.size(), " nodes)");
    AMRVK_CHECK(std::isfinite(x) && std::isfinite(alpha), "opacity node (", x, ", ", alpha, ") is not finite");
    OpacityNode& n = mOpacity[i];
    if (i > 0 && i + 1 < mOpacity.size()) n.x = std::clamp(x, mOpacity[i - 1].x, mOpacity[i + 1].x);
    n.alpha = std::max(alpha, 0.0f);
}

std::optional<size_t> TfEditor::nodeNear(float x, float alpha, float tolX, float tolA) const {
    std::optional<size_t> best;
    double bestD = INFINITY;
    for (size_t i = 0; i < mOpacity.size(); ++i) {
        const double dx = (mOpacity[i].x - x) / tolX, da = (mOpacity[i].alpha - alpha) / tolA;
        const double d = dx * dx + da * da;
        if (d <= 1.0 && d < bestD) {
            bestD = d;
            best = i;
        }
    }
    return best;
}

void TfEditor::setRange(float lo, float hi) {
    AMRVK_CHECK(std::isfinite(lo) && std::isfinite(hi) && lo < hi, "value range [", lo, ", ", hi,
                "]: needs finite lo < hi");
    mLo = lo;
    mHi = hi;
}

std::string TfEditor::toParaViewJson(const std::string& name) const {
    scene::TfChannels c = channels();
    c.name = name;
    return scene::paraViewPresetJson(c);
}

void TfHistory::push(const TfEditor& state) {
    mStates.erase(mStates.begin() + std::ptrdiff_t(mAt) + 1, mStates.end());  // a new edit drops the redo branch
    mStates.push_back(state);
    if (mStates.size() > kMaxStates) mStates.erase(mStates.begin());
    mAt = mStates.size() - 1;
}

const TfEditor& TfHistory::undo() {
    if (mAt > 0) --mAt;
    return mStates[mAt];
}

const TfEditor& TfHistory::redo() {
    if (mAt + 1 < mStates.size()) ++mAt;
    return mStates[mAt];
}

}  // namespace amrvk::session
