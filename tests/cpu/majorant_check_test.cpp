// The exact range of the reconstruction (amr/exact_range.*) against dense brute-force sampling and
// an analytic field, and the exhaustive majorant check (scene/majorant_check.*): every traversal's
// boxes pass on real and synthetic data, and planted defects (no GPU padding, no position
// margin, a majorant too small) are caught.
#include "scene/majorant_check.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "accel/majorant_bounds.h"
#include "accel/support_range.h"
#include "amr/exact_range.h"
#include "amr/sampler.h"
#include "model_fixtures.h"
#include "scene/tf_presets.h"
#include "scene/volume.h"

namespace amrvk {
namespace {

// A 3-level refined fixture with a smooth field: level jumps of one and two, several bricks.
amr::Model refinedFixture() {
    amr::Model m = test::makeRefinedModel(11, {3, 3, 2}, 2, 0.45);
    test::addField(m, "f", [](glm::dvec3 p) { return std::sin(0.37 * p.x) + 0.5 * std::cos(0.23 * p.y + 0.11 * p.z); });
    return m;
}

// Every value the brute-force sampler finds at a lattice of points in the box (and at random
// points) lies in the exact range; the range's ends are taken where it says.
void expectTightAndContaining(const amr::Model& m, glm::dvec3 lo, glm::dvec3 hi, uint32_t seed) {
    const amr::ReferenceSampler ref(m, m.fields[0]);
    const amr::ExactRange exact(m, m.fields[0]);
    const amr::ExactRange::Result r = exact.over(lo, hi);
    ASSERT_FALSE(r.empty());
    const double tol = 1e-12 * std::max(1.0, r.maxAbs);
    // The ends are values of the reconstruction at the reported points (attained, so tight).
    EXPECT_NEAR(ref.sample(r.argLo).value, r.lo, tol);
    EXPECT_NEAR(ref.sample(r.argHi).value, r.hi, tol);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    size_t inside = 0;
    for (int k = 0; k < 20000; ++k) {
        // Random points, a quarter of them on the faces (where the range grows first).
        glm::dvec3 t(u(rng), u(rng), u(rng));
        if (k % 4 == 0) t[k % 3] = double((k / 4) % 2);
        const amr::Sample s = ref.sample(lo + (hi - lo) * t);
        if (!s.valid()) continue;
        ++inside;
        EXPECT_GE(s.value, r.lo - tol);
        EXPECT_LE(s.value, r.hi + tol);
    }
    EXPECT_GT(inside, 1000u);
}

TEST(ExactRange, ContainsEverySampledValueAndAttainsItsEnds) {
    const amr::Model m = refinedFixture();
    const amr::ModelSummary s = amr::summarize(m);
    const glm::dvec3 lo(s.bounds.lower), hi(s.bounds.upper);
    expectTightAndContaining(m, lo, hi, 1);                          // the whole data
    expectTightAndContaining(m, lo + 1.25, lo + glm::dvec3(5.5, 3.75, 2.5), 2);  // across level jumps
    expectTightAndContaining(m, lo + glm::dvec3(0.3, 0.1, 0.2), lo + glm::dvec3(0.4, 0.35, 0.3), 3);  // inside a cell
    expectTightAndContaining(m, lo - 0.75, lo + 0.25, 4);  // sticking out of the data
}

TEST(ExactRange, LinearFieldTakesItsExtremesAtTheBoxCorners) {
    // One level: the tent reconstruction reproduces a linear field between the outer cell centres.
    amr::Model m = test::makeRefinedModel(3, {8, 8, 8}, 0, 0.0);
    test::addField(m, "f", [](glm::dvec3 p) { return 2.0 * p.x - 0.5 * p.y + 0.25 * p.z; });
    const amr::ExactRange exact(m, m.fields[0]);
    const glm::dvec3 lo(1.3, 2.6, 0.9), hi(5.2, 6.1, 7.4);  // inside the outer centres [0.5, 7.5]
    const amr::ExactRange::Result r = exact.over(lo, hi);
    EXPECT_NEAR(r.lo, 2.0 * lo.x - 0.5 * hi.y + 0.25 * lo.z, 1e-12);
    EXPECT_NEAR(r.hi, 2.0 * hi.x - 0.5 * lo.y + 0.25 * hi.z, 1e-12);
    EXPECT_GT(r.vertices, 8u);  // the interior centre planes are evaluated too
}

TEST(ExactRange, NoSupportMeansEmpty) {
    const amr::Model m = refinedFixture();
    const amr::ExactRange exact(m, m.fields[0]);
    EXPECT_TRUE(exact.over(glm::dvec3(-100), glm::dvec3(-50)).empty());
    EXPECT_TRUE(exact.over(glm::dvec3(5), glm::dvec3(4)).empty());  // reversed box
}

// What the renderer's structures must pass: every box set of a synthetic cloud, a refined
// fixture and Enzo, under every preset (range-fixed, and spiky and foggy fitted to the data),
// with the sub-boxes of every TF that refines macrocells (spiky does on each of these at its grid).
void expectAllPass(amr::Model m, const char* grid = "16") {
    const std::shared_ptr<const scene::Volume> v = scene::makeVolume(std::move(m));
    scene::MajorantCheckOptions o;
    o.grid = grid;
    o.kdLeaves = 256;
    for (const std::string& name : scene::presetNames()) o.tfs.push_back(scene::makePreset(name, v->valueLo(), v->valueHi()));
    for (const char* name : {"spiky", "foggy"}) o.tfs.push_back(scene::makePreset(name, v->percentiles));  // fitted
    const std::vector<scene::BoxSetCheck> checks = scene::checkMajorants(v, o);
    const size_t subSets = size_t(std::count_if(checks.begin(), checks.end(),
                                                [](const scene::BoxSetCheck& c) { return c.boxes == "sub-boxes"; }));
    ASSERT_EQ(checks.size(), 4 + o.tfs.size() + subSets);
    EXPECT_TRUE(std::any_of(checks.begin(), checks.end(),
                            [](const scene::BoxSetCheck& c) { return c.boxes == "sub-boxes" && c.tf == "spiky"; }));
    for (const scene::BoxSetCheck& c : checks) {
        SCOPED_TRACE(c.boxes + " " + c.tf);
        EXPECT_TRUE(c.ok()) << c.rangeFailures << " range failures; " << c.worst;
        EXPECT_GT(c.withData, 0u);
        EXPECT_GT(c.vertices, c.withData);
        EXPECT_EQ(c.tfs.size(), c.tf.empty() ? o.tfs.size() : 1u);
    }
}

TEST(MajorantCheck, EveryBoxSetPassesOnACloud) { expectAllPass(test::makeThreeLevelCloud()); }
// Grid 4: at 16 its macrocells are a cell or two wide, too thin for spiky to refine them, and the
// sub-boxes across its level jumps are the ones most worth checking.
TEST(MajorantCheck, EveryBoxSetPassesOnARefinedFixture) { expectAllPass(refinedFixture(), "4"); }
TEST(MajorantCheck, EveryBoxSetPassesOnEnzo) {
    AMRVK_REQUIRE_DATA(test::kEnzoDataSet);
    expectAllPass(test::readEnzoDensity());
}

// Planted defects over the brick domains of a cloud: the check must reject each.
class MajorantCheckPower : public ::testing::Test {
protected:
    void SetUp() override {
        volume = scene::makeVolume(test::makeThreeLevelCloud());
        exact = std::make_unique<amr::ExactRange>(volume->model, volume->field());
        query = std::make_unique<accel::SupportRangeQuery>(volume->bricks, volume->brickValues());
        margin = accel::positionMargin(volume->bounds());
        for (const accel::Brick& b : volume->bricks.bricks) {
            const accel::HalfBox d = accel::brickDomain(b);
            boxes.push_back({d.lower(), d.upper()});
        }
        spiky = scene::makePreset("spiky", volume->valueLo(), volume->valueHi());
    }
    scene::BoxSetCheck run(const scene::StoredBoxes& s) const {
        scene::BoxSetCheck c;
        c.boxes = "planted";
        scene::checkBoxSet(*exact, s, margin, {&spiky}, {}, c);
        return c;
    }
    std::shared_ptr<const scene::Volume> volume;
    std::unique_ptr<amr::ExactRange> exact;
    std::unique_ptr<accel::SupportRangeQuery> query;
    double margin = 0;
    std::vector<accel::BoxD> boxes;
    scene::TransferFunction spiky;
};

TEST_F(MajorantCheckPower, TheRenderersRangesPass) {
    scene::StoredBoxes s{boxes, accel::brickDomainRanges(*query, volume->bricks, margin), {}};
    EXPECT_TRUE(run(s).ok());
}

TEST_F(MajorantCheckPower, RangesWithoutRoomForTheGpusRoundingFail) {
    scene::StoredBoxes s{boxes, {}, {}};
    for (const accel::BoxD& b : boxes) s.ranges.push_back(query->query(b));  // exact, unpadded
    const scene::BoxSetCheck c = run(s);
    EXPECT_GT(c.rangeFailures, 0u);  // wherever the range is attained (e.g. at a cell centre)
    EXPECT_FALSE(c.worst.empty());
}

TEST_F(MajorantCheckPower, RangesWithoutThePositionMarginFail) {
    // The exact range of each box itself, padded for the GPU: tight on the box, so it misses
    // what a rounding beyond a face can see wherever the field rises across the face.
    scene::StoredBoxes s{boxes, {}, {}};
    for (const accel::BoxD& b : boxes) {
        const amr::ExactRange::Result r = exact->over(b.lo, b.hi);
        s.ranges.push_back(accel::padForGpu(r.lo, r.hi, r.maxAbs));
    }
    const scene::BoxSetCheck c = run(s);
    EXPECT_GT(c.rangeFailures, 0u);
    // Grown by the margin instead, the same construction passes: the margin is what was missing.
    for (size_t i = 0; i < boxes.size(); ++i) {
        const amr::ExactRange::Result r = exact->over(boxes[i].lo - margin, boxes[i].hi + margin);
        s.ranges[i] = accel::padForGpu(r.lo, r.hi, r.maxAbs);
    }
    EXPECT_EQ(run(s).rangeFailures, 0u);
}

TEST_F(MajorantCheckPower, AMajorantTooSmallFailsUnderItsTf) {
    scene::StoredBoxes s{boxes, accel::brickDomainRanges(*query, volume->bricks, margin), {}};
    for (const accel::ValueRange& r : s.ranges) s.majorants.push_back(0.999f * spiky.maxAlpha(r.lo, r.hi));
    const scene::BoxSetCheck c = run(s);
    EXPECT_EQ(c.rangeFailures, 0u);
    ASSERT_EQ(c.tfs.size(), 1u);
    EXPECT_GT(c.tfs[0].failures, 0u);
    EXPECT_GT(c.tfs[0].worstRatio, 1.0);
}

}  // namespace
}  // namespace amrvk
