// Majorant kd-tree (accel/kdtree.h) checked independently: leaf ranges against brute force over
// every cell, leaf majorants against the TF alpha of the brute-force reconstruction
// (amr::ReferenceSampler) at random points, tiling by rasterising leaves into voxels.
#include "accel/kdtree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "accel/brick_build.h"
#include "accel/bricks.h"
#include "accel/majorant_bounds.h"
#include "accel/support_range.h"
#include "amr/sampler.h"
#include "amr/synthetic.h"
#include "core/error.h"
#include "model_fixtures.h"
#include "scene/tf_presets.h"
#include "scene/transfer_function.h"
#include "test_data.h"

using namespace amrvk;
using namespace amrvk::accel;

namespace {

struct Built : test::Built {
    amr::Box3l bounds;     // union of leaf cells
    float lo = 0, hi = 0;  // field range
};

Built build(amr::Model m) {
    Built b{test::buildBricks(std::move(m))};
    b.bounds = amr::summarize(b.model).bounds;
    const amr::FieldStats st = amr::computeFieldStats(b.model, b.model.fields[0]);
    b.lo = st.minValue;
    b.hi = st.maxValue;
    return b;
}

amr::Model fixture(uint32_t seed, glm::ivec3 origin = glm::ivec3(0)) {
    amr::Model m = test::makeRefinedModel(seed, {5, 4, 3}, 3, 0.4, origin);
    test::addRandomField(m, "r", seed + 100);
    return m;
}

// A TF as an (alpha, exact maxAlpha) pair: a tent of height 1 around `centre`, half width `half`.
struct TentTf {
    float centre, half;
    float alpha(float v) const { return std::max(0.0f, 1.0f - std::abs(v - centre) / half); }
    float maxAlpha(float lo, float hi) const {
        if (lo <= centre && centre <= hi) return 1.0f;
        return std::max(alpha(lo), alpha(hi));
    }
};

BoxD closedBox(const amr::Box3l& b) { return {glm::dvec3(b.lower), glm::dvec3(b.upper)}; }

// Every cell whose closed support [lower - w/2, lower + 3w/2] meets the closed box.
ValueRange bruteRange(const amr::Model& m, const BoxD& box) {
    ValueRange r;
    for (size_t i = 0; i < m.cells.size(); ++i) {
        const amr::Cell& c = m.cells[i];
        const double w = double(amr::cellWidth(c.level));
        bool meets = true;
        for (int d = 0; d < 3; ++d)
            meets = meets && double(c.lower[d]) - 0.5 * w <= box.hi[d] &&
                    double(c.lower[d]) + 1.5 * w >= box.lo[d];
        if (meets) r.extend(m.fields[0].values[i]);
    }
    return r;
}

double volumeOf(const BoxD& b) {
    const glm::dvec3 s = b.hi - b.lo;
    return s.x * s.y * s.z;
}

// Leaves tile `root` exactly: every voxel of the root is covered by exactly one leaf, leaf faces
// are integers inside the root, and the volumes add up.
void expectTiles(const KdTree& t, const amr::Box3l& root) {
    const glm::i64vec3 s = root.size();
    std::vector<int> cover(size_t(s.x * s.y * s.z), 0);
    double volume = 0;
    for (const BoxD& l : t.leaves) {
        for (int d = 0; d < 3; ++d) {
            EXPECT_EQ(l.lo[d], std::floor(l.lo[d]));
            EXPECT_EQ(l.hi[d], std::floor(l.hi[d]));
            EXPECT_LT(l.lo[d], l.hi[d]);
            EXPECT_GE(l.lo[d], double(root.lower[d]));
            EXPECT_LE(l.hi[d], double(root.upper[d]));
        }
        volume += volumeOf(l);
        const glm::i64vec3 a = glm::i64vec3(l.lo) - root.lower, b = glm::i64vec3(l.hi) - root.lower;
        for (int64_t z = std::max<int64_t>(a.z, 0); z < std::min(b.z, s.z); ++z)
            for (int64_t y = std::max<int64_t>(a.y, 0); y < std::min(b.y, s.y); ++y)
                for (int64_t x = std::max<int64_t>(a.x, 0); x < std::min(b.x, s.x); ++x)
                    cover[size_t((z * s.y + y) * s.x + x)]++;
    }
    EXPECT_EQ(volume, root.volume());
    size_t bad = 0;
    for (int c : cover) bad += c != 1;
    EXPECT_EQ(bad, 0u) << "voxels covered by no leaf or by several leaves";
}

// Exact up to the GPU padding: the brute-force range of the closed leaf (margins below half a
// voxel add nothing) lies inside the leaf's range, which lies inside that range padded
// (accel/majorant_bounds.h; slabs are padded by their own magnitudes, at most the leaf's).
bool tightRange(const ValueRange& got, const ValueRange& brute) {
    if (brute.empty()) return got.empty();
    const ValueRange padded = padForGpu(brute);
    return got.lo <= brute.lo && got.hi >= brute.hi && got.lo >= padded.lo && got.hi <= padded.hi;
}

void expectExactLeafRanges(const KdTree& t, const amr::Model& m) {
    ASSERT_EQ(t.leafRanges.size(), t.leaves.size());
    ASSERT_EQ(t.leafMajorants.size(), t.leaves.size());
    for (size_t i = 0; i < t.leaves.size(); ++i) {
        const ValueRange want = bruteRange(m, t.leaves[i]);
        EXPECT_TRUE(tightRange(t.leafRanges[i], want))
            << "leaf " << i << ": [" << t.leafRanges[i].lo << ", " << t.leafRanges[i].hi
            << "], brute force [" << want.lo << ", " << want.hi << "]";
    }
}

// alpha(f(P)) <= majorant of the leaf holding P, at random points of every closed leaf (faces
// included); returns the number of valid samples checked.
size_t expectMajorantsBound(const KdTree& t, const amr::Model& m,
                            const std::function<float(float)>& alpha, uint32_t seed) {
    amr::ReferenceSampler ref(m, m.fields[0]);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    size_t checked = 0, failures = 0;
    for (size_t i = 0; i < t.leaves.size(); ++i) {
        const BoxD& l = t.leaves[i];
        for (int k = 0; k < 40; ++k) {
            glm::dvec3 f(u(rng), u(rng), u(rng));
            if (k % 4 == 0) f[int(rng() % 3)] = double(rng() % 2);  // on a face
            const glm::dvec3 p = l.lo + (l.hi - l.lo) * f;
            const amr::Sample s = ref.sample(p);
            if (!s.valid()) continue;
            ++checked;
            const float a = alpha(float(s.value));
            // float rounding of the TF lookup: a few ulps.
            if (a > t.leafMajorants[i] * (1.0f + 1e-5f) + 1e-6f && ++failures <= 10)
                ADD_FAILURE() << "leaf " << i << " majorant " << t.leafMajorants[i] << " < alpha "
                              << a << " of value " << s.value << " at (" << p.x << ", " << p.y
                              << ", " << p.z << ")";
        }
    }
    EXPECT_EQ(failures, 0u);
    return checked;
}

amr::Model syntheticCloud(uint64_t cells, uint64_t seed) {
    amr::SyntheticParams p;
    p.kind = amr::SyntheticKind::Cloud;
    p.cells = cells;
    p.blockCells = 4;
    p.seed = seed;
    return amr::makeSyntheticModel(p);
}

}  // namespace

