// Dense sampler (accel/dense_grid.h): every sample against the brute-force reconstruction
// (amr::ReferenceSampler) and its leaf-cell test, the interpolation on hand-made grids, the dense
// macrocell ranges against brute-force interpolation inside each macrocell, and the byte limit.
#include "accel/dense_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <random>

#include "accel/brick_build.h"
#include "accel/bricks.h"
#include "accel/majorant_bounds.h"
#include "accel/range_grid.h"
#include "amr/sampler.h"
#include "amr/synthetic.h"
#include "core/error.h"
#include "model_fixtures.h"

using namespace amrvk;
using namespace amrvk::accel;

namespace {

constexpr uint64_t kNoLimit = std::numeric_limits<uint64_t>::max();
const float kNaN = std::numeric_limits<float>::quiet_NaN();

struct Built {
    amr::Model model;
    BrickSet bricks;
    std::vector<float> values;  // brick order
    amr::ModelSummary summary;
};

Built build(amr::Model m) {
    Built b{std::move(m), {}, {}, {}};
    amr::validate(b.model);
    b.bricks = buildBricks(b.model);
    b.values = brickOrderValues(b.bricks, b.model.fields[0]);
    b.summary = amr::summarize(b.model);
    return b;
}

DenseGrid buildDense(const Built& b, uint64_t maxBytes = kNoLimit) {
    return buildDenseGrid(b.model, b.bricks, b.values, b.summary.bounds, b.summary.minLevel, maxBytes);
}

// A four-level refined block of 4x3x3 roots (width 8) at voxel (-16, 8, -8) with random cells
// removed and one whole root missing: holes inside and a non-box union.
amr::Model holeyModel(uint32_t seed) {
    amr::Model full = test::makeRefinedModel(seed, {4, 3, 3}, 3, 0.45, {-2, 1, -1});
    amr::Model m = full;
    m.cells.clear();
    std::mt19937 rng(seed + 100);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (const amr::Cell& c : full.cells) {
        const bool inMissingRoot = c.lower.x >= -8 && c.lower.x < 0 && c.lower.y >= 24 && c.lower.z >= 8;
        if (inMissingRoot || u(rng) < 0.12) continue;
        m.cells.push_back(c);
    }
    test::addRandomField(m, "f", seed);
    return m;
}

// The same model with every cell twice as wide (finest level present = 1).
amr::Model coarsened(amr::Model m) {
    for (size_t i = 0; i < m.cells.size(); ++i) {
        amr::Cell c = m.cells[i];
        c.lower *= 2;
        c.level += 1;
        m.cells.set(i, c);
    }
    return m;
}

void expectMatchesReference(const Built& b, const char* name) {
    SCOPED_TRACE(name);
    const DenseGrid g = buildDense(b);
    ASSERT_EQ(g.level, b.summary.minLevel);
    ASSERT_EQ(g.origin, b.summary.bounds.lower);
    for (int a = 0; a < 3; ++a)
        ASSERT_EQ(int64_t(g.dims[a]) * amr::cellWidth(g.level), b.summary.bounds.size()[a]);
    ASSERT_EQ(g.values.size(), size_t(g.dims.x) * size_t(g.dims.y) * size_t(g.dims.z));
    amr::ReferenceSampler ref(b.model, b.model.fields[0]);
    size_t inside = 0, outside = 0;
    for (int z = 0; z < g.dims.z; ++z)
        for (int y = 0; y < g.dims.y; ++y)
            for (int x = 0; x < g.dims.x; ++x) {
                const glm::dvec3 p = glm::dvec3(b.summary.bounds.lower) + (glm::dvec3(x, y, z) + 0.5) * g.width();
                const float v = g.values[g.index({x, y, z})];
                if (!ref.insideLeafCell(p)) {
                    ++outside;
                    EXPECT_TRUE(std::isnan(v)) << "sample (" << x << ", " << y << ", " << z << ") outside";
                    continue;
                }
                ++inside;
                const amr::Sample s = ref.sample(p);
                ASSERT_TRUE(s.valid());
                ASSERT_FALSE(std::isnan(v)) << "sample (" << x << ", " << y << ", " << z << ") inside";
                EXPECT_NEAR(v, s.value, 1e-5 * std::max(1.0, std::abs(s.value)))
                    << "sample (" << x << ", " << y << ", " << z << ")";
            }
    EXPECT_GT(inside, 0u);
    std::cout << "[ info     ] " << name << ": " << g.dims.x << "x" << g.dims.y << "x" << g.dims.z << " samples, "
              << inside << " inside, " << outside << " NaN, built in " << g.buildSeconds << " s\n";
}

// Hand-made 3x2x2 grid of width 2 at (-4, 0, 2): value 1 + 0.5 i, NaN at (2, 1, 1).
DenseGrid smallGrid() {
    DenseGrid g;
    g.origin = {-4, 0, 2};
    g.level = 1;
    g.dims = {3, 2, 2};
    for (int i = 0; i < 12; ++i) g.values.push_back(1.0f + 0.5f * float(i));
    g.values[g.index({2, 1, 1})] = kNaN;
    return g;
}

}  // namespace

