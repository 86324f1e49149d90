// Transfer function: evaluation (nodes, between, beyond, steps), exact maxAlpha against brute
// force, presets (range-fixed, and fitted to the data's percentiles: known distributions, plateaus,
// a synthetic cloud and Enzo against the range-fixed ones), ParaView JSON and both `.xf` formats,
// and every malformed input.
#include "scene/transfer_function.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>

#include "amr/value_percentiles.h"
#include "core/error.h"
#include "core/strings.h"
#include "model_fixtures.h"
#include "scene/tf_files.h"
#include "scene/tf_presets.h"
#include "scene/volume.h"
#include "shared/render_params.h"
#include "test_data.h"

using namespace amrvk;
using scene::TransferFunction;

using namespace amrvk::test;

namespace {

void writeText(const std::filesystem::path& p, const std::string& text) {
    std::ofstream out(p, std::ios::binary);
    out << text;
}

void writeBytes(const std::filesystem::path& p, const std::vector<uint8_t>& bytes) {
    std::ofstream out(p, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

template <typename T>
void append(std::vector<uint8_t>& out, T v) {
    const size_t at = out.size();
    out.resize(at + sizeof(T));
    std::memcpy(out.data() + at, &v, sizeof(T));
}

// The 2080-byte-style `.xf` layout: magic, opacityScale, absDomain, relDomain, N, rgba[N].
std::vector<uint8_t> xfBytes(float opacityScale, float absLo, float absHi, float relLo, float relHi,
                             const std::vector<glm::vec4>& rgba, uint64_t magic = scene::kXfMagic) {
    std::vector<uint8_t> b;
    append(b, magic);
    for (float f : {opacityScale, absLo, absHi, relLo, relHi}) append(b, f);
    append(b, int32_t(rgba.size()));
    for (const glm::vec4& c : rgba)
        for (int k = 0; k < 4; ++k) append(b, c[k]);
    return b;
}

std::vector<glm::vec4> xfColors(int n) {
    std::vector<glm::vec4> c;
    for (int i = 0; i < n; ++i) {
        float t = float(i) / float(n - 1);
        c.emplace_back(t, 1.0f - t, 0.5f, t * t);
    }
    return c;
}

void expectVec4Near(glm::vec4 a, glm::vec4 b, float tol) {
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(a[k], b[k], tol) << "channel " << k;
}

// Linear interpolation of (positions, values) in double, constant beyond the ends.
double lerpNodes(const std::vector<double>& pos, const std::vector<double>& val, double x) {
    if (x <= pos.front()) return val.front();
    if (x >= pos.back()) return val.back();
    size_t k = 1;
    while (pos[k] <= x) ++k;
    double t = (x - pos[k - 1]) / (pos[k] - pos[k - 1]);
    return val[k - 1] + t * (val[k] - val[k - 1]);
}

const glm::vec4 kA(0.0f, 0.0f, 0.0f, 0.0f), kB(1.0f, 0.5f, 0.0f, 2.0f), kC(0.0f, 1.0f, 1.0f, 1.0f),
    kD(0.2f, 0.2f, 0.2f, 3.0f);

}  // namespace

TEST(TransferFunction, EvaluatesNodesBetweenAndBeyond) {
    TransferFunction tf({0.0f, 1.0f, 3.0f}, {kA, kB, kC});
    EXPECT_EQ(tf.evaluate(0.0f), kA);
    EXPECT_EQ(tf.evaluate(1.0f), kB);
    EXPECT_EQ(tf.evaluate(3.0f), kC);
    expectVec4Near(tf.evaluate(0.5f), glm::vec4(0.5f, 0.25f, 0.0f, 1.0f), 1e-7f);
    expectVec4Near(tf.evaluate(2.0f), glm::vec4(0.5f, 0.75f, 0.5f, 1.5f), 1e-7f);
    expectVec4Near(tf.evaluate(1.5f), glm::vec4(0.75f, 0.625f, 0.25f, 1.75f), 1e-7f);
    EXPECT_EQ(tf.evaluate(-1.0f), kA);
    EXPECT_EQ(tf.evaluate(-std::numeric_limits<float>::infinity()), kA);
    EXPECT_EQ(tf.evaluate(7.0f), kC);
    EXPECT_EQ(tf.evaluate(std::numeric_limits<float>::infinity()), kC);
    EXPECT_EQ(tf.evaluate(std::numeric_limits<float>::quiet_NaN()), kA);
}

TEST(TransferFunction, StepsTakeTheRightNode) {
    TransferFunction mid({0.0f, 1.0f, 1.0f, 2.0f}, {kA, kB, kC, kD});
    EXPECT_EQ(mid.evaluate(1.0f), kC);
    expectVec4Near(mid.evaluate(std::nextafter(1.0f, 0.0f)), kB, 1e-6f);
    expectVec4Near(mid.evaluate(1.5f), glm::mix(kC, kD, 0.5f), 1e-7f);

    // A step on the last node: the right (last) node from the step on.
    TransferFunction last({0.0f, 1.0f, 1.0f}, {kA, kB, kC});
    EXPECT_EQ(last.evaluate(1.0f), kC);
    EXPECT_EQ(last.evaluate(5.0f), kC);
    expectVec4Near(last.evaluate(std::nextafter(1.0f, 0.0f)), kB, 1e-6f);

    // A step on the first node: exactly there the first colour (as tf.glsl), just above the second.
    TransferFunction first({0.0f, 0.0f, 1.0f}, {kA, kB, kC});
    EXPECT_EQ(first.evaluate(0.0f), kA);
    expectVec4Near(first.evaluate(1e-30f), kB, 1e-6f);
}

TEST(TransferFunction, KeepsOnlyTheEndsOfANodeGroup) {
    // The middle node of three at one position is never evaluated, so it is dropped.
    TransferFunction tf({0.0f, 1.0f, 1.0f, 1.0f, 2.0f}, {kA, kA, kD, kA, kA});
    EXPECT_EQ(tf.positions(), (std::vector<float>{0.0f, 1.0f, 1.0f, 2.0f}));
    EXPECT_EQ(tf.maxAlpha(0.0f, 2.0f), 0.0f);
    TransferFunction firstGroup({3.0f, 3.0f, 3.0f}, {kA, kD, kB});
    EXPECT_EQ(firstGroup.colors(), (std::vector<glm::vec4>{kA, kB}));
}

TEST(TransferFunction, SingleNodeAndDefaultAreConstant) {
    TransferFunction one({2.0f}, {kB});
    for (float v : {-5.0f, 2.0f, 9.0f}) EXPECT_EQ(one.evaluate(v), kB);
    EXPECT_EQ(one.maxAlpha(-1.0f, 1.0f), 2.0f);
    TransferFunction none;
    EXPECT_EQ(none.maxAlpha(-1e30f, 1e30f), 0.0f);
    EXPECT_EQ(none.evaluate(3.0f).a, 0.0f);
}

TEST(TransferFunction, MatchesDoublePrecisionInterpolation) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<float> pos;
    std::vector<glm::vec4> col;
    float p = -3.0f;
    for (int i = 0; i < 40; ++i) {
        p += 0.01f + u(rng);
        pos.push_back(p);
        col.emplace_back(u(rng), u(rng), u(rng), 4.0f * u(rng));
    }
    TransferFunction tf(pos, col);
    std::vector<double> dpos(pos.begin(), pos.end());
    for (int k = 0; k < 4; ++k) {
        std::vector<double> dval;
        for (const glm::vec4& c : col) dval.push_back(c[k]);
        for (int s = 0; s < 2000; ++s) {
            float v = -4.0f + 30.0f * u(rng);
            EXPECT_NEAR(tf.evaluate(v)[k], lerpNodes(dpos, dval, v), 1e-5) << "v " << v;
        }
    }
}

TEST(TransferFunction, MaxAlphaCountsStepsOnTheEnds) {
    // Alpha rises to 1 just below 1 and drops to 0 at 1: the supremum over [0.5, 1] is 1.
    TransferFunction tf({0.0f, 1.0f, 1.0f, 2.0f}, {kA, glm::vec4(1.0f), kA, kA});
    EXPECT_EQ(tf.evaluate(1.0f).a, 0.0f);
    EXPECT_NEAR(tf.evaluate(std::nextafter(1.0f, 0.0f)).a, 1.0f, 1e-6f);
    EXPECT_EQ(tf.maxAlpha(0.5f, 1.0f), 1.0f);
    EXPECT_EQ(tf.maxAlpha(1.0f, 2.0f), 1.0f);
    EXPECT_EQ(tf.maxAlpha(1.5f, 2.0f), 0.0f);
    EXPECT_NEAR(tf.maxAlpha(0.25f, 0.5f), 0.5f, 1e-7f);
    EXPECT_EQ(tf.maxAlpha(0.5f, 0.25f), 0.0f);  // empty range
    EXPECT_EQ(tf.maxAlpha(0.75f, 0.75f), tf.evaluate(0.75f).a);
}

// Brute force: maxAlpha bounds evaluate at dense samples over [lo, hi], the ends, every node
// inside and its float neighbours inside; and it equals the maximum of those samples plus, for a
// node exactly on an end, its neighbour one float step outside (the other side of a step there),
// up to the error of reaching a step's limit one ulp away (slope times ulp).
TEST(TransferFunction, MaxAlphaMatchesBruteForce) {
    std::mt19937 rng(12345);
    std::uniform_int_distribution<int> nodeCount(1, 10), grid(0, 16), pick(0, 5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    int withNodes = 0;
    for (int t = 0; t < 400; ++t) {
        // Positions on a 1/4 grid over [0, 4]: repeats make steps, distinct ones are >= 0.25
        // apart, so with alpha in [0, 1] no slope exceeds 4.
        std::vector<float> pos;
        std::vector<glm::vec4> col;
        for (int i = nodeCount(rng); i > 0; --i) pos.push_back(float(grid(rng)) / 4.0f);
        std::sort(pos.begin(), pos.end());
        for (size_t i = 0; i < pos.size(); ++i)
            col.emplace_back(u(rng), u(rng), u(rng), pick(rng) == 0 ? 0.0f : u(rng));
        TransferFunction tf(pos, col);
        const float ulp = std::nextafter(4.5f, 9.0f) - 4.5f;
        const float tol = 1e-6f + 2.0f * 4.0f * ulp;
        const float bound = 1.0f + 8.0f * std::numeric_limits<float>::epsilon();

        auto endpoint = [&]() {
            switch (pick(rng)) {
                case 0: return pos[size_t(grid(rng)) % pos.size()];
                case 1: return std::nextafter(pos[size_t(grid(rng)) % pos.size()], -1.0f);
                case 2: return std::nextafter(pos[size_t(grid(rng)) % pos.size()], 9.0f);
                default: return -0.5f + 5.0f * u(rng);
            }
        };
        for (int r = 0; r < 25; ++r) {
            float lo = endpoint(), hi = endpoint();
            if (lo > hi) {
                EXPECT_EQ(tf.maxAlpha(lo, hi), 0.0f);
                std::swap(lo, hi);
            }
            const float m = tf.maxAlpha(lo, hi);
            std::vector<float> inside = {lo, hi};
            for (int s = 1; s < 256; ++s) inside.push_back(std::min(hi, lo + (hi - lo) * float(s) / 256.0f));
            bool containsNode = false;
            for (float p : pos) {
                if (p < lo || p > hi) continue;
                containsNode = true;
                for (float q : {p, std::nextafter(p, -1e9f), std::nextafter(p, 1e9f)})
                    if (q >= lo && q <= hi) inside.push_back(q);
            }
            float brute = 0.0f;
            for (float p : pos) {
                if (p == lo) brute = std::max(brute, tf.evaluate(std::nextafter(p, -1e9f)).a);
                if (p == hi) brute = std::max(brute, tf.evaluate(std::nextafter(p, 1e9f)).a);
            }
            for (float v : inside) {
                const float a = tf.evaluate(v).a;
                brute = std::max(brute, a);
                EXPECT_LE(a, m * bound) << "v " << v << " in [" << lo << ", " << hi << "]";
            }
            EXPECT_NEAR(m, brute, tol) << "[" << lo << ", " << hi << "]";
            withNodes += containsNode;
        }
    }
    EXPECT_GT(withNodes, 2000);
}

// minAlpha (the control extinction's minorant, lib/tracking.glsl) against brute force over the same
// random TFs and ranges as maxAlpha: every value in [lo, hi] has alpha >= the minorant the
// renderer makes of it (minAlpha less kMinorantMargin of maxAlpha, at least 0), and minAlpha is
// the least alpha there (both sides of a step on an end count, as for maxAlpha).
TEST(TransferFunction, MinAlphaMatchesBruteForce) {
    std::mt19937 rng(54321);
    std::uniform_int_distribution<int> nodeCount(1, 10), grid(0, 16), pick(0, 5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    int positive = 0;
    for (int t = 0; t < 400; ++t) {
        std::vector<float> pos;
        std::vector<glm::vec4> col;
        for (int i = nodeCount(rng); i > 0; --i) pos.push_back(float(grid(rng)) / 4.0f);
        std::sort(pos.begin(), pos.end());
        for (size_t i = 0; i < pos.size(); ++i) col.emplace_back(0.5f, 0.5f, 0.5f, pick(rng) == 0 ? 0.0f : u(rng));
        TransferFunction tf(pos, col);
        auto endpoint = [&]() {
            switch (pick(rng)) {
                case 0: return pos[size_t(grid(rng)) % pos.size()];
                case 1: return std::nextafter(pos[size_t(grid(rng)) % pos.size()], -1.0f);
                default: return -0.5f + 5.0f * u(rng);
            }
        };
        for (int r = 0; r < 25; ++r) {
            float lo = endpoint(), hi = endpoint();
            if (lo > hi) {
                EXPECT_EQ(tf.minAlpha(lo, hi), std::numeric_limits<float>::infinity());
                std::swap(lo, hi);
            }
            const float m = tf.minAlpha(lo, hi);
            const float minorant = std::max(0.0f, m - shared::kMinorantMargin * tf.maxAlpha(lo, hi));
            std::vector<float> inside = {lo, hi};
            for (int k = 1; k < 256; ++k) inside.push_back(std::min(hi, lo + (hi - lo) * float(k) / 256.0f));
            for (float p : pos)
                for (float q : {p, std::nextafter(p, -1e9f), std::nextafter(p, 1e9f)})
                    if (q >= lo && q <= hi) inside.push_back(q);
            float brute = std::numeric_limits<float>::infinity();
            for (float p : pos) {
                if (p == lo) brute = std::min(brute, tf.evaluate(std::nextafter(p, -1e9f)).a);
                if (p == hi) brute = std::min(brute, tf.evaluate(std::nextafter(p, 1e9f)).a);
            }
            for (float v : inside) {
                const float a = tf.evaluate(v).a;
                brute = std::min(brute, a);
                EXPECT_GE(a, minorant) << "v " << v << " in [" << lo << ", " << hi << "]";
            }
            const float ulp = std::nextafter(4.5f, 9.0f) - 4.5f;
            EXPECT_NEAR(m, brute, 1e-6f + 8.0f * ulp) << "[" << lo << ", " << hi << "]";
            positive += minorant > 0.0f;
        }
    }
    EXPECT_GT(positive, 2000) << "most ranges have a minorant above 0";
}

TEST(TransferFunction, MaxAlphaOfAMillionNodesEqualsTheLinearScan) {
    // Work bounded by the TF's meaning, not its size: maxAlpha is two binary searches and a max
    // tree (O(log nodes)); it must equal the definition's linear scan over every node in range.
    const size_t n = 1000000;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<float> pos(n);
    std::vector<glm::vec4> col(n);
    for (size_t i = 0; i < n; ++i) {
        pos[i] = float(i) * 1e-3f;  // distinct, ascending
        col[i] = glm::vec4(0.5f, 0.5f, 0.5f, u(rng) < 0.999f ? 0.5f * u(rng) : 1.0f + u(rng));
    }
    const TransferFunction tf(pos, col, "million");
    EXPECT_EQ(tf.alphaTree().size(), 2u * 1048576u);
    auto linear = [&](float lo, float hi) {
        if (lo > hi) return 0.0f;
        float m = std::max(tf.evaluate(lo).a, tf.evaluate(hi).a);
        for (size_t i = 0; i < n; ++i)
            if ((std::isnan(lo) || pos[i] >= lo) && (std::isnan(hi) || pos[i] <= hi)) m = std::max(m, col[i].a);
        return m;
    };
    std::uniform_real_distribution<float> v(-5.0f, 1005.0f);
    double sum = 0;
    for (int q = 0; q < 200000; ++q) {  // in seconds with the tree; hours with a scan per query
        float lo = v(rng), hi = v(rng);
        if (q % 7 == 0) hi = lo + 0.01f * u(rng);  // short ranges, often with no node inside
        if (q % 11 == 0) lo = pos[size_t(q) % n];  // an end exactly on a node
        sum += tf.maxAlpha(std::min(lo, hi), std::max(lo, hi));
        if (q % 1000 == 0) {
            EXPECT_EQ(tf.maxAlpha(std::min(lo, hi), std::max(lo, hi)), linear(std::min(lo, hi), std::max(lo, hi)))
                << "[" << lo << ", " << hi << "]";
        }
    }
    EXPECT_GT(sum, 0.0);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(tf.maxAlpha(nan, 10.0f), linear(nan, 10.0f)) << "a NaN end counts every node up to the other end";
    EXPECT_EQ(tf.maxAlpha(990.0f, nan), linear(990.0f, nan));
    EXPECT_EQ(tf.maxAlpha(0.0f, 1e9f), linear(0.0f, 1e9f));
}

TEST(TransferFunction, RescaledMapsTheNodeRange) {
    TransferFunction tf({-1.0f, 0.0f, 0.0f, 3.0f}, {kA, kB, kC, kD});
    TransferFunction r = tf.rescaled(10.0f, 30.0f);
    EXPECT_EQ(r.positions(), (std::vector<float>{10.0f, 15.0f, 15.0f, 30.0f}));
    EXPECT_EQ(r.colors(), tf.colors());
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-0.5f, 1.5f);
    for (int i = 0; i < 1000; ++i) {
        float t = u(rng);
        expectVec4Near(r.evaluate(10.0f + 20.0f * t), tf.evaluate(-1.0f + 4.0f * t), 2e-5f);
    }
    // Collapsed onto one position: a step from the first to the last colour.
    TransferFunction flat = tf.rescaled(5.0f, 5.0f);
    EXPECT_EQ(flat.positions(), (std::vector<float>{5.0f, 5.0f}));
    EXPECT_EQ(flat.colors(), (std::vector<glm::vec4>{kA, kD}));
    TransferFunction point = TransferFunction({2.0f, 2.0f}, {kA, kB}).rescaled(0.0f, 1.0f);
    EXPECT_EQ(point.positions(), (std::vector<float>{0.5f, 0.5f}));
    expectError([&] { tf.rescaled(1.0f, 0.0f); }, {"rescaling", "not a finite ascending range"});
    expectError([&] { tf.rescaled(0.0f, std::numeric_limits<float>::quiet_NaN()); }, {"rescaling"});
}

TEST(TransferFunction, Presets) {
    const std::vector<std::string> expected = {"ramp", "grey", "spiky", "foggy", "constant", "empty", "layers"};
    EXPECT_EQ(scene::presetNames(), expected);
    for (const std::string& name : scene::presetNames()) {
        TransferFunction tf = scene::makePreset(name, 2.0f, 6.0f);
        EXPECT_EQ(tf.firstPosition(), 2.0f) << name;
        EXPECT_EQ(tf.lastPosition(), 6.0f) << name;
    }
    TransferFunction ramp = scene::makePreset("ramp", 2.0f, 6.0f);
    EXPECT_EQ(ramp.evaluate(2.0f).a, 0.0f);
    EXPECT_EQ(ramp.evaluate(6.0f).a, 1.0f);
    EXPECT_NEAR(ramp.evaluate(4.0f).a, 0.5f, 1e-6f);
    EXPECT_NEAR(ramp.evaluate(3.0f).a, 0.25f, 1e-6f);
    EXPECT_GT(ramp.evaluate(6.0f).r, ramp.evaluate(2.0f).r);  // dark purple to yellow

    TransferFunction spiky = scene::makePreset("spiky", 2.0f, 6.0f);
    EXPECT_EQ(spiky.evaluate(4.0f).a, 1.0f);
    EXPECT_EQ(spiky.evaluate(2.0f).a, 0.0f);
    EXPECT_EQ(spiky.evaluate(3.9f).a, 0.0f);
    EXPECT_EQ(spiky.evaluate(4.1f).a, 0.0f);
    EXPECT_EQ(spiky.maxAlpha(2.0f, 6.0f), 1.0f);
    EXPECT_EQ(spiky.maxAlpha(2.0f, 3.9f), 0.0f);

    TransferFunction foggy = scene::makePreset("foggy", 2.0f, 6.0f);
    for (float v = 1.0f; v <= 7.0f; v += 0.25f) {
        EXPECT_GE(foggy.evaluate(v).a, 0.05f - 1e-7f);
        EXPECT_LE(foggy.evaluate(v).a, 0.2f + 1e-7f);
    }
    TransferFunction constant = scene::makePreset("constant", 2.0f, 6.0f);
    for (float v : {-10.0f, 2.0f, 3.3f, 6.0f, 100.0f}) EXPECT_EQ(constant.evaluate(v), glm::vec4(1.0f));
    EXPECT_EQ(scene::makePreset("empty", 2.0f, 6.0f).maxAlpha(-1e30f, 1e30f), 0.0f);
    EXPECT_EQ(scene::makePreset("grey", 0.0f, 1.0f).evaluate(0.5f), glm::vec4(0.8f, 0.8f, 0.8f, 0.5f));

    expectError([] { scene::makePreset("rainbow", 0.0f, 1.0f); },
                {"unknown transfer function preset 'rainbow'", "ramp", "spiky"});
    expectError([] { scene::makePreset("ramp", 1.0f, 0.0f); }, {"preset 'ramp'", "[1, 0]"});
}

namespace {

// The alphas of a TF's nodes.
std::vector<float> alphasOf(const TransferFunction& tf) {
    std::vector<float> a;
    for (const glm::vec4& c : tf.colors()) a.push_back(c.a);
    return a;
}

// The fraction of `values` where the TF's alpha is at least `alpha`.
double fractionAtLeast(const TransferFunction& tf, const std::vector<float>& values, float alpha) {
    size_t n = 0;
    for (float v : values) n += tf.evaluate(v).a >= alpha ? 1 : 0;
    return double(n) / double(values.size());
}

}  // namespace

TEST(TransferFunction, FittedPresetsSitAtTheDataPercentiles) {
    // A known distribution: the integers 0..100000, so P_k = 1000 k exactly.
    std::vector<float> v(100001);
    for (size_t i = 0; i < v.size(); ++i) v[i] = float(i);
    const amr::Percentiles p = amr::percentilesOf(v);
    ASSERT_EQ(p[75], 75000.0f);

    const TransferFunction spiky = scene::makePreset("spiky", p);
    EXPECT_EQ(spiky.name(), "spiky");
    EXPECT_EQ(spiky.positions(), (std::vector<float>{0, 74000, 75000, 76000, 89000, 90000, 91000, 96000, 97000, 98000,
                                                     100000}));
    EXPECT_EQ(alphasOf(spiky), (std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0}));
    EXPECT_EQ(spiky.evaluate(74500.0f).a, 0.5f);
    EXPECT_EQ(spiky.evaluate(80000.0f).a, 0.0f);
    EXPECT_EQ(spiky.maxAlpha(0.0f, 73999.0f), 0.0f);

    const TransferFunction foggy = scene::makePreset("foggy", p);
    EXPECT_EQ(foggy.positions(), (std::vector<float>{0, 50000, 60000, 70000, 80000, 90000, 95000, 99000, 100000}));
    const std::vector<float> fogAlpha = alphasOf(foggy);
    const int at[] = {0, 50, 60, 70, 80, 90, 95, 99, 100};
    for (size_t i = 0; i < fogAlpha.size(); ++i)
        EXPECT_NEAR(fogAlpha[i], 0.05f * float(std::max(0, at[i] - 50)) / 50.0f, 1e-7f) << at[i];
    EXPECT_EQ(foggy.maxAlpha(0.0f, 50000.0f), 0.0f);  // no fog over the lower half of the cells
    EXPECT_NEAR(foggy.evaluate(55000.0f).a, 0.005f, 1e-7f);
    EXPECT_NEAR(foggy.evaluate(100000.0f).a, 0.05f, 1e-7f);
    EXPECT_GT(foggy.evaluate(0.0f).b, foggy.evaluate(0.0f).r);  // bluish

    // The other presets span the range: the range-fixed ones over [P0, P100].
    for (const char* name : {"ramp", "grey", "constant", "empty"}) {
        const TransferFunction fitted = scene::makePreset(name, p), fixed = scene::makePreset(name, 0.0f, 100000.0f);
        EXPECT_EQ(fitted.positions(), fixed.positions()) << name;
        EXPECT_EQ(fitted.colors(), fixed.colors()) << name;
    }

    // Any distribution: the node positions are its percentiles (an exponential sample here).
    std::vector<float> e(54321);
    for (size_t i = 0; i < e.size(); ++i) e[i] = float(-std::log1p(-(double(i) + 0.5) / double(e.size())));
    const amr::Percentiles q = amr::percentilesOf(e);
    EXPECT_EQ(scene::makePreset("spiky", q).positions(),
              (std::vector<float>{q[0], q[74], q[75], q[76], q[89], q[90], q[91], q[96], q[97], q[98], q[100]}));
    EXPECT_EQ(scene::makePreset("foggy", q).positions(),
              (std::vector<float>{q[0], q[50], q[60], q[70], q[80], q[90], q[95], q[99], q[100]}));
    // Range-fixed, the same names mean other functions: one mid-range peak, fog everywhere.
    EXPECT_NE(scene::makePreset("spiky", q).positions(), scene::makePreset("spiky", q.lo(), q.hi()).positions());
    EXPECT_GT(scene::makePreset("foggy", q.lo(), q.hi()).evaluate(q[10]).a, 0.0f);
    EXPECT_EQ(scene::makePreset("foggy", q).evaluate(q[10]).a, 0.0f);

    expectError([&] { scene::makePreset("rainbow", p); }, {"unknown transfer function preset 'rainbow'"});
    expectError([] { scene::makePreset("spiky", amr::Percentiles{}); }, {"preset 'spiky'", "no values"});
    const TransferFunction loaded = scene::loadTransferFunction("spiky", p, amr::VolumeHistogram{});
    EXPECT_EQ(loaded.positions(), spiky.positions());
}

TEST(TransferFunction, FittedPresetsOnPlateaus) {
    // Values many cells share (AMReX's flame: a cold and a hot plateau with a few values between):
    // every apex keeps alpha 1 at its value and near it, whatever the percentiles it spans.
    std::vector<float> v;
    auto add = [&](float value, int cells) { v.insert(v.end(), size_t(cells), value); };
    add(298.0f, 4000);   // P0..P39
    add(900.0f, 500);    // P40..P44
    add(1578.0f, 2950);  // P45..P74
    add(1579.0f, 49);
    add(1580.0f, 2501);  // P75..P100: the maximum, which P90 and P97 share
    const amr::Percentiles p = amr::percentilesOf(v);
    ASSERT_EQ(p[74], 1578.0f);
    ASSERT_EQ(p[75], 1580.0f);
    ASSERT_EQ(p[97], p.hi());
    const TransferFunction spiky = scene::makePreset("spiky", p);
    // P90 and P97 equal P75's value: one peak, at the maximum, alpha 1 there and beyond.
    EXPECT_EQ(spiky.evaluate(1580.0f).a, 1.0f);
    EXPECT_GT(spiky.evaluate(std::nextafter(1580.0f, 0.0f)).a, 0.99f);
    EXPECT_EQ(spiky.evaluate(1579.0f).a, 0.5f);  // from the foot at P74 = 1578 up to the apex
    EXPECT_EQ(spiky.maxAlpha(298.0f, 1578.0f), 0.0f);
    EXPECT_EQ(spiky.lastPosition(), 1580.0f);
    EXPECT_EQ(spiky.firstPosition(), 298.0f);

    // A peak with both neighbours on its value, inside the range: both sides 1e-4 of the range wide.
    std::vector<float> w;
    auto addW = [&](float value, int cells) { w.insert(w.end(), size_t(cells), value); };
    addW(0.0f, 7000);
    addW(5.0f, 700);  // P71..P76: both neighbours of P75 share its value
    addW(6.0f, 1200);
    addW(7.0f, 500);
    addW(10.0f, 600);
    const amr::Percentiles q = amr::percentilesOf(w);
    ASSERT_EQ(q[74], 5.0f);
    ASSERT_EQ(q[76], 5.0f);
    const TransferFunction peaked = scene::makePreset("spiky", q);
    EXPECT_EQ(peaked.evaluate(5.0f).a, 1.0f);
    EXPECT_NEAR(peaked.evaluate(5.0f - 0.0005f).a, 0.5f, 1e-3f);  // side 1e-4 x range 10
    EXPECT_NEAR(peaked.evaluate(5.0f + 0.0005f).a, 0.5f, 1e-3f);
    EXPECT_EQ(peaked.evaluate(4.99f).a, 0.0f);
    EXPECT_EQ(peaked.maxAlpha(0.0f, 4.99f), 0.0f);

    // foggy: a background value most cells hold keeps alpha 0 (its lowest percentile's).
    const TransferFunction foggy = scene::makePreset("foggy", q);
    EXPECT_EQ(foggy.evaluate(0.0f).a, 0.0f);
    EXPECT_EQ(q[60], 0.0f);  // P60 shares the background's value
    EXPECT_GT(foggy.evaluate(6.0f).a, 0.0f);

    // One value: the range-fixed presets at that value.
    const amr::Percentiles one = amr::percentilesOf(std::vector<float>(10, 3.0f));
    for (const std::string& name : scene::presetNames()) {
        EXPECT_EQ(scene::makePreset(name, one).positions(), scene::makePreset(name, 3.0f, 3.0f).positions()) << name;
        EXPECT_EQ(scene::makePreset(name, one).colors(), scene::makePreset(name, 3.0f, 3.0f).colors()) << name;
    }
}

TEST(TransferFunction, FittedPresetsAreValidForAnyDistribution) {
    // Random distributions over a few values, with plateaus, huge and tiny magnitudes and values one
    // float step apart: the fitted TFs are valid (the constructor checks the order), spiky has alpha
    // 1 at each of its apexes and foggy none at or below the median.
    std::mt19937 rng(17);
    const float pool[] = {-3e38f, -1.0f, 0.0f, 1e-40f, 1.0f, std::nextafter(1.0f, 2.0f), std::nextafter(1.0f, 3.0f),
                          2.0f, 1e6f, std::nextafter(1e6f, 2e6f), 3e38f};
    for (int trial = 0; trial < 3000; ++trial) {
        std::vector<float> v(size_t(std::uniform_int_distribution<int>(1, 400)(rng)));
        const size_t distinct = size_t(std::uniform_int_distribution<int>(1, 11)(rng));
        for (float& x : v) x = pool[std::uniform_int_distribution<size_t>(0, distinct - 1)(rng)];
        const amr::Percentiles p = amr::percentilesOf(v);
        SCOPED_TRACE("trial " + std::to_string(trial));
        const TransferFunction spiky = scene::makePreset("spiky", p);
        const TransferFunction foggy = scene::makePreset("foggy", p);
        if (!(p.lo() < p.hi())) continue;
        std::string nodes;
        for (size_t i = 0; i < spiky.nodeCount(); ++i)
            nodes += strCat(" (", spiky.positions()[i], ", ", spiky.colors()[i].a, ")");
        for (int k : {75, 90, 97}) ASSERT_EQ(spiky.evaluate(p[k]).a, 1.0f) << "P" << k << " = " << p[k] << ":" << nodes;
        ASSERT_EQ(foggy.maxAlpha(p.lo(), p[50]), 0.0f);
        ASSERT_EQ(spiky.firstPosition(), p.lo());
        ASSERT_EQ(spiky.lastPosition(), p.hi());
    }
}

TEST(TransferFunction, FittedFoggyClearsTheCloudsBackground) {
    // A synthetic cloud: most of the volume is coarse background of low values. The background value
    // (the volume-weighted median) gets no fog from the fitted foggy and fog from the range-fixed one;
    // the upper percentiles get fog from both.
    amr::SyntheticParams params;
    params.cells = 50000;
    params.seed = 1;
    const std::shared_ptr<const scene::Volume> v = scene::makeVolume(amr::makeSyntheticModel(params));
    std::vector<std::pair<float, double>> byValue;  // value, cell volume
    for (size_t i = 0; i < v->model.cells.size(); ++i)
        byValue.emplace_back(v->field().values[i], amr::cellVolume(v->model.cells[i].level));
    std::sort(byValue.begin(), byValue.end());
    double total = 0, below = 0;
    for (const auto& c : byValue) total += c.second;
    float background = byValue.back().first;
    for (const auto& c : byValue)
        if ((below += c.second) >= 0.5 * total) {
            background = c.first;
            break;
        }
    const amr::Percentiles& p = v->percentiles;
    ASSERT_LT(background, p[50]);  // the background lies below the cell median

    const TransferFunction fitted = scene::makePreset("foggy", p);
    const TransferFunction fixed = scene::makePreset("foggy", v->valueLo(), v->valueHi());
    EXPECT_EQ(fitted.evaluate(background).a, 0.0f);
    EXPECT_GE(fixed.evaluate(background).a, 0.05f);  // the old foggy fogs the background: the box
    for (int k : {60, 80, 90, 99}) {
        EXPECT_GT(fitted.evaluate(p[k]).a, 0.0f) << k;
        EXPECT_GT(fitted.evaluate(p[k]).a, fitted.evaluate(p[k - 10]).a) << k;
    }
    // Over the whole volume, fog only where the cells of the upper half are (0.32 of it here; the
    // 10^6-cell cloud: 0.02); the range-fixed foggy fogs all of it.
    double fogged = 0;
    for (const auto& c : byValue) fogged += fitted.evaluate(c.first).a > 0 ? c.second : 0.0;
    EXPECT_LT(fogged / total, 0.4);
    const std::vector<float> values(v->field().values.begin(), v->field().values.end());
    EXPECT_EQ(fractionAtLeast(fixed, values, 0.0499f), 1.0);
}

TEST(TransferFunction, FittedSpikyHitsTheDataWhereTheRangeFixedOneMisses) {
    // Enzo's Density spans 0.012..1030 with most cells below 1: the range-fixed spiky's peak at
    // mid-range (515 +- 10) reaches alpha 0.5 in one cell of 137,502; the fitted one's three peaks
    // in about 3% of the cells.
    AMRVK_REQUIRE_DATA(test::kEnzoDataSet);
    const std::shared_ptr<const scene::Volume> v = scene::makeVolume(test::readEnzoDensity());
    const std::vector<float> values(v->field().values.begin(), v->field().values.end());
    const TransferFunction fitted = scene::makePreset("spiky", v->percentiles);
    const TransferFunction fixed = scene::makePreset("spiky", v->valueLo(), v->valueHi());
    EXPECT_LT(fractionAtLeast(fixed, values, 0.5f), 1e-4);
    EXPECT_GT(fractionAtLeast(fitted, values, 0.5f), 0.02);
    EXPECT_LT(fractionAtLeast(fitted, values, 0.5f), 0.05);
    for (int k : {75, 90, 97}) EXPECT_EQ(fitted.evaluate(v->percentiles[k]).a, 1.0f) << k;
}

TEST(TransferFunction, ParaViewSeparateColourAndOpacityNodes) {
    auto dir = test::scratchDir();
    // Colour: a ramp 0 -> 10 with a step at 6; opacity: its own nodes with a step at 2.
    writeText(dir / "cmap.json", R"([{
        "ColorSpace": "RGB", "Name": "Test Map",
        "RGBPoints": [0, 0, 0, 1,   4, 0.5, 0.5, 0.5,   6, 1, 0, 0,   6, 0, 1, 0,   10, 1, 1, 1],
        "Points": [-2, 0.0, 0.5, 0.0,   2, 0.2, 0.5, 0.0,   2, 0.8, 0.5, 0.0,   7, 3.0, 0.5, 0.0]
    }])");
    TransferFunction tf = scene::loadTransferFunction((dir / "cmap.json").string(), 0.0f, 1.0f);
    EXPECT_EQ(tf.name(), "Test Map");
    EXPECT_EQ(tf.positions(), (std::vector<float>{-2, 0, 2, 2, 4, 6, 6, 7, 10}));

    const std::vector<double> cpos = {0, 4, 6, 10}, apos = {-2, 2, 7};
    const std::vector<double> r = {0, 0.5, 1, 1}, g = {0, 0.5, 0, 1}, b = {1, 0.5, 0, 1};
    const std::vector<double> a = {0.0, 0.8, 3.0};
    // Off the steps each channel is one linear function; compare both sides of each step apart.
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-4.0, 12.0);
    for (int i = 0; i < 3000; ++i) {
        const double v = u(rng);
        const glm::vec4 c = tf.evaluate(float(v));
        const double x = float(v);
        const bool pastColourStep = x >= 6.0, pastAlphaStep = x >= 2.0;
        auto colour = [&](const std::vector<double>& ch, double leftAt6, double rightAt6) {
            std::vector<double> vals = ch;
            vals[2] = pastColourStep ? rightAt6 : leftAt6;
            return lerpNodes(cpos, vals, x);
        };
        EXPECT_NEAR(c.r, colour(r, 1, 0), 1e-5) << v;
        EXPECT_NEAR(c.g, colour(g, 0, 1), 1e-5) << v;
        EXPECT_NEAR(c.b, colour(b, 0, 0), 1e-5) << v;
        std::vector<double> av = a;
        if (!pastAlphaStep) av[1] = 0.2;
        EXPECT_NEAR(c.a, lerpNodes(apos, av, x), 1e-5) << v;
    }
    // The steps themselves: right nodes at the step, left limits just below.
    expectVec4Near(tf.evaluate(6.0f), glm::vec4(0, 1, 0, float(0.8 + 2.2 * 4.0 / 5.0)), 1e-6f);
    expectVec4Near(tf.evaluate(std::nextafter(6.0f, 0.0f)), glm::vec4(1, 0, 0, 0.8f + 2.2f * 0.8f), 1e-5f);
    EXPECT_NEAR(tf.evaluate(2.0f).a, 0.8f, 1e-7f);
    EXPECT_NEAR(tf.evaluate(std::nextafter(2.0f, 0.0f)).a, 0.2f, 1e-5f);
    EXPECT_EQ(tf.maxAlpha(-10.0f, 1.99f), tf.evaluate(1.99f).a);
}