TEST(KdTree, LeafRangesAreExactAndMajorantsBoundTheReconstruction) {
    Built b = build(fixture(1, {-2, 0, 1}));
    SupportRangeQuery q(b.bricks, b.values);
    const TentTf tf{b.lo + 0.4f * (b.hi - b.lo), 0.2f * (b.hi - b.lo)};
    const KdTree t =
        buildKdTree(q, b.bounds, [&](float lo, float hi) { return tf.maxAlpha(lo, hi); }, {150});
    EXPECT_EQ(t.leaves.size(), 150u);
    expectExactLeafRanges(t, b.model);
    for (size_t i = 0; i < t.leaves.size(); ++i)
        EXPECT_EQ(t.leafMajorants[i], t.leafRanges[i].empty()
                                          ? 0.0f
                                          : tf.maxAlpha(t.leafRanges[i].lo, t.leafRanges[i].hi));
    EXPECT_GT(expectMajorantsBound(
                  t, b.model, [&](float v) { return tf.alpha(v); }, 2),
              4000u);
}

TEST(KdTree, SpikyPresetOnSyntheticCloud) {
    Built b = build(syntheticCloud(20000, 3));
    SupportRangeQuery q(b.bricks, b.values);
    // Peak where the cloud has plenty of cells: the median value.
    std::vector<float> v = b.model.fields[0].values;
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    const float median = v[v.size() / 2];
    const scene::TransferFunction tf =
        scene::makePreset("spiky", median - 0.5f * (b.hi - b.lo), median + 0.5f * (b.hi - b.lo));
    const KdTree t =
        buildKdTree(q, b.bounds, [&](float lo, float hi) { return tf.maxAlpha(lo, hi); }, {256});
    EXPECT_EQ(t.leaves.size(), 256u);
    EXPECT_EQ(t.bounds.lower, b.bounds.lower);
    EXPECT_EQ(t.bounds.upper, b.bounds.upper);
    expectExactLeafRanges(t, b.model);
    EXPECT_GT(expectMajorantsBound(
                  t, b.model, [&](float x) { return tf.evaluate(x).a; }, 4),
              5000u);
    size_t positive = 0;
    for (float mu : t.leafMajorants) positive += mu > 0;
    EXPECT_GT(positive, 0u);
    EXPECT_GT(t.buildSeconds, 0.0);
    EXPECT_EQ(t.memoryBytes(), 256u * (sizeof(BoxD) + sizeof(ValueRange) + sizeof(float)));
}

