// Reconstruction: the brute-force tent sum over all cells (amr::ReferenceSampler) against two
// independent brick-based paths (extended-brick BVH and ABR brick lists), plus analytic fields.
#include <gtest/gtest.h>

#include <random>

#include "accel/abrs.h"
#include "accel/brick_build.h"
#include "accel/brick_sampler.h"
#include "accel/bricks.h"
#include "amr/sampler.h"
#include "model_fixtures.h"

using namespace amrvk;
using namespace amrvk::accel;

namespace {

using test::Built;
Built build(amr::Model m) { return test::buildBricks(std::move(m), true); }

// Random points in the union of leaf cells (the medium), uniformly per cell.
std::vector<glm::dvec3> pointsInCells(const amr::Model& m, size_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<size_t> pick(0, m.cells.size() - 1);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<glm::dvec3> pts;
    for (size_t i = 0; i < count; ++i) {
        const amr::Cell& c = m.cells[pick(rng)];
        double w = double(amr::cellWidth(c.level));
        pts.push_back(glm::dvec3(c.lower) + w * glm::dvec3(u(rng), u(rng), u(rng)));
    }
    return pts;
}

// Faces, edges and corners of boxes: the 27 points of {lo, mid, hi}^3 per box.
std::vector<glm::dvec3> boxFeaturePoints(const std::vector<BoxD>& boxes, size_t maxBoxes) {
    std::vector<glm::dvec3> pts;
    for (size_t i = 0; i < boxes.size() && i < maxBoxes; ++i) {
        const BoxD& b = boxes[i];
        for (int k = 0; k < 27; ++k) {
            glm::dvec3 t(k % 3, (k / 3) % 3, k / 9);
            pts.push_back(b.lo + (b.hi - b.lo) * (t * 0.5));
        }
    }
    return pts;
}

void expectClose(double a, double b, double rel, const glm::dvec3& p, const char* what) {
    double tol = rel * std::max(1.0, std::max(std::abs(a), std::abs(b)));
    EXPECT_NEAR(a, b, tol) << what << " at (" << p.x << ", " << p.y << ", " << p.z << ")";
}

}  // namespace

TEST(Reconstruction, ConstantFieldStaysConstantAcrossLevelJumps) {
    amr::Model m = test::makeRefinedModel(7, {4, 3, 3}, 4, 0.45);
    test::addField(m, "c", [](glm::dvec3) { return 2.5; });
    Built b = build(std::move(m));
    ASSERT_GE(amr::summarize(b.model).maxLevel - amr::summarize(b.model).minLevel, 3);
    amr::ReferenceSampler ref(b.model, b.model.fields[0]);
    ExtBrickSampler ext(b.bricks, b.values);
    AbrSampler abr(b.abrs, b.bricks, b.values);
    auto pts = pointsInCells(b.model, 20000, 1);
    auto features = boxFeaturePoints(brickDomainBoxes(b.bricks), 2000);
    pts.insert(pts.end(), features.begin(), features.end());
    size_t checked = 0;
    for (const auto& p : pts) {
        amr::Sample r = ref.sample(p);
        if (!r.valid()) continue;
        ++checked;
        EXPECT_NEAR(r.value, 2.5, 1e-12);
        EXPECT_NEAR(ext.sample(p).value, 2.5, 1e-12);
        EXPECT_NEAR(abr.sample(p).value, 2.5, 1e-12);
    }
    EXPECT_GT(checked, 20000u);
}

TEST(Reconstruction, EveryPointInsideALeafCellHasWeight) {
    amr::Model m = test::makeRefinedModel(3, {3, 3, 2}, 3, 0.5);
    test::addRandomField(m, "r", 3);
    Built b = build(std::move(m));
    amr::ReferenceSampler ref(b.model, b.model.fields[0]);
    // Cell corners and face centres are the extreme points of the medium.
    for (const amr::Cell& c : b.model.cells) {
        double w = double(amr::cellWidth(c.level));
        for (int k = 0; k < 8; ++k) {
            glm::dvec3 p = glm::dvec3(c.lower) + w * glm::dvec3(k & 1, (k >> 1) & 1, (k >> 2) & 1);
            EXPECT_GT(ref.sample(p).weightSum, 0.0);
        }
    }
}