TEST(TransferFunction, ParaViewWithoutOpacityRampsOverTheColourRange) {
    auto dir = test::scratchDir();
    writeText(dir / "one.json", R"({"Name": "Solo", "RGBPoints": [-1, 0, 0, 0, 3, 1, 1, 1]})");
    TransferFunction tf = scene::loadParaViewPreset(dir / "one.json");
    EXPECT_EQ(tf.positions(), (std::vector<float>{-1, 3}));
    EXPECT_EQ(tf.evaluate(-1.0f), glm::vec4(0.0f));
    EXPECT_EQ(tf.evaluate(3.0f), glm::vec4(1.0f));
    expectVec4Near(tf.evaluate(0.0f), glm::vec4(0.25f), 1e-7f);
    TransferFunction r = tf.rescaled(100.0f, 200.0f);
    expectVec4Near(r.evaluate(125.0f), glm::vec4(0.25f), 1e-6f);
}

TEST(TransferFunction, ParaViewFileWithSeveralPresets) {
    auto dir = test::scratchDir();
    writeText(dir / "many.json", R"([
        {"Name": "First", "RGBPoints": [0, 1, 0, 0, 1, 1, 0, 0]},
        {"Name": "Second", "RGBPoints": [0, 0, 1, 0, 2, 0, 1, 0], "Points": [0, 0.5, 0.5, 0, 2, 0.5, 0.5, 0]},
        {"Name": "Broken", "RGBPoints": [0, 1, 0]}
    ])");
    EXPECT_EQ(scene::loadParaViewPreset(dir / "many.json").name(), "First");
    TransferFunction second = scene::loadTransferFunction((dir / "many.json").string(), 0, 1, "Second");
    EXPECT_EQ(second.name(), "Second");
    EXPECT_EQ(second.evaluate(1.0f), glm::vec4(0.0f, 1.0f, 0.0f, 0.5f));
    expectError([&] { scene::loadParaViewPreset(dir / "many.json", "Third"); },
                {"many.json", "no preset named 'Third'", "3 presets", "First, Second, Broken"});
    expectError([&] { scene::loadParaViewPreset(dir / "many.json", "Broken"); },
                {"many.json", "preset 'Broken'", "RGBPoints has 3 numbers"});
}

