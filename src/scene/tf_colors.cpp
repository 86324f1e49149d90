#include "scene/tf_colors.h"

#include <algorithm>
#include <cmath>

#include "core/strings.h"

namespace amrvk::scene {

namespace {

constexpr Named<TfColors> kTfColors[] = {{"linear", TfColors::Linear}, {"srgb", TfColors::Srgb}};
constexpr int kMaxPieces = 64;
// Nodes the albedo TF may add in all (its pieces per segment shrink for a TF of many nodes, whose
// segments are too narrow for the curve between their ends to show): the work and memory stay
// bounded by the input's size (3x10^5 random colours made 19 M nodes and 850 MB).
constexpr uint64_t kMaxAddedNodes = uint64_t(1) << 20;

glm::dvec3 decode(glm::dvec3 c) { return {srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b)}; }
glm::dvec3 encode(glm::dvec3 c) { return {linearToSrgb(c.r), linearToSrgb(c.g), linearToSrgb(c.b)}; }

// The largest error, in display units, of `pieces` uniform pieces of [c0, c1] (display), each
// interpolated linearly between its decoded ends, against decode(mix(c0, c1, t)).
double pieceError(glm::dvec3 c0, glm::dvec3 c1, int pieces) {
    double worst = 0;
    for (int j = 0; j < pieces; ++j) {
        const glm::dvec3 a = glm::mix(c0, c1, double(j) / pieces), b = glm::mix(c0, c1, double(j + 1) / pieces);
        const glm::dvec3 la = decode(a), lb = decode(b);
        for (double t : {0.25, 0.5, 0.75}) {
            const glm::dvec3 error = glm::abs(encode(glm::mix(la, lb, t)) - glm::mix(a, b, t));
            worst = std::max({worst, error.r, error.g, error.b});
        }
    }
    return worst;
}

// The fewest uniform pieces within kTfColorTolerance (at most maxPieces), by bisection (the
// error falls with the count): about 2 kMaxPieces piece evaluations at most per segment, where
// counting up from 1 took O(pieces^2) (a TF of 3x10^5 random colours took 5-10 s).
int piecesFor(glm::dvec3 c0, glm::dvec3 c1, int maxPieces) {
    if (maxPieces <= 1 || pieceError(c0, c1, 1) <= kTfColorTolerance) return 1;
    int lo = 1, hi = maxPieces;  // err(lo) > tolerance; hi is the answer unless a smaller count is
    while (hi - lo > 1) {
        const int mid = (lo + hi) / 2;
        if (pieceError(c0, c1, mid) <= kTfColorTolerance)
            hi = mid;
        else
            lo = mid;
    }
    return hi;
}

}  // namespace

TfColors parseTfColors(std::string_view text, const char* option) { return parseNamed(kTfColors, text, option); }
const char* tfColorsName(TfColors colors) { return nameOf(kTfColors, colors); }

double srgbToLinear(double display) {
    const double c = std::clamp(display, 0.0, 1.0);
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

double linearToSrgb(double linear) {
    const double c = std::clamp(linear, 0.0, 1.0);
    return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

TransferFunction albedoOf(const TransferFunction& tf, TfColors colors) {
    if (colors == TfColors::Linear) return tf;
    const std::vector<float>& x = tf.positions();
    const std::vector<glm::vec4>& c = tf.colors();
    std::vector<float> positions;
    std::vector<glm::vec4> albedo;
    auto add = [&](float p, glm::dvec3 display, double alpha) {
        positions.push_back(positions.empty() ? p : std::max(p, positions.back()));
        albedo.emplace_back(glm::vec3(decode(display)), float(alpha));
    };
    uint64_t segments = 0;
    for (size_t i = 0; i + 1 < x.size(); ++i) segments += x[i] < x[i + 1] ? 1 : 0;
    const int maxPieces =
        int(std::clamp<uint64_t>(1 + kMaxAddedNodes / std::max<uint64_t>(segments, 1), 1, kMaxPieces));
    for (size_t i = 0; i < x.size(); ++i) {
        add(x[i], glm::dvec3(c[i]), c[i].a);
        if (i + 1 == x.size() || !(x[i] < x[i + 1])) continue;
        const glm::dvec3 c0(c[i]), c1(c[i + 1]);
        const int pieces = piecesFor(c0, c1, maxPieces);
        const double x0 = x[i], width = double(x[i + 1]) - x0;
        for (int k = 1; k < pieces; ++k) {
            // The node's colour and alpha at its float position, so it lies on the TF as given.
            const float p = std::clamp(float(x0 + width * k / pieces), x[i], x[i + 1]);
            const double t = (double(p) - x0) / width;
            add(p, glm::mix(c0, c1, t), glm::mix(double(c[i].a), double(c[i + 1].a), t));
        }
    }
    return TransferFunction(positions, albedo, tf.name());
}

TransferFunction albedoOf(const TfChannels& tf, TfColors colors) { return albedoOf(tf.merged(), colors); }

}  // namespace amrvk::scene