TEST(DenseGrid, SamplesMatchReferenceAndLeafCells) {
    Built holey = build(holeyModel(3));
    ASSERT_GE(holey.summary.maxLevel - holey.summary.minLevel, 2);
    expectMatchesReference(holey, "holey");
    expectMatchesReference(build(coarsened(holeyModel(4))), "holey, finest level 1");
    expectMatchesReference(build(test::makeThreeLevelCloud()), "three-level cloud");
}

TEST(DenseGrid, HolesAreNaN) {
    const Built b = build(holeyModel(5));
    const DenseGrid g = buildDense(b);
    // The missing root cell: voxels [-8, 0) x [24, 32) x [8, 16).
    const glm::dvec3 lo = glm::dvec3(g.origin);
    for (double z = 8.5; z < 16; z += 1)
        for (double y = 24.5; y < 32; y += 1)
            for (double x = -7.5; x < 0; x += 1) {
                const glm::ivec3 i(glm::floor((glm::dvec3(x, y, z) - lo) / g.width()));
                EXPECT_TRUE(std::isnan(g.values[g.index(i)]));
            }
    // A fully covered model has no NaN at all.
    amr::Model full = test::makeRefinedModel(5, {2, 2, 2}, 3, 0.5);
    test::addRandomField(full, "f", 5);
    const DenseGrid gf = buildDense(build(std::move(full)));
    for (float v : gf.values) ASSERT_FALSE(std::isnan(v));
}