TEST(Reconstruction, LinearFieldIsReproducedInsideALevel) {
    auto linear = [](glm::dvec3 p) { return 0.25 * p.x - 0.5 * p.y + 0.125 * p.z + 3.0; };
    // Uniform level-1 grid: trilinear interpolation of a linear function is exact.
    amr::Model uniform = test::makeRefinedModel(1, {12, 10, 8}, 1, 0.0);
    test::addField(uniform, "lin", linear);
    Built u = build(std::move(uniform));
    amr::ReferenceSampler refU(u.model, u.model.fields[0]);
    AbrSampler abrU(u.abrs, u.bricks, u.values);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> ux(1.0, 23.0), uy(1.0, 19.0), uz(1.0, 15.0);
    for (int i = 0; i < 5000; ++i) {
        glm::dvec3 p(ux(rng), uy(rng), uz(rng));  // at least one cell centre away from the boundary
        EXPECT_NEAR(refU.sample(p).value, linear(p), 2e-5 * std::abs(linear(p)) + 1e-5);
        EXPECT_NEAR(abrU.sample(p).value, linear(p), 2e-5 * std::abs(linear(p)) + 1e-5);
    }
    // Multi-level: a level-2 half beside a level-0 half (a jump of two levels), plus random
    // refinement elsewhere; wherever all 8 contributors share one level, the value is linear.
    amr::Model multi;
    multi.source = "two-halves";
    for (int z = 0; z < 16; z += 4)
        for (int y = 0; y < 16; y += 4)
            for (int x = 0; x < 24; x += 4) {
                if (x < 12) {
                    multi.cells.push_back({{x, y, z}, 2});
                    continue;
                }
                for (int k = 0; k < 64; ++k)
                    multi.cells.push_back({{x + (k & 3), y + ((k >> 2) & 3), z + (k >> 4)}, 0});
            }
    test::addField(multi, "lin", linear);
    Built mb = build(std::move(multi));
    const amr::Field& f = mb.model.fields[0];
    amr::ReferenceSampler refM(mb.model, f);
    amr::CellHash hash(mb.model.cells);
    size_t sameLevelPoints = 0;
    for (const auto& p : pointsInCells(mb.model, 20000, 9)) {
        int count = 0, level = -1;
        bool mixed = false;
        for (int32_t l : hash.levels()) {
            double w = double(amr::cellWidth(l));
            glm::dvec3 k0 = glm::floor(p / w - 0.5);
            for (int c = 0; c < 8; ++c) {
                glm::dvec3 k = k0 + glm::dvec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
                uint32_t idx = hash.find(glm::ivec3(k * w), l);
                if (idx == amr::CellHash::kNone || amr::tentWeight(mb.model.cells[idx], p) <= 0)
                    continue;
                ++count;
                mixed = mixed || (level >= 0 && level != l);
                level = l;
            }
        }
        if (mixed || count != 8) continue;
        ++sameLevelPoints;
        EXPECT_NEAR(refM.sample(p).value, linear(p), 2e-5 * std::abs(linear(p)) + 1e-5);
    }
    EXPECT_GT(sameLevelPoints, 1000u);
}

TEST(Reconstruction, ValueLiesInContributingCellsRange) {
    amr::Model m = test::makeRefinedModel(21, {4, 3, 3}, 3, 0.45);
    test::addRandomField(m, "r", 4);
    Built b = build(std::move(m));
    amr::ReferenceSampler ref(b.model, b.model.fields[0]);
    for (const auto& p : pointsInCells(b.model, 20000, 2)) {
        amr::Sample s = ref.sample(p);
        ASSERT_TRUE(s.valid());
        float lo, hi;
        ref.contributingRange(p, lo, hi);
        EXPECT_GE(s.value, double(lo) - 1e-9);
        EXPECT_LE(s.value, double(hi) + 1e-9);
    }
}

TEST(Reconstruction, BruteForceEqualsBrickAndAbrPaths) {
    // Two independent models: irregular refinement, and a shifted domain with negative corners.
    for (uint32_t seed : {31u, 32u}) {
        amr::Model m = test::makeRefinedModel(seed, {5, 4, 3}, 4, 0.35,
                                              seed == 32 ? glm::ivec3(-3, -1, 2) : glm::ivec3(0));
        test::addRandomField(m, "r", seed);
        Built b = build(std::move(m));
        amr::ReferenceSampler ref(b.model, b.model.fields[0]);
        ExtBrickSampler ext(b.bricks, b.values);
        AbrSampler abr(b.abrs, b.bricks, b.values);
        auto pts = pointsInCells(b.model, 100000, seed);
        auto brickPts = boxFeaturePoints(brickDomainBoxes(b.bricks), 5000);
        auto abrPts = boxFeaturePoints(abrBoxes(b.abrs), 5000);
        pts.insert(pts.end(), brickPts.begin(), brickPts.end());
        pts.insert(pts.end(), abrPts.begin(), abrPts.end());
        size_t valid = 0;
        for (const auto& p : pts) {
            amr::Sample r = ref.sample(p), e = ext.sample(p), a = abr.sample(p);
            expectClose(r.weightSum, e.weightSum, 1e-9, p, "ext-brick weight");
            expectClose(r.weightSum, a.weightSum, 1e-9, p, "abr weight");
            if (!r.valid()) continue;
            ++valid;
            expectClose(r.value, e.value, 1e-6, p, "ext-brick value");
            expectClose(r.value, a.value, 1e-6, p, "abr value");
            // With the ABR known (ABR traversal), no lookup is needed and the result is the same.
            int64_t ai = abr.findAbr(p);
            ASSERT_GE(ai, 0);
            expectClose(r.value, abr.sampleInAbr(b.abrs.abrs[size_t(ai)], p).value, 1e-6, p,
                        "abr (known region)");
        }
        EXPECT_GT(valid, 100000u);
    }
}

TEST(Reconstruction, ZeroWeightOutsideTheDataGivesNoSample) {
    amr::Model m = test::makeRefinedModel(2, {2, 2, 2}, 2, 0.3);
    test::addField(m, "c", [](glm::dvec3) { return 1.0; });
    Built b = build(std::move(m));
    amr::ReferenceSampler ref(b.model, b.model.fields[0]);
    ExtBrickSampler ext(b.bricks, b.values);
    AbrSampler abr(b.abrs, b.bricks, b.values);
    amr::Box3l bounds = amr::summarize(b.model).bounds;
    // Exactly on the outer domain boundary (bounds grown by half a coarse cell) and beyond it.
    glm::dvec3 far = glm::dvec3(bounds.upper) + 100.0;
    for (auto s : {ref.sample(far), ext.sample(far), abr.sample(far)}) {
        EXPECT_FALSE(s.valid());
        EXPECT_EQ(s.value, 0.0);
    }
}
