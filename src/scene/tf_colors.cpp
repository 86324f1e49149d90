#include "scene/tf_colors.h"

#include <algorithm>
#include <cmath>

#include "core/strings.h"

namespace amrvk::scene {

namespace {

constexpr Named<TfColors> kTfColors[] = {{"linear", TfColors::Linear}, {"srgb", TfColors::Srgb}};
constexpr int kMaxPieces = 64;

glm::dvec3 decode(glm::dvec3 c) { return {srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b)}; }
glm::dvec3 encode(glm::dvec3 c) { return {linearToSrgb(c.r), linearToSrgb(c.g), linearToSrgb(c.b)}; }

// Whether `pieces` uniform pieces of [c0, c1] (display), each interpolated linearly between its
// decoded ends, stay within kTfColorTolerance of decode(mix(c0, c1, t)) (compared in display units).
bool closeEnough(glm::dvec3 c0, glm::dvec3 c1, int pieces) {
    for (int j = 0; j < pieces; ++j) {
        const glm::dvec3 a = glm::mix(c0, c1, double(j) / pieces), b = glm::mix(c0, c1, double(j + 1) / pieces);
        const glm::dvec3 la = decode(a), lb = decode(b);
        for (double t : {0.25, 0.5, 0.75}) {
            const glm::dvec3 error = glm::abs(encode(glm::mix(la, lb, t)) - glm::mix(a, b, t));
            if (std::max({error.r, error.g, error.b}) > kTfColorTolerance) return false;
        }
    }
    return true;
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
    for (size_t i = 0; i < x.size(); ++i) {
        add(x[i], glm::dvec3(c[i]), c[i].a);
        if (i + 1 == x.size() || !(x[i] < x[i + 1])) continue;
        const glm::dvec3 c0(c[i]), c1(c[i + 1]);
        int pieces = 1;
        while (pieces < kMaxPieces && !closeEnough(c0, c1, pieces)) ++pieces;
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

}  // namespace amrvk::scene