TEST(DenseGrid, SampleAtCentresAndMidpoints) {
    const DenseGrid g = smallGrid();
    for (int z = 0; z < 2; ++z)
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 3; ++x) {
                const float v = g.values[g.index({x, y, z})];
                const DenseSample s = sampleDense(g, g.centre({x, y, z}));
                if (std::isnan(v)) {
                    EXPECT_TRUE(std::isnan(s.value));
                    EXPECT_FALSE(s.inside);
                } else {
                    EXPECT_EQ(s.value, v);
                    EXPECT_TRUE(s.inside);
                }
            }
    // Halfway between two samples along each axis: their mean.
    auto mid = [&](glm::ivec3 a, glm::ivec3 b) { return sampleDense(g, 0.5 * (g.centre(a) + g.centre(b))); };
    auto val = [&](glm::ivec3 a) { return double(g.values[g.index(a)]); };
    EXPECT_FLOAT_EQ(mid({0, 0, 0}, {1, 0, 0}).value, float(0.5 * (val({0, 0, 0}) + val({1, 0, 0}))));
    EXPECT_FLOAT_EQ(mid({1, 0, 1}, {1, 1, 1}).value, float(0.5 * (val({1, 0, 1}) + val({1, 1, 1}))));
    EXPECT_FLOAT_EQ(mid({2, 1, 0}, {2, 1, 1}).value, float(val({2, 1, 0})));  // NaN neighbour: skipped
    // NaN neighbour along x: renormalised onto the other one; the point lies in the NaN sample's cell.
    const DenseSample nanMid = mid({1, 1, 1}, {2, 1, 1});
    EXPECT_FLOAT_EQ(nanMid.value, float(val({1, 1, 1})));
    EXPECT_FALSE(nanMid.inside);
    // Centre of the 8 samples (0..1)^3: the mean of all eight.
    double sum = 0;
    for (int c = 0; c < 8; ++c) sum += val({c & 1, (c >> 1) & 1, (c >> 2) & 1});
    EXPECT_FLOAT_EQ(sampleDense(g, glm::dvec3(-4, 0, 2) + 2.0).value, float(sum / 8));
    // Outside the grid: indices clamp to the nearest sample.
    const DenseSample below = sampleDense(g, glm::dvec3(-20, -7, -3));
    EXPECT_EQ(below.value, g.values[0]);
    EXPECT_TRUE(below.inside);
    // All eight NaN: NaN and not inside.
    DenseGrid empty = g;
    std::fill(empty.values.begin(), empty.values.end(), kNaN);
    const DenseSample e = sampleDense(empty, glm::dvec3(-1.3, 1.7, 3.2));
    EXPECT_TRUE(std::isnan(e.value));
    EXPECT_FALSE(e.inside);
}

TEST(DenseGrid, SampleAtCentresOfBuiltGrid) {
    const Built b = build(holeyModel(6));
    const DenseGrid g = buildDense(b);
    std::mt19937 rng(6);
    std::uniform_int_distribution<int> ux(0, g.dims.x - 2), uy(0, g.dims.y - 1), uz(0, g.dims.z - 1);
    size_t means = 0;
    for (int i = 0; i < 2000; ++i) {
        const glm::ivec3 c(ux(rng), uy(rng), uz(rng)), n = c + glm::ivec3(1, 0, 0);
        const float v = g.values[g.index(c)], w = g.values[g.index(n)];
        const DenseSample s = sampleDense(g, g.centre(c));
        if (std::isnan(v)) {
            EXPECT_FALSE(s.inside);
            continue;
        }
        EXPECT_EQ(s.value, v);
        EXPECT_TRUE(s.inside);
        if (std::isnan(w)) continue;
        EXPECT_FLOAT_EQ(sampleDense(g, 0.5 * (g.centre(c) + g.centre(n))).value, float(0.5 * (double(v) + double(w))));
        ++means;
    }
    EXPECT_GT(means, 500u);
}

