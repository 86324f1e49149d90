// What TF colours mean (scene/tf_colors.*, issue 35): the sRGB curves against IEC 61966-2-1's
// numbers, and albedoOf: linear keeps the TF; srgb decodes it so that the albedo encoded again is
// the colour map interpolated as given (in display space) within a quarter 8-bit step everywhere,
// alphas and steps kept.
#include "scene/tf_colors.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/error.h"
#include "test_data.h"

using namespace amrvk;
using scene::TfColors;

namespace {

// The largest display-space difference between the colour map as given (tf evaluated) and its
// albedo (albedoOf(tf, Srgb) evaluated, encoded), over `samples` values spanning the nodes.
double largestDisplayError(const scene::TransferFunction& tf, int samples) {
    const scene::TransferFunction albedo = scene::albedoOf(tf, TfColors::Srgb);
    const double lo = tf.firstPosition(), hi = tf.lastPosition();
    double worst = 0;
    for (int i = 0; i <= samples; ++i) {
        const float v = float(lo + (hi - lo) * i / samples);
        const glm::vec4 given = tf.evaluate(v), a = albedo.evaluate(v);
        for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(scene::linearToSrgb(a[k]) - given[k]));
        EXPECT_NEAR(a.a, given.a, 1e-6 * std::max(1.0f, given.a)) << "alpha at " << v;
    }
    return worst;
}

scene::TransferFunction viridisNine() {
    // ParaView's "Viridis (matplotlib)" at nine evenly spaced stops (rounded to 3 digits).
    const float rgb[9][3] = {{0.267f, 0.005f, 0.329f}, {0.282f, 0.141f, 0.458f}, {0.254f, 0.265f, 0.530f},
                             {0.207f, 0.372f, 0.553f}, {0.164f, 0.471f, 0.558f}, {0.128f, 0.567f, 0.551f},
                             {0.135f, 0.659f, 0.518f}, {0.267f, 0.749f, 0.441f}, {0.993f, 0.906f, 0.144f}};
    std::vector<float> x;
    std::vector<glm::vec4> c;
    for (int i = 0; i < 9; ++i) {
        x.push_back(float(i) / 8.0f);
        c.emplace_back(rgb[i][0], rgb[i][1], rgb[i][2], float(i) / 8.0f);
    }
    return scene::TransferFunction(x, c, "viridis 9");
}

}  // namespace

TEST(TfColors, CurvesMatchTheStandard) {
    // IEC 61966-2-1: 0.5 display is 0.21404 linear; the linear segment below 0.04045.
    EXPECT_NEAR(scene::srgbToLinear(0.5), 0.214041, 1e-6);
    EXPECT_NEAR(scene::srgbToLinear(0.2), 0.0331048, 1e-6);
    EXPECT_NEAR(scene::srgbToLinear(0.04), 0.04 / 12.92, 1e-12);
    EXPECT_EQ(scene::srgbToLinear(0.0), 0.0);
    EXPECT_EQ(scene::srgbToLinear(1.0), 1.0);
    EXPECT_EQ(scene::srgbToLinear(2.0), 1.0);  // clamped
    for (int i = 0; i <= 255; ++i)
        EXPECT_NEAR(scene::linearToSrgb(scene::srgbToLinear(i / 255.0)), i / 255.0, 1e-12) << i;
}

TEST(TfColors, NamesParseAndBadOnesNameTheOption) {
    EXPECT_EQ(scene::parseTfColors("srgb"), TfColors::Srgb);
    EXPECT_EQ(scene::parseTfColors("linear"), TfColors::Linear);
    EXPECT_STREQ(scene::tfColorsName(TfColors::Srgb), "srgb");
    const std::string e = test::errorOf([] { scene::parseTfColors("gamma"); });
    EXPECT_NE(e.find("--tf-colors 'gamma': expected linear|srgb"), std::string::npos) << e;
    EXPECT_NE(test::errorOf([] { scene::parseTfColors("SRGB", "tf_colors"); }).find("tf_colors 'SRGB'"),
              std::string::npos);
}

TEST(TfColors, LinearKeepsTheTfAsGiven) {
    const scene::TransferFunction tf = viridisNine();
    const scene::TransferFunction same = scene::albedoOf(tf, TfColors::Linear);
    EXPECT_EQ(same.positions(), tf.positions());
    EXPECT_EQ(same.colors(), tf.colors());
}

