#include "scene/transfer_function.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>

#include "core/error.h"
#include "core/file_io.h"
#include "core/json_text.h"
#include "core/strings.h"

namespace fs = std::filesystem;

namespace amrvk::scene {

namespace {

constexpr float kGreyAlbedo = 0.8f;
const glm::vec3 kFoggyLow(0.8f, 0.85f, 0.95f), kFoggyHigh(0.95f, 0.95f, 1.0f);  // foggy's albedo, low to high

// spiky fitted to the data (makePreset over percentiles): its peaks, apex percentile and albedo.
struct SpikyPeak {
    int percentile;
    glm::vec3 albedo;
};
const SpikyPeak kSpikyPeaks[] = {{75, {0.45f, 0.65f, 1.0f}}, {90, {1.0f, 0.6f, 0.2f}}, {97, {1.0f, 0.95f, 0.75f}}};
constexpr int kSpikyHalfWidth = 1;      // percentiles from an apex to its feet
constexpr float kSpikyMinSide = 1e-4f;  // a side's shortest width, in units of the value range
// foggy fitted to the data: nodes at these percentiles, alpha kFoggyMaxAlpha (k - 50) / 50 above the median.
constexpr int kFoggyPercentiles[] = {0, 50, 60, 70, 80, 90, 95, 99, 100};
constexpr float kFoggyMaxAlpha = 0.05f;  // a quarter of the range-fixed foggy's top: haze, not a wall
// layers: kLayerCount triangular layers, apexes evenly over the range, each a quarter of the
// spacing wide on either side, albedo cool to warm (ColorBrewer's Spectral, bright end first).
constexpr int kLayerCount = 8;
const uint32_t kLayerColors[kLayerCount] = {0x5e4fa2, 0x3288bd, 0x66c2a5, 0xabdda4,
                                            0xe6f598, 0xfee08b, 0xfdae61, 0xf46d43};
// Fitted, each layer's expected optical depth along a chord through the data (so all eight add to
// about 1.2: the far side shows through), at most kLayerMaxAlpha per finest cell.
constexpr double kLayerDepth = 0.15;
constexpr float kLayerMaxAlpha = 1.0f;
// Range-fixed, alpha kLayerTopAlpha at the top layer, halving layer by layer below it.
constexpr float kLayerTopAlpha = 0.5f;
constexpr int kMaxXfNodes = 1 << 20;
constexpr uint64_t kXfHeaderBytes = 8 + 4 + 2 * 4 + 2 * 4 + 4;
constexpr uint64_t kOldXfBytes = 128 * sizeof(float);

// Throws unless the nodes form a valid transfer function; `where` starts every message.
void validateNodes(const std::vector<float>& positions, const std::vector<glm::vec4>& colors,
                   const std::string& where) {
    AMRVK_CHECK(!positions.empty(), where, ": no nodes");
    AMRVK_CHECK(positions.size() == colors.size(), where, ": ", positions.size(),
                " positions but ", colors.size(), " colours");
    for (size_t i = 0; i < positions.size(); ++i) {
        AMRVK_CHECK(std::isfinite(positions[i]), where, ": node ", i, " position is not finite (",
                    positions[i], ")");
        AMRVK_CHECK(i == 0 || positions[i] >= positions[i - 1], where,
                    ": positions not ascending at node ", i, " (", positions[i], " after ",
                    positions[i - 1], ")");
        const glm::vec4& c = colors[i];
        for (int k = 0; k < 4; ++k)
            AMRVK_CHECK(std::isfinite(c[k]), where, ": node ", i, " colour ", "rgba"[k],
                        " is not finite (", c[k], ")");
        for (int k = 0; k < 3; ++k)
            AMRVK_CHECK(c[k] >= 0.0f && c[k] <= 1.0f, where, ": node ", i, " colour ", "rgb"[k], " = ",
                        formatDouble(c[k]), " is outside [0, 1]");
        AMRVK_CHECK(c.a >= 0.0f, where, ": node ", i, " alpha ", c.a, " is negative");
    }
}

void checkRange(float lo, float hi, const std::string& what) {
    AMRVK_CHECK(std::isfinite(lo) && std::isfinite(hi) && lo <= hi, what, ": range [", lo, ", ",
                hi, "] is not a finite ascending range");
}

// Node i of n spaced uniformly over [lo, hi] (both ends exact); double arithmetic, monotone in i.
float uniformPosition(int i, int n, double lo, double hi) {
    if (n <= 1 || i == 0) return static_cast<float>(lo);
    if (i == n - 1) return static_cast<float>(hi);
    double p = lo + (hi - lo) * (static_cast<double>(i) / (n - 1));
    return static_cast<float>(std::clamp(p, lo, hi));
}

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
void mergeChannels(const Channel<glm::dvec3>& rgb, const Channel<double>& alpha,
                   std::vector<float>& positions, std::vector<glm::vec4>& colors) {
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

// The numbers of array member `key`, which must hold a positive multiple of `stride` numbers.
std::vector<double> readNumberArray(const nlohmann::json& preset, const char* key, size_t stride,
                                    const std::string& where) {
    const nlohmann::json& arr = preset.at(key);
    AMRVK_CHECK(arr.is_array(), where, ": ", key, " is not an array (it is a ", arr.type_name(), ")");
    std::vector<double> out;
    out.reserve(arr.size());
    for (size_t i = 0; i < arr.size(); ++i) {
        AMRVK_CHECK(arr[i].is_number(), where, ": ", key, " element ", i, " is a ",
                    arr[i].type_name(), ", not a number");
        out.push_back(arr[i].get<double>());
    }
    AMRVK_CHECK(!out.empty() && out.size() % stride == 0, where, ": ", key, " has ", out.size(),
                " numbers, not a positive multiple of ", stride);
    return out;
}

// Node positions of a ParaView array: finite as float and non-descending.
float presetPosition(double x, size_t node, const char* key, const std::string& where,
                     const std::vector<float>& previous) {
    float p = static_cast<float>(x);
    AMRVK_CHECK(std::isfinite(p), where, ": ", key, " node ", node, " position ", x,
                " is not a finite float");
    AMRVK_CHECK(previous.empty() || p >= previous.back(), where, ": ", key,
                " positions not ascending at node ", node, " (", x, " after ", previous.back(), ")");
    return p;
}

TfChannels channelsFromJson(const nlohmann::json& preset, const std::string& where, const std::string& name) {
    AMRVK_CHECK(preset.contains("RGBPoints"), where, ": no RGBPoints",
                preset.contains("IndexedColors") ? " (indexed colour maps are not supported)" : "");
    TfChannels out;
    out.name = name;
    std::vector<double> rgbPoints = readNumberArray(preset, "RGBPoints", 4, where);
    for (size_t i = 0; i < rgbPoints.size() / 4; ++i) {
        out.colorPositions.push_back(presetPosition(rgbPoints[4 * i], i, "RGBPoints", where, out.colorPositions));
        glm::dvec3 c(rgbPoints[4 * i + 1], rgbPoints[4 * i + 2], rgbPoints[4 * i + 3]);
        for (int k = 0; k < 3; ++k)
            AMRVK_CHECK(c[k] >= 0.0 && c[k] <= 1.0, where, ": RGBPoints node ", i, " colour ", "rgb"[k], " = ",
                        formatDouble(c[k]), " is outside [0, 1]");
        out.colors.emplace_back(c);
    }
    if (preset.contains("Points")) {
        std::vector<double> points = readNumberArray(preset, "Points", 4, where);
        for (size_t i = 0; i < points.size() / 4; ++i) {
            out.opacityPositions.push_back(presetPosition(points[4 * i], i, "Points", where, out.opacityPositions));
            double a = points[4 * i + 1];
            AMRVK_CHECK(a >= 0.0 && std::isfinite(static_cast<float>(a)), where, ": Points node ",
                        i, " opacity ", a, " is negative or not a finite float");
            out.alphas.push_back(float(a));
        }
    } else {
        out.opacityPositions = {out.colorPositions.front(), out.colorPositions.back()};
        out.alphas = {0.0f, 1.0f};
    }
    out.merged();  // validates the combination (one error naming the preset)
    return out;
}

std::string oneLine(std::string s) {
    std::replace(s.begin(), s.end(), '\n', ' ');
    return s;
}

struct PresetNodes {
    const char* name;
    std::vector<float> positions;
    std::vector<glm::vec4> colors;
};

glm::vec3 hexColor(uint32_t rgb) {
    return glm::vec3(float((rgb >> 16) & 0xff), float((rgb >> 8) & 0xff), float(rgb & 0xff)) / 255.0f;
}

// The layers over [lo, hi] (lo < hi) with alphas[k] at apex k: alpha 0 at both ends and between
// layers.
PresetNodes layerNodes(float lo, float hi, const std::vector<float>& alphas) {
    PresetNodes p{"layers", {lo}, {glm::vec4(hexColor(kLayerColors[0]), 0.0f)}};
    const double spacing = (double(hi) - lo) / kLayerCount;
    for (int k = 0; k < kLayerCount; ++k) {
        const glm::vec3 c = hexColor(kLayerColors[k]);
        const double apex = lo + (k + 0.5) * spacing;
        for (int side = -1; side <= 1; ++side) {
            // Clamped and kept ascending: a range only a few floats wide collapses layers, never reverses them.
            const float x = std::clamp(float(apex + side * 0.25 * spacing), std::max(lo, p.positions.back()), hi);
            p.positions.push_back(x);
            p.colors.emplace_back(c, side == 0 ? alphas[size_t(k)] : 0.0f);
        }
    }
    p.positions.push_back(hi);
    p.colors.emplace_back(p.colors.back());
    return p;
}

const std::vector<PresetNodes>& presetTable() {
    static const std::vector<PresetNodes> table = [] {
        std::vector<PresetNodes> t;
        // viridis at nine evenly spaced stops, alpha equal to the position
        const uint32_t viridis[] = {0x440154, 0x472d7b, 0x3b528b, 0x2c728e, 0x21908c,
                                    0x27ad81, 0x5dc863, 0xaadc32, 0xfde725};
        PresetNodes ramp{"ramp", {}, {}};
        for (int i = 0; i < 9; ++i) {
            float x = float(i) / 8.0f;
            ramp.positions.push_back(x);
            ramp.colors.emplace_back(hexColor(viridis[i]), x);
        }
        t.push_back(std::move(ramp));
        t.push_back({"grey", {0.0f, 1.0f}, {glm::vec4(glm::vec3(kGreyAlbedo), 0.0f),
                                            glm::vec4(glm::vec3(kGreyAlbedo), 1.0f)}});
        const glm::vec3 orange(1.0f, 0.6f, 0.2f);
        t.push_back({"spiky",
                     {0.0f, 0.49f, 0.5f, 0.51f, 1.0f},
                     {glm::vec4(orange, 0.0f), glm::vec4(orange, 0.0f), glm::vec4(orange, 1.0f),
                      glm::vec4(orange, 0.0f), glm::vec4(orange, 0.0f)}});
        t.push_back({"foggy", {0.0f, 1.0f}, {glm::vec4(kFoggyLow, 0.05f), glm::vec4(kFoggyHigh, 0.2f)}});
        t.push_back({"constant", {0.0f, 1.0f}, {glm::vec4(1.0f), glm::vec4(1.0f)}});
        t.push_back({"empty", {0.0f, 1.0f}, {glm::vec4(1.0f, 1.0f, 1.0f, 0.0f),
                                             glm::vec4(1.0f, 1.0f, 1.0f, 0.0f)}});
        std::vector<float> layerAlphas(kLayerCount);
        for (int k = 0; k < kLayerCount; ++k) layerAlphas[size_t(k)] = std::ldexp(kLayerTopAlpha, k - (kLayerCount - 1));
        t.push_back(layerNodes(0.0f, 1.0f, layerAlphas));
        return t;
    }();
    return table;
}

}  // namespace

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

TransferFunction::TransferFunction(const std::vector<float>& positions,
                                   const std::vector<glm::vec4>& colors, std::string name)
    : mName(std::move(name)) {
    validateNodes(positions, colors, mName);
    // Keep only the first and last of nodes sharing a position: evaluate never reaches the
    // others, and maxAlpha must not count them.
    for (size_t i = 0; i < positions.size(); ++i) {
        const bool hidden = i > 0 && i + 1 < positions.size() && positions[i - 1] == positions[i] &&
                            positions[i] == positions[i + 1];
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
        if (pos[mid] <= v) lo = mid;
        else hi = mid;
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

const std::vector<std::string>& presetNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> n;
        for (const PresetNodes& p : presetTable()) n.emplace_back(p.name);
        return n;
    }();
    return names;
}

namespace {
std::string joinedPresetNames() { return join(presetNames(), ", "); }

// The built-in preset named `name`; else an error listing the presets.
const PresetNodes& findPreset(std::string_view name) {
    for (const PresetNodes& p : presetTable())
        if (name == p.name) return p;
    throw Error(strCat("unknown transfer function preset '", name, "' (presets: ", joinedPresetNames(), ")"));
}
}  // namespace

TransferFunction makePreset(std::string_view name, float lo, float hi) {
    const PresetNodes& p = findPreset(name);
    checkRange(lo, hi, strCat("preset '", name, "'"));
    return TransferFunction(p.positions, p.colors, p.name).rescaled(lo, hi);
}

bool presetFollowsData(std::string_view name) { return name == "spiky" || name == "foggy" || name == "layers"; }

namespace {

// spiky over the percentiles p (p.lo() < p.hi()): see makePreset(name, percentiles).
TransferFunction spikyOver(const amr::Percentiles& p) {
    const float lo = p.lo(), hi = p.hi();
    const float minSide = kSpikyMinSide * (hi - lo);
    std::vector<const SpikyPeak*> peaks;  // one per distinct apex value
    for (const SpikyPeak& peak : kSpikyPeaks)
        if (peaks.empty() || p[peak.percentile] > p[peaks.back()->percentile]) peaks.push_back(&peak);
    std::vector<float> positions;
    std::vector<glm::vec4> colors;
    auto add = [&](float x, const glm::vec3& c, float a) {
        positions.push_back(x);
        colors.emplace_back(c, a);
    };
    for (size_t i = 0; i < peaks.size(); ++i) {
        const int at = peaks[i]->percentile;
        const glm::vec3& c = peaks[i]->albedo;
        const float apex = p[at];
        // Each side ends at the neighbouring percentile, or where it holds the apex value too (1% of
        // the cells or more share it) minSide away (at least one float step), so alpha 1 has room
        // for rounding; never beyond the data's range or halfway to the next apex, and never on a
        // neighbouring apex (which would then be a step down to 0 there).
        float left = p[at - kSpikyHalfWidth], right = p[at + kSpikyHalfWidth];
        if (left == apex) left = std::min(apex - minSide, std::nextafter(apex, -INFINITY));
        if (right == apex) right = std::max(apex + minSide, std::nextafter(apex, INFINITY));
        float below = lo, above = hi;
        if (i > 0) {
            const float previous = p[peaks[i - 1]->percentile];
            below = std::max(std::midpoint(previous, apex), std::nextafter(previous, INFINITY));
        }
        if (i + 1 < peaks.size()) {
            const float next = p[peaks[i + 1]->percentile];
            above = std::min(std::midpoint(apex, next), std::nextafter(next, -INFINITY));
        }
        left = std::max(left, below);
        right = std::min(right, above);
        if (left < apex || apex > lo) add(left, c, 0.0f);  // at the apex itself: a step up to 1
        add(apex, c, 1.0f);
        if (right > apex) add(right, c, 0.0f);  // else the apex is the maximum (or a float step below the next)
    }
    if (positions.front() > lo) {
        positions.insert(positions.begin(), lo);
        colors.insert(colors.begin(), glm::vec4(glm::vec3(colors.front()), 0.0f));
    }
    if (positions.back() < hi) add(hi, glm::vec3(colors.back()), 0.0f);
    return TransferFunction(positions, colors, "spiky");
}

// foggy over the percentiles p: see makePreset(name, percentiles).
TransferFunction foggyOver(const amr::Percentiles& p) {
    std::vector<float> positions;
    std::vector<glm::vec4> colors;
    for (int k : kFoggyPercentiles) {
        const float t = float(std::max(0, k - 50)) / 50.0f;
        // Of percentiles that share a value only the lowest is kept: a value many cells hold
        // (a uniform background) gets the alpha of its lowest percentile.
        if (!positions.empty() && p[k] == positions.back()) continue;
        positions.push_back(p[k]);
        colors.emplace_back(glm::mix(kFoggyLow, kFoggyHigh, t), kFoggyMaxAlpha * t);
    }
    return TransferFunction(positions, colors, "foggy");
}

// layers over the histogram h's range (lo < hi): see makePreset(name, percentiles, volumes).
TransferFunction layersOver(const amr::VolumeHistogram& h) {
    const double spacing = (double(h.hi) - h.lo) / kLayerCount;
    const double chord = h.depth();
    std::vector<float> alphas(kLayerCount);
    for (int k = 0; k < kLayerCount; ++k) {
        // The share of the bounds' volume under layer k's triangle (weight 1 at its apex).
        const double apex = h.lo + (k + 0.5) * spacing, half = 0.25 * spacing;
        double share = 0;
        for (int b = 0; b < amr::VolumeHistogram::kBins; ++b)
            share += h.volume[size_t(b)] * std::max(0.0, 1.0 - std::abs(h.binCentre(b) - apex) / half);
        share = h.boundsVolume > 0 ? share / h.boundsVolume : 0;
        const double alpha = share * chord > 0 ? kLayerDepth / (share * chord) : double(kLayerMaxAlpha);
        alphas[size_t(k)] = float(std::min(alpha, double(kLayerMaxAlpha)));
    }
    const PresetNodes nodes = layerNodes(h.lo, h.hi, alphas);
    return TransferFunction(nodes.positions, nodes.colors, "layers");
}

}  // namespace

TransferFunction makePreset(std::string_view name, const amr::Percentiles& p, const amr::VolumeHistogram& volumes) {
    findPreset(name);  // an unknown name is an error whatever the data
    AMRVK_CHECK(p.count > 0, "preset '", name, "': the field has no values to fit it to");
    checkRange(p.lo(), p.hi(), strCat("preset '", name, "'"));
    if (!presetFollowsData(name) || !(p.lo() < p.hi())) return makePreset(name, p.lo(), p.hi());
    if (name == "layers")
        return volumes.empty() || !(volumes.lo < volumes.hi) ? makePreset(name, p.lo(), p.hi()) : layersOver(volumes);
    return name == "spiky" ? spikyOver(p) : foggyOver(p);
}

namespace {

// The presets of a ParaView JSON file: one object or an array of them, each with its label (its
// "Name", else "#index").
struct PresetDocument {
    nlohmann::json doc;
    std::vector<const nlohmann::json*> presets;
    std::vector<std::string> labels;
};

PresetDocument readPresetDocument(const fs::path& path) {
    const std::string file = path.string();
    PresetDocument d;
    try {
        const std::string text = readTextFile(path);
        checkJsonDepth(text, file);
        d.doc = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        std::string msg = e.what();
        if (size_t close = msg.find("] "); msg.starts_with("[json.exception") && close != std::string::npos)
            msg = msg.substr(close + 2);
        AMRVK_CHECK(false, file, ": malformed JSON (", oneLine(msg), ")");
    }
    AMRVK_CHECK(d.doc.is_array() || d.doc.is_object(), file,
                ": expected a ParaView preset object or an array of presets, found a ", d.doc.type_name());
    if (d.doc.is_object()) {
        d.presets.push_back(&d.doc);
    } else {
        for (const nlohmann::json& p : d.doc) d.presets.push_back(&p);
    }
    AMRVK_CHECK(!d.presets.empty(), file, ": no presets (empty array)");
    for (size_t i = 0; i < d.presets.size(); ++i) {
        const nlohmann::json& p = *d.presets[i];
        d.labels.push_back(p.is_object() && p.contains("Name") && p["Name"].is_string() ? p["Name"].get<std::string>()
                                                                                       : strCat("#", i));
    }
    return d;
}

TfChannels presetChannels(const PresetDocument& d, size_t i, const fs::path& path) {
    const std::string where = strCat(path.string(), ": preset '", d.labels[i], "'");
    AMRVK_CHECK(d.presets[i]->is_object(), where, ": not a JSON object");
    return channelsFromJson(*d.presets[i], where, d.labels[i]);
}

}  // namespace

TransferFunction loadParaViewPreset(const fs::path& path, std::string_view presetName) {
    const PresetDocument d = readPresetDocument(path);
    size_t chosen = 0;
    if (!presetName.empty()) {
        chosen = d.presets.size();
        std::string available;
        for (size_t i = 0; i < d.presets.size(); ++i) {
            if (d.labels[i] == presetName && chosen == d.presets.size()) chosen = i;
            if (i < 8) available += (i ? ", " : "") + d.labels[i];
            else if (i == 8) available += ", ...";
        }
        AMRVK_CHECK(chosen < d.presets.size(), path.string(), ": no preset named '", presetName, "' (",
                    d.presets.size(), " presets: ", available, ")");
    }
    return presetChannels(d, chosen, path).merged();
}

ParaViewPresets loadParaViewPresets(const fs::path& path) {
    const PresetDocument d = readPresetDocument(path);
    ParaViewPresets out;
    for (size_t i = 0; i < d.presets.size(); ++i) {
        try {
            out.presets.push_back(presetChannels(d, i, path));
        } catch (const Error& e) {
            out.skipped.push_back(e.what());
        }
    }
    return out;
}

TfChannels parseParaViewPreset(const std::string& text, const std::string& where) {
    nlohmann::json j;
    checkJsonDepth(text, where);
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        AMRVK_CHECK(false, where, ": malformed JSON (", oneLine(e.what()), ")");
    }
    AMRVK_CHECK(j.is_object(), where, ": expected a ParaView preset object, found a ", j.type_name());
    const std::string name = j.contains("Name") && j["Name"].is_string() ? j["Name"].get<std::string>() : "session";
    return channelsFromJson(j, where, name);
}

TfChannels builtInChannels(std::string_view name) {
    const PresetNodes& p = findPreset(name);
    return TfChannels::split(TransferFunction(p.positions, p.colors, p.name));
}

std::string paraViewPresetJson(const TfChannels& c) {
    nlohmann::json rgb = nlohmann::json::array(), points = nlohmann::json::array();
    for (size_t i = 0; i < c.colorPositions.size(); ++i)
        for (float v : {c.colorPositions[i], c.colors[i].r, c.colors[i].g, c.colors[i].b}) rgb.push_back(v);
    for (size_t i = 0; i < c.opacityPositions.size(); ++i)
        for (float v : {c.opacityPositions[i], c.alphas[i], 0.5f, 0.0f}) points.push_back(v);
    const nlohmann::ordered_json p = {{"Name", c.name}, {"ColorSpace", "RGB"}, {"RGBPoints", rgb}, {"Points", points}};
    return nlohmann::ordered_json::array({p}).dump(1) + "\n";
}

TransferFunction loadXf(const fs::path& path, float dataLo, float dataHi) {
    const std::string file = path.string();
    BinaryReader in(path);
    uint64_t magic = 0;
    if (in.size() >= sizeof(magic)) in.read(&magic, sizeof(magic));
    std::vector<float> positions;
    std::vector<glm::vec4> colors;
    if (magic == kXfMagic) {
        float opacityScale = 0, absLo = 0, absHi = 0, relLo = 0, relHi = 0;
        int32_t n = 0;
        in.read(&opacityScale, 4);
        in.read(&absLo, 4);
        in.read(&absHi, 4);
        in.read(&relLo, 4);
        in.read(&relHi, 4);
        in.read(&n, 4);
        AMRVK_CHECK(n >= 1 && n <= kMaxXfNodes, file, ": node count N = ", n, " at byte 28 is outside [1, ",
                    kMaxXfNodes, "]");
        const uint64_t expected = kXfHeaderBytes + uint64_t(n) * 16;
        AMRVK_CHECK(in.size() == expected, file, ": size ", in.size(), " bytes, expected ", expected,
                    " for N = ", n, " nodes");
        AMRVK_CHECK(std::isfinite(absLo) && std::isfinite(absHi) && absLo <= absHi, file,
                    ": absDomain [", absLo, ", ", absHi, "] is not a finite ascending range");
        AMRVK_CHECK(std::isfinite(relLo) && std::isfinite(relHi) && relLo <= relHi, file,
                    ": relDomain [", relLo, ", ", relHi, "] (percent) is not a finite ascending range");
        const double scale = std::pow(1.1, static_cast<double>(opacityScale) - 100.0);
        AMRVK_CHECK(std::isfinite(opacityScale) && std::isfinite(static_cast<float>(scale)), file,
                    ": opacityScale ", opacityScale, " is out of range (alpha factor 1.1^(v-100))");
        const double width = static_cast<double>(absHi) - absLo;
        const double lo = absLo + relLo / 100.0 * width, hi = absLo + relHi / 100.0 * width;
        std::vector<float> rgba;
        in.readArray(rgba, uint64_t(n) * 4);
        for (int i = 0; i < n; ++i) {
            const float* c = &rgba[size_t(i) * 4];
            positions.push_back(uniformPosition(i, n, lo, hi));
            colors.emplace_back(c[0], c[1], c[2], static_cast<float>(c[3] * scale));
            AMRVK_CHECK(!(c[3] < 0.0f), file, ": node ", i, " alpha ", c[3], " at byte ",
                        kXfHeaderBytes + uint64_t(i) * 16 + 12, " is negative");
        }
    } else {
        AMRVK_CHECK(in.size() == kOldXfBytes, file, ": not a .xf transfer function: magic 0x", std::hex,
                    magic, " (expected 0x", kXfMagic, ")", std::dec, " and size ", in.size(),
                    " bytes (an owlExaBrick alpha table has ", kOldXfBytes, ")");
        checkRange(dataLo, dataHi, file + ": data");
        std::vector<float> alpha;
        in.seek(0);
        in.readArray(alpha, 128);
        for (int i = 0; i < 128; ++i) {
            positions.push_back(uniformPosition(i, 128, dataLo, dataHi));
            colors.emplace_back(glm::vec3(kGreyAlbedo), alpha[size_t(i)]);
        }
    }
    validateNodes(positions, colors, file);
    return TransferFunction(positions, colors, path.filename().string());
}

TransferFunction loadTransferFunction(std::string_view spec, const amr::Percentiles& data,
                                      const amr::VolumeHistogram& volumes, std::string_view presetName) {
    for (const std::string& name : presetNames())
        if (spec == name) return makePreset(spec, data, volumes);
    return loadTransferFunction(spec, data.lo(), data.hi(), presetName);
}

TransferFunction loadTransferFunction(std::string_view spec, float dataLo, float dataHi,
                                      std::string_view presetName) {
    for (const std::string& name : presetNames())
        if (spec == name) return makePreset(spec, dataLo, dataHi);
    const fs::path path(spec);
    std::error_code ec;
    AMRVK_CHECK(fs::exists(path, ec), "'", spec,
                "' is neither a transfer function preset (", joinedPresetNames(),
                ") nor an existing file");
    const std::string ext = toLower(path.extension().string());
    if (ext == ".xf") return loadXf(path, dataLo, dataHi);
    if (ext == ".json") return loadParaViewPreset(path, presetName);
    BinaryReader in(path);
    std::array<char, 64> head{};
    const uint64_t headBytes = std::min<uint64_t>(in.size(), head.size());
    in.read(head.data(), headBytes);
    uint64_t magic = 0;
    if (headBytes >= sizeof(magic)) std::memcpy(&magic, head.data(), sizeof(magic));
    if (magic == kXfMagic) return loadXf(path, dataLo, dataHi);
    for (uint64_t i = 0; i < headBytes; ++i) {
        if (std::isspace(static_cast<unsigned char>(head[i]))) continue;
        if (head[i] == '[' || head[i] == '{') return loadParaViewPreset(path, presetName);
        break;
    }
    AMRVK_CHECK(false, spec, ": unknown transfer function format (expected a .xf file or a ParaView ",
                "preset .json file)");
    return {};
}

}  // namespace amrvk::scene