TEST(DenseGrid, RangesBoundInterpolationInEveryMacrocell) {
    for (uint32_t seed : {7u, 8u}) {
        const Built b = build(seed == 7 ? holeyModel(seed) : coarsened(holeyModel(seed)));
        const DenseGrid g = buildDense(b);
        RangeGrid grid = rangeGridLayout(b.summary.bounds, {5, 3, 4});  // not sample-aligned
        assignDenseRanges(g, grid);
        ASSERT_EQ(grid.ranges.size(), size_t(5 * 3 * 4));
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        size_t checked = 0, nonEmpty = 0;
        for (int cz = 0; cz < grid.dims.z; ++cz)
            for (int cy = 0; cy < grid.dims.y; ++cy)
                for (int cx = 0; cx < grid.dims.x; ++cx) {
                    const glm::ivec3 c(cx, cy, cz);
                    const ValueRange r = grid.ranges[grid.index(c)];
                    const glm::dvec3 lo = grid.origin + glm::dvec3(c) * grid.cellSize;
                    std::vector<glm::dvec3> pts;
                    for (int k = 0; k < 27; ++k)  // corners, edges, faces, centre
                        pts.push_back(lo + grid.cellSize * (0.5 * glm::dvec3(k % 3, (k / 3) % 3, k / 9)));
                    for (int k = 0; k < 400; ++k) pts.push_back(lo + grid.cellSize * glm::dvec3(u(rng), u(rng), u(rng)));
                    for (const glm::dvec3& p : pts) {
                        const DenseSample s = sampleDense(g, p);
                        if (std::isnan(s.value)) continue;
                        ++checked;
                        EXPECT_TRUE(r.contains(s.value)) << "macrocell (" << cx << ", " << cy << ", " << cz << "): "
                                                         << s.value << " outside [" << r.lo << ", " << r.hi << "]";
                    }
                    // Brute force: the range covers the samples of the spec's index box
                    // floor(qa) .. floor(qb) + 1 and no more than one index further on each side.
                    ValueRange exact, wider;
                    glm::ivec3 a0, a1, w0, w1;
                    for (int a = 0; a < 3; ++a) {
                        const double qa = (lo[a] - double(g.origin[a])) / g.width() - 0.5;
                        const double qb = (lo[a] + grid.cellSize[a] - double(g.origin[a])) / g.width() - 0.5;
                        auto clampI = [&](double v) { return int(std::clamp(v, 0.0, double(g.dims[a] - 1))); };
                        a0[a] = clampI(std::floor(qa));
                        a1[a] = clampI(std::floor(qb) + 1);
                        w0[a] = clampI(std::floor(qa) - 1);
                        w1[a] = clampI(std::floor(qb) + 2);
                    }
                    for (int z = w0.z; z <= w1.z; ++z)
                        for (int y = w0.y; y <= w1.y; ++y)
                            for (int x = w0.x; x <= w1.x; ++x) {
                                const float v = g.values[g.index({x, y, z})];
                                if (std::isnan(v)) continue;
                                wider.extend(v);
                                if (x >= a0.x && x <= a1.x && y >= a0.y && y <= a1.y && z >= a0.z && z <= a1.z)
                                    exact.extend(v);
                            }
                    if (!exact.empty()) {
                        EXPECT_LE(r.lo, exact.lo);
                        EXPECT_GE(r.hi, exact.hi);
                    }
                    if (!r.empty()) {  // up to the padding for the GPU's float sums
                        ++nonEmpty;
                        EXPECT_GE(r.lo, padForGpu(wider).lo);
                        EXPECT_LE(r.hi, padForGpu(wider).hi);
                    }
                }
        EXPECT_GT(checked, 10000u);
        EXPECT_GT(nonEmpty, 30u);
    }
}

TEST(DenseGrid, ConstantRegionGivesPointRange) {
    // 32 x 16 x 16 voxels; the field is 2 for x < 16 and varies for x >= 16.
    amr::Model m = test::makeRefinedModel(9, {4, 2, 2}, 3, 0.4);
    test::addField(m, "f", [](glm::dvec3 p) { return p.x < 16 ? 2.0 : 0.1 * p.x + std::sin(p.y) + 0.05 * p.z; });
    const Built b = build(std::move(m));
    ASSERT_LT(b.summary.minLevel, b.summary.maxLevel);
    const DenseGrid g = buildDense(b);
    RangeGrid grid = rangeGridLayout(b.summary.bounds, {4, 2, 2});  // macrocells of 8 voxels
    assignDenseRanges(g, grid);
    for (int cz = 0; cz < 2; ++cz)
        for (int cy = 0; cy < 2; ++cy) {
            const ValueRange r0 = grid.ranges[grid.index({0, cy, cz})];  // 2, padded for the GPU
            EXPECT_EQ(r0.lo, padForGpu(ValueRange(2.0f, 2.0f)).lo);
            EXPECT_EQ(r0.hi, padForGpu(ValueRange(2.0f, 2.0f)).hi);
            EXPECT_LT(r0.hi - r0.lo, 1e-4f);
            const ValueRange r3 = grid.ranges[grid.index({3, cy, cz})];
            EXPECT_LT(r3.lo + 0.5f, r3.hi);
        }
}