TEST(KdTree, LeafCountReachesTheLimitWhenDataAllows) {
    Built b = build(fixture(2));
    SupportRangeQuery q(b.bricks, b.values);
    const float lo = b.lo, hi = b.hi;
    auto ramp = [&](float, float top) { return std::clamp((top - lo) / (hi - lo), 0.0f, 1.0f); };
    for (uint32_t n : {1u, 2u, 3u, 17u, 100u, 400u}) {
        const KdTree t = buildKdTree(q, b.bounds, ramp, {n});
        EXPECT_EQ(t.leaves.size(), n);
    }
}

TEST(KdTree, AllZeroTransferFunctionGivesOneEmptyMajorantLeaf) {
    Built b = build(fixture(3));
    SupportRangeQuery q(b.bricks, b.values);
    const KdTree t = buildKdTree(q, b.bounds, [](float, float) { return 0.0f; }, {4096});
    ASSERT_EQ(t.leaves.size(), 1u);
    EXPECT_EQ(t.leafMajorants[0], 0.0f);
    EXPECT_EQ(t.leaves[0].lo, glm::dvec3(b.bounds.lower));
    EXPECT_EQ(t.leaves[0].hi, glm::dvec3(b.bounds.upper));
    EXPECT_TRUE(tightRange(t.leafRanges[0], bruteRange(b.model, closedBox(b.bounds))));
}

TEST(KdTree, StopsWhenEveryOpaqueLeafIsOneVoxel) {
    // 4^3 voxels, opaque everywhere: 64 one-voxel leaves, however many are allowed.
    amr::Model m = test::makeRefinedModel(4, {2, 2, 2}, 1, 0.5);
    test::addRandomField(m, "r", 4);
    Built b = build(std::move(m));
    SupportRangeQuery q(b.bricks, b.values);
    const KdTree t = buildKdTree(q, b.bounds, [](float, float) { return 1.0f; }, {1000});
    EXPECT_EQ(t.leaves.size(), 64u);
    for (const BoxD& l : t.leaves) EXPECT_EQ(volumeOf(l), 1.0);
    expectTiles(t, b.bounds);
    expectExactLeafRanges(t, b.model);
}

