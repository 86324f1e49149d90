#include "scene/tf_presets.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/error.h"
#include "core/strings.h"

namespace amrvk::scene {

namespace {

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
        t.push_back(
            {"grey", {0.0f, 1.0f}, {glm::vec4(glm::vec3(kGreyAlbedo), 0.0f), glm::vec4(glm::vec3(kGreyAlbedo), 1.0f)}});
        const glm::vec3 orange(1.0f, 0.6f, 0.2f);
        t.push_back({"spiky",
                     {0.0f, 0.49f, 0.5f, 0.51f, 1.0f},
                     {glm::vec4(orange, 0.0f), glm::vec4(orange, 0.0f), glm::vec4(orange, 1.0f),
                      glm::vec4(orange, 0.0f), glm::vec4(orange, 0.0f)}});
        t.push_back({"foggy", {0.0f, 1.0f}, {glm::vec4(kFoggyLow, 0.05f), glm::vec4(kFoggyHigh, 0.2f)}});
        t.push_back({"constant", {0.0f, 1.0f}, {glm::vec4(1.0f), glm::vec4(1.0f)}});
        t.push_back({"empty", {0.0f, 1.0f}, {glm::vec4(1.0f, 1.0f, 1.0f, 0.0f), glm::vec4(1.0f, 1.0f, 1.0f, 0.0f)}});
        std::vector<float> layerAlphas(kLayerCount);
        for (int k = 0; k < kLayerCount; ++k)
            layerAlphas[size_t(k)] = std::ldexp(kLayerTopAlpha, k - (kLayerCount - 1));
        t.push_back(layerNodes(0.0f, 1.0f, layerAlphas));
        return t;
    }();
    return table;
}

}  // namespace

const std::vector<std::string>& presetNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> n;
        for (const PresetNodes& p : presetTable()) n.emplace_back(p.name);
        return n;
    }();
    return names;
}

std::string joinedPresetNames() { return join(presetNames(), ", "); }

namespace {
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

TfChannels builtInChannels(std::string_view name) {
    const PresetNodes& p = findPreset(name);
    return TfChannels::split(TransferFunction(p.positions, p.colors, p.name));
}

}  // namespace amrvk::scene