// Upstream's viewer applies the .xf relDomain twice (exabrick-reference.md 1.6, 8): the nodes
// must span absDomain narrowed by relDomain exactly once.
TEST(UpstreamBug_RelDomainAppliedTwice, XfRoundTrip) {
    auto dir = test::scratchDir();
    const std::vector<glm::vec4> rgba = xfColors(128);
    // absDomain [-1, 3], relDomain 25..75 % -> nodes over [0, 2] (applied once); scale 100 -> 1.
    std::vector<uint8_t> bytes = xfBytes(100.0f, -1.0f, 3.0f, 25.0f, 75.0f, rgba);
    ASSERT_EQ(bytes.size(), 2080u);
    writeBytes(dir / "a.xf", bytes);
    writeBytes(dir / "a_without_extension", bytes);
    for (const char* name : {"a.xf", "a_without_extension"}) {
        TransferFunction tf = scene::loadTransferFunction((dir / name).string(), 50.0f, 60.0f);
        ASSERT_EQ(tf.nodeCount(), 128u);
        EXPECT_EQ(tf.firstPosition(), 0.0f);
        EXPECT_EQ(tf.lastPosition(), 2.0f);
        for (size_t i = 0; i < 128; ++i) {
            EXPECT_NEAR(tf.positions()[i], 2.0 * double(i) / 127.0, 1e-6);
            EXPECT_EQ(tf.colors()[i], rgba[i]);
        }
    }
    // opacityScale 110 -> alpha times 1.1^10.
    writeBytes(dir / "s.xf", xfBytes(110.0f, 0.0f, 1.0f, 0.0f, 100.0f, rgba));
    TransferFunction scaled = scene::loadXf(dir / "s.xf", 0.0f, 1.0f);
    for (size_t i = 0; i < 128; ++i) {
        EXPECT_NEAR(scaled.colors()[i].a, rgba[i].a * std::pow(1.1, 10.0), 1e-6);
        EXPECT_EQ(glm::vec3(scaled.colors()[i]), glm::vec3(rgba[i]));
    }
}