TEST(TfColors, SrgbNodesAreDecodedAndTheMapIsInterpolatedAsGiven) {
    // The colour: (0.2, 0.4, 0.6) display is (0.0331, 0.1329, 0.3185) linear.
    const scene::TransferFunction one({0.0f}, {glm::vec4(0.2f, 0.4f, 0.6f, 1.0f)});
    const glm::vec4 a = scene::albedoOf(one, TfColors::Srgb).evaluate(0.0f);
    EXPECT_NEAR(a.r, 0.0331048, 1e-6);
    EXPECT_NEAR(a.g, 0.1328683, 1e-6);
    EXPECT_NEAR(a.b, 0.3185468, 1e-6);
    EXPECT_EQ(a.a, 1.0f);
    // Black to white: halfway is display 0.5 (linear 0.214), not linear 0.5 (display 0.735).
    const scene::TransferFunction grey({0.0f, 2.0f}, {glm::vec4(0, 0, 0, 0), glm::vec4(1, 1, 1, 4)});
    const scene::TransferFunction g = scene::albedoOf(grey, TfColors::Srgb);
    EXPECT_NEAR(scene::linearToSrgb(g.evaluate(1.0f).r), 0.5, scene::kTfColorTolerance);
    EXPECT_GT(g.nodeCount(), 2u);   // extra nodes were needed
    EXPECT_LE(g.nodeCount(), 65u);  // at most 63 per segment
    EXPECT_FLOAT_EQ(g.maxAlpha(0.0f, 2.0f), 4.0f);
    EXPECT_FLOAT_EQ(g.maxAlpha(0.0f, 1.0f), grey.maxAlpha(0.0f, 1.0f));
    EXPECT_LE(largestDisplayError(grey, 4000), scene::kTfColorTolerance + 1e-6);
    // Nine viridis stops, and a colour map with a step and a steep segment.
    EXPECT_LE(largestDisplayError(viridisNine(), 4000), scene::kTfColorTolerance + 1e-6);
    const scene::TransferFunction step({0.0f, 1.0f, 1.0f, 1.001f, 3.0f},
                                       {glm::vec4(0.9f, 0.1f, 0.0f, 0.5f), glm::vec4(0.1f, 0.9f, 1.0f, 2.0f),
                                        glm::vec4(1.0f, 1.0f, 0.0f, 0.0f), glm::vec4(0.0f, 0.0f, 1.0f, 1.0f),
                                        glm::vec4(0.5f, 0.5f, 0.5f, 3.0f)});
    EXPECT_LE(largestDisplayError(step, 20000), scene::kTfColorTolerance + 1e-6);
    // The step stays a step: left and right of position 1 as given.
    const scene::TransferFunction s = scene::albedoOf(step, TfColors::Srgb);
    EXPECT_NEAR(scene::linearToSrgb(s.evaluate(std::nextafter(1.0f, 0.0f)).g), 0.9, 1e-3);
    EXPECT_NEAR(scene::linearToSrgb(s.evaluate(1.0f).g), 1.0, 1e-6);
    // A map already dense (ParaView's 256-stop presets) gets no extra nodes.
    std::vector<float> x;
    std::vector<glm::vec4> c;
    for (int i = 0; i < 256; ++i) {
        x.push_back(float(i));
        c.emplace_back(float(i) / 255.0f, 0.5f, 1.0f - float(i) / 255.0f, 1.0f);
    }
    EXPECT_EQ(scene::albedoOf(scene::TransferFunction(x, c), TfColors::Srgb).nodeCount(), 256u);
}

// A TF of 3x10^5 random colours (issue 52, point 6) made 19 M albedo nodes, 850 MB and 5-10 s:
// the extra nodes are now at most 2^20 in all, and each node of the input is kept as given.
TEST(TfColors, ManyNodesAddABoundedNumber) {
    const size_t n = 300000;
    std::vector<float> x(n);
    std::vector<glm::vec4> c(n);
    uint32_t state = 12345;
    auto next = [&state] { return float((state = state * 1664525u + 1013904223u) >> 8) / float(1 << 24); };
    for (size_t i = 0; i < n; ++i) {
        x[i] = float(i);
        c[i] = glm::vec4(next(), next(), next(), next());
    }
    const scene::TransferFunction tf(x, c);
    const scene::TransferFunction a = scene::albedoOf(tf, TfColors::Srgb);
    EXPECT_GE(a.nodeCount(), n);
    EXPECT_LE(a.nodeCount(), n + (size_t(1) << 20));
    for (size_t i : {size_t(0), n / 2, n - 1}) EXPECT_NEAR(a.evaluate(x[i]).r, scene::srgbToLinear(c[i].r), 1e-6);
}