TEST(KdTree, RefinesWhereTheOpaqueValuesAre) {
    // Field = x / 64 over 64 x 16 x 16 voxels; the TF has alpha 1 only for values in
    // [0.45, 0.55], i.e. near x = 32, and alphaElsewhere elsewhere. The band must get many small
    // leaves, the rest few large ones: a builder that ignored mu in its costs or in its choice of
    // leaf (median splits, largest leaf first) would give comparable mean volumes.
    amr::Model m = test::makeRefinedModel(5, {8, 2, 2}, 3, 0.3);
    test::addField(m, "x", [](glm::dvec3 c) { return c.x / 64.0; });
    Built b = build(std::move(m));
    SupportRangeQuery q(b.bricks, b.values);
    for (float alphaElsewhere : {0.0f, 0.01f}) {
        auto band = [=](float lo, float hi) {
            return lo <= 0.55f && hi >= 0.45f ? 1.0f : alphaElsewhere;
        };
        const KdTree t = buildKdTree(q, b.bounds, band, {64});
        ASSERT_EQ(t.leaves.size(), 64u);
        expectTiles(t, b.bounds);
        double bandVolume = 0, otherVolume = 0;
        size_t inBand = 0, other = 0;
        for (size_t i = 0; i < t.leaves.size(); ++i) {
            const bool isBand = t.leafMajorants[i] == 1.0f;
            (isBand ? bandVolume : otherVolume) += volumeOf(t.leaves[i]);
            (isBand ? inBand : other)++;
            // Band leaves lie where band values can be reached: cells with centres in
            // [28.8, 35.2], grown by at most one coarse support (8 voxels).
            if (isBand) {
                EXPECT_GE(t.leaves[i].hi.x, 28.8 - 8.0);
                EXPECT_LE(t.leaves[i].lo.x, 35.2 + 8.0);
            }
        }
        ASSERT_GT(inBand, 0u);
        ASSERT_GT(other, 0u);
        EXPECT_LT(bandVolume / double(inBand), 0.1 * otherVolume / double(other))
            << "alpha elsewhere " << alphaElsewhere;
    }
}

TEST(KdTree, BadParametersAreRejected) {
    Built b = build(fixture(6));
    SupportRangeQuery q(b.bricks, b.values);
    auto one = [](float, float) { return 1.0f; };
    test::expectError([&] { buildKdTree(q, b.bounds, one, {0}); }, {"--kd-leaves", "at least 1"});
    test::expectError([&] { buildKdTree(q, b.bounds, [](float, float) { return NAN; }, {8}); },
                      {"transfer function majorant"});
    test::expectError([&] { buildKdTree(q, b.bounds, [](float, float) { return -1.0f; }, {8}); },
                      {"transfer function majorant"});
}

// Upstream loads the kd-tree with setModelBounds(cellBounds) before cellBounds is computed, so the
// root is owl's default empty box. Ours: the root is the union of leaf cells and the leaves tile
// it exactly, for every leaf count; an empty root box is refused instead of silently used.
TEST(UpstreamBug_KdTreeModelBoundsBeforeInit, RootIsTheCellUnionAndLeavesTileIt) {
    for (uint32_t seed : {7u, 8u}) {
        Built b = build(fixture(seed, seed == 8 ? glm::ivec3(-3, 1, -2) : glm::ivec3(0)));
        // The union of leaf cells, computed here from the cells themselves.
        amr::Box3l cells{glm::i64vec3(INT64_MAX), glm::i64vec3(INT64_MIN)};
        for (const amr::Cell& c : b.model.cells) {
            cells.lower = glm::min(cells.lower, glm::i64vec3(c.lower));
            cells.upper = glm::max(cells.upper, glm::i64vec3(c.lower) + amr::cellWidth(c.level));
        }
        SupportRangeQuery q(b.bricks, b.values);
        const TentTf tf{b.lo + 0.7f * (b.hi - b.lo), 0.1f * (b.hi - b.lo)};
        for (uint32_t n : {1u, 2u, 5u, 64u, 300u}) {
            const KdTree t =
                buildKdTree(q, cells, [&](float lo, float hi) { return tf.maxAlpha(lo, hi); }, {n});
            ASSERT_FALSE(t.bounds.empty());
            EXPECT_EQ(t.bounds.lower, cells.lower);
            EXPECT_EQ(t.bounds.upper, cells.upper);
            EXPECT_LE(t.leaves.size(), n);
            EXPECT_GE(t.leaves.size(), 1u);
            expectTiles(t, cells);
            if (n == 1) {
                EXPECT_EQ(t.leaves[0].lo, glm::dvec3(cells.lower));
                EXPECT_EQ(t.leaves[0].hi, glm::dvec3(cells.upper));
            }
        }
        test::expectError(
            [&] { buildKdTree(q, amr::Box3l{}, [](float, float) { return 1.0f; }, {8}); },
            {"empty root box", "union of the leaf cells"});
    }
}