TEST(TransferFunction, OwlExaBrickAlphaTable) {
    auto dir = test::scratchDir();
    std::vector<uint8_t> bytes;
    for (int i = 0; i < 128; ++i) append(bytes, float(i) / 127.0f);
    ASSERT_EQ(bytes.size(), 512u);
    writeBytes(dir / "old.xf", bytes);
    TransferFunction tf = scene::loadTransferFunction((dir / "old.xf").string(), -4.0f, 4.0f);
    ASSERT_EQ(tf.nodeCount(), 128u);
    EXPECT_EQ(tf.firstPosition(), -4.0f);
    EXPECT_EQ(tf.lastPosition(), 4.0f);
    expectVec4Near(tf.evaluate(0.0f), glm::vec4(0.8f, 0.8f, 0.8f, 0.5f), 1e-6f);
    EXPECT_EQ(tf.evaluate(4.0f).a, 1.0f);
}

TEST(TransferFunction, MalformedInputs) {
    auto dir = test::scratchDir();
    auto json = [&](const std::string& name, const std::string& text) {
        writeText(dir / name, text);
        return [path = dir / name] { scene::loadParaViewPreset(path); };
    };
    expectError(json("syntax.json", "[{\"RGBPoints\": [0, 1, 1, 1,]}]"), {"syntax.json", "malformed JSON"});
    expectError(json("number.json", "42"), {"number.json", "expected a ParaView preset", "number"});
    expectError(json("empty.json", "[]"), {"empty.json", "no presets"});
    expectError(json("norgb.json", "[{\"Name\": \"X\"}]"), {"norgb.json", "preset 'X'", "no RGBPoints"});
    expectError(json("indexed.json", "{\"Name\": \"I\", \"IndexedColors\": [1, 0, 0]}"),
                {"indexed.json", "indexed colour maps are not supported"});
    expectError(json("notobj.json", "[3]"), {"notobj.json", "preset '#0'", "not a JSON object"});
    expectError(json("odd.json", "{\"RGBPoints\": [0, 1, 1, 1, 2, 1, 1]}"),
                {"odd.json", "RGBPoints has 7 numbers, not a positive multiple of 4"});
    expectError(json("str.json", "{\"RGBPoints\": [0, \"red\", 1, 1]}"),
                {"str.json", "RGBPoints element 1 is a string"});
    expectError(json("notarr.json", "{\"RGBPoints\": 5}"), {"notarr.json", "RGBPoints is not an array"});
    expectError(json("order.json", "{\"RGBPoints\": [0, 1, 1, 1, 2, 1, 1, 1, 1, 1, 1, 1]}"),
                {"order.json", "RGBPoints positions not ascending at node 2 (1 after 2)"});
    expectError(json("colour.json", "{\"RGBPoints\": [0, 1, 1.5, 1]}"),
                {"colour.json", "colour g = 1.5 is outside [0, 1]"});
    expectError(json("negop.json", "{\"RGBPoints\": [0, 1, 1, 1], \"Points\": [0, -0.5, 0.5, 0]}"),
                {"negop.json", "Points node 0 opacity -0.5 is negative"});
    expectError(json("points.json", "{\"RGBPoints\": [0, 1, 1, 1], \"Points\": [0, 1, 0.5]}"),
                {"points.json", "Points has 3 numbers"});
    expectError(json("huge.json", "{\"RGBPoints\": [1e300, 1, 1, 1]}"),
                {"huge.json", "not a finite float"});
    expectError([&] { scene::loadParaViewPreset(dir / "missing.json"); }, {"missing.json", "no such file"});

    const std::vector<glm::vec4> rgba = xfColors(128);
    auto xf = [&](const std::string& name, const std::vector<uint8_t>& bytes) {
        writeBytes(dir / name, bytes);
        return [path = dir / name] { scene::loadXf(path, 0.0f, 1.0f); };
    };
    std::vector<uint8_t> badMagic = xfBytes(100, 0, 1, 0, 100, rgba, 0x1234);
    expectError(xf("magic.xf", badMagic), {"magic.xf", "magic 0x1234 (expected 0x1235abc000)", "2080 bytes"});
    std::vector<uint8_t> truncated = xfBytes(100, 0, 1, 0, 100, rgba);
    truncated.resize(2000);
    expectError(xf("short.xf", truncated), {"short.xf", "size 2000 bytes, expected 2080 for N = 128"});
    std::vector<uint8_t> zero = xfBytes(100, 0, 1, 0, 100, {});
    expectError(xf("zero.xf", zero), {"zero.xf", "N = 0", "outside [1,"});
    std::vector<uint8_t> negativeN = xfBytes(100, 0, 1, 0, 100, {});
    int32_t minusOne = -1;
    std::memcpy(&negativeN[28], &minusOne, 4);
    expectError(xf("negn.xf", negativeN), {"negn.xf", "N = -1"});
    std::vector<glm::vec4> negAlpha = rgba;
    negAlpha[5].a = -0.25f;
    expectError(xf("nega.xf", xfBytes(100, 0, 1, 0, 100, negAlpha)), {"nega.xf", "node 5 alpha -0.25", "byte 124"});
    std::vector<glm::vec4> nanColour = rgba;
    nanColour[7].g = std::numeric_limits<float>::quiet_NaN();
    expectError(xf("nan.xf", xfBytes(100, 0, 1, 0, 100, nanColour)), {"nan.xf", "node 7 colour g is not finite"});
    expectError(xf("domain.xf", xfBytes(100, 2, 1, 0, 100, rgba)), {"domain.xf", "absDomain [2, 1]"});
    expectError(xf("rel.xf", xfBytes(100, 0, 1, 80, 20, rgba)), {"rel.xf", "relDomain [80, 20]"});
    expectError(xf("scale.xf", xfBytes(1e9f, 0, 1, 0, 100, rgba)), {"scale.xf", "opacityScale"});
    std::vector<uint8_t> oldNan(512, 0);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(&oldNan[40], &nan, 4);
    expectError(xf("oldnan.xf", oldNan), {"oldnan.xf", "node 10 colour a is not finite"});
    expectError(xf("tiny.xf", {1, 2, 3}), {"tiny.xf", "not a .xf transfer function", "size 3 bytes"});

    expectError([] { scene::loadTransferFunction("no-such-preset-or-file", 0, 1); },
                {"'no-such-preset-or-file' is neither a transfer function preset", "ramp"});
    writeText(dir / "notes.txt", "hello");
    expectError([&] { scene::loadTransferFunction((dir / "notes.txt").string(), 0, 1); },
                {"notes.txt", "unknown transfer function format"});

    const float inf = std::numeric_limits<float>::infinity();
    expectError([] { TransferFunction({}, {}, "custom"); }, {"custom: no nodes"});
    expectError([] { TransferFunction({0.0f, 1.0f}, {kA}, "custom"); }, {"custom", "2 positions but 1 colours"});
    expectError([&] { TransferFunction({0.0f, nan}, {kA, kB}, "custom"); }, {"node 1 position is not finite"});
    expectError([&] { TransferFunction({0.0f, inf}, {kA, kB}, "custom"); }, {"node 1 position is not finite"});
    expectError([] { TransferFunction({1.0f, 0.0f}, {kA, kB}, "custom"); },
                {"positions not ascending at node 1 (0 after 1)"});
    expectError([] { TransferFunction({0.0f}, {glm::vec4(0, 0, 0, -1)}, "custom"); },
                {"node 0 alpha -1 is negative"});
    expectError([] { TransferFunction({0.0f}, {glm::vec4(0, 0, 2, 1)}, "custom"); },
                {"node 0 colour b = 2 is outside [0, 1]"});
    expectError([&] { TransferFunction({0.0f}, {glm::vec4(0, 0, 0, nan)}, "custom"); },
                {"node 0 colour a is not finite"});
}