TEST(DenseGrid, ByteLimit) {
    const Built b = build(holeyModel(10));
    const DenseGrid g = buildDense(b);
    const uint64_t bytes = denseGridBytes(b.summary.bounds, b.summary.minLevel);
    EXPECT_EQ(bytes, g.values.size() * sizeof(float));
    EXPECT_EQ(bytes, g.memoryBytes());
    EXPECT_EQ(denseGridBytes(b.summary.bounds, b.summary.minLevel + 1) * 8, bytes);  // 2^k-wide bounds
    // Exactly at the limit builds; one byte less throws.
    EXPECT_NO_THROW(buildDense(b, bytes));
    EXPECT_THROW(buildDense(b, bytes - 1), Error);

    // 512^3 samples need 512 MiB: refused with a 1 MiB limit, with both sizes in the message.
    const amr::Box3l big{{0, 0, 0}, {512, 512, 512}};
    EXPECT_EQ(denseGridBytes(big, 0), uint64_t(512) * 512 * 512 * 4);
    EXPECT_EQ(denseGridBytes(big, 1), uint64_t(256) * 256 * 256 * 4);
    try {
        buildDenseGrid(b.model, b.bricks, b.values, big, 0, uint64_t(1) << 20);
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("512^3"), std::string::npos) << msg;
        EXPECT_NE(msg.find("512.0 MiB"), std::string::npos) << msg;
        EXPECT_NE(msg.find("limit 1.0 MiB"), std::string::npos) << msg;
        EXPECT_NE(msg.find("--dense-max-mib"), std::string::npos) << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
    // Counts that overflow or exceed 2^31-1 per axis are refused whatever the limit.
    const amr::Box3l huge{{0, 0, 0}, {int64_t(1) << 33, int64_t(1) << 33, int64_t(1) << 33}};
    EXPECT_EQ(denseGridBytes(huge, 0), std::numeric_limits<uint64_t>::max());
    EXPECT_THROW(buildDenseGrid(b.model, b.bricks, b.values, huge, 0, kNoLimit), Error);
    const amr::Box3l longX{{0, 0, 0}, {int64_t(1) << 32, 1, 1}};
    EXPECT_EQ(denseGridBytes(longX, 0), uint64_t(16) << 30);
    EXPECT_THROW(buildDenseGrid(b.model, b.bricks, b.values, longX, 0, kNoLimit), Error);
}

TEST(DenseGrid, BuildsLargerCloud) {
    // A 128^3 grid from a synthetic cloud; the build time is printed.
    amr::SyntheticParams p;
    p.kind = amr::SyntheticKind::Cloud;
    p.cells = 300000;
    p.seed = 2;
    p.levels = 5;  // 2^4 blocks of 8 cells: 128 finest cells wide
    p.blockCells = 8;
    const Built b = build(amr::makeSyntheticModel(p));
    const DenseGrid g = buildDense(b);
    EXPECT_EQ(g.values.size(), size_t(g.dims.x) * size_t(g.dims.y) * size_t(g.dims.z));
    std::cout << "[ info     ] cloud " << b.model.cells.size() << " cells: " << g.dims.x << "x" << g.dims.y << "x"
              << g.dims.z << " dense samples in " << g.buildSeconds << " s\n";
    // Spot checks against the reference.
    amr::ReferenceSampler ref(b.model, b.model.fields[0]);
    std::mt19937 rng(2);
    std::uniform_int_distribution<int> ux(0, g.dims.x - 1), uy(0, g.dims.y - 1), uz(0, g.dims.z - 1);
    for (int i = 0; i < 3000; ++i) {
        const glm::ivec3 c(ux(rng), uy(rng), uz(rng));
        const glm::dvec3 q = g.centre(c);
        const float v = g.values[g.index(c)];
        ASSERT_EQ(ref.insideLeafCell(q), !std::isnan(v));
        if (!std::isnan(v)) {
            EXPECT_NEAR(v, ref.sample(q).value, 1e-5 * std::max(1.0, std::abs(double(v))));
        }
    }
}
