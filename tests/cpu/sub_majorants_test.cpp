// Sub-majorants (scene/sub_majorants.*, accel::SubRangeMaker): every sub-box's value range is the
// exact range of the reconstruction over the grown sub-box (brute force over the cells,
// amr::ExactRange), never narrower with the GPU's room and wider by no more than the padding; the
// quantized majorants M q / 255 bound every sub-box's alpha maximum; the alpha mean is the TF's
// integral; the budget is kept, the loosest macrocells come first and a smooth TF refines none.
// Power: the macrocell's own range is wider than the exact sub-box range on most sub-boxes (so the
// tightness check would reject it), and a q one step lower fails the bound somewhere.
#include "scene/sub_majorants.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>

#include "accel/brick_grid.h"
#include "accel/majorant_bounds.h"
#include "accel/range_grid.h"
#include "amr/exact_range.h"
#include "amr/synthetic.h"
#include "model_fixtures.h"
#include "scene/tf_presets.h"
#include "scene/transfer_function.h"
#include "scene/volume.h"
#include "scene/volume_scene.h"
#include "test_data.h"

using namespace amrvk;

namespace {

struct Fixture {
    std::shared_ptr<const scene::Volume> volume;
    std::unique_ptr<scene::VolumeScene> scene;
};

// A grid-dda scene with sub-majorants (host structures only) over `m`.
Fixture sceneOf(amr::Model m, const std::string& grid) {
    Fixture f;
    f.volume = scene::makeVolume(std::move(m));
    scene::StructureConfig c;
    c.grid = grid;
    c.sampler = scene::SamplerKind::ExtBrick;  // the brick grid is kept for the sub-majorants alone
    c.subMajorants = 8;
    f.scene = std::make_unique<scene::VolumeScene>(f.volume, c);
    return f;
}

amr::Model cloud(uint64_t cells, uint32_t seed) {
    amr::SyntheticParams p;
    p.kind = amr::SyntheticKind::Cloud;
    p.cells = cells;
    p.seed = seed;
    return amr::makeSyntheticModel(p);
}

}  // namespace

// Sub-boxes are far smaller than a macrocell's lattice limit, so each one's range is exact: the
// exact range of the reconstruction over its box grown by the grid's margin (outwards on the
// grid's faces), with the room for the GPU's float sums, up to the padding. On Enzo (every level
// and brick size) and on a cloud with macrocells a few cells wide, n = 2, 4, 8 and 16.
TEST(SubMajorants, SubRangesAreTheExactRangesOfTheirGrownSubBoxes) {
    AMRVK_REQUIRE_DATA(test::kEnzoDataSet);
    struct Case {
        std::string name;
        amr::Model model;
        std::string grid;
    };
    std::vector<Case> cases;
    cases.push_back({"Enzo", test::readEnzoDensity(), "auto"});
    cases.push_back({"cloud", cloud(20000, 5), "12"});
    for (Case& c : cases) {
        SCOPED_TRACE(c.name);
        const Fixture f = sceneOf(std::move(c.model), c.grid);
        const scene::Volume& v = *f.volume;
        const accel::RangeGrid& rg = *f.scene->grid;
        const accel::SubRangeMaker maker(*f.scene->brickGrid, v.bricks, v.brickValues());
        const amr::ExactRange exact(v.model, v.field());
        const glm::dvec3 margin = accel::brickGridMargin(rg.cellSize, rg.dims);
        const amr::ModelSummary& sum = v.summary;
        const glm::dvec3 far(4.0 * double(amr::cellWidth(sum.maxLevel)) + 1.0);
        const glm::dvec3 boundsLo = glm::dvec3(sum.bounds.lower) - far, boundsHi = glm::dvec3(sum.bounds.upper) + far;
        const double eps = double(std::numeric_limits<float>::epsilon());
        size_t checked = 0, wider = 0, tighterThanMacrocell = 0;
        std::vector<accel::ValueRange> sub;
        std::mt19937 rng(7);
        for (size_t k = 0; k < 60; ++k) {
            // Macrocells with a range (some of them on the grid's faces).
            size_t cell = rng() % rg.ranges.size();
            while (rg.ranges[cell].empty() || !(rg.ranges[cell].lo < rg.ranges[cell].hi)) cell = rng() % rg.ranges.size();
            const int n = 2 << (k % 4);
            maker.ranges(cell, n, sub);
            ASSERT_EQ(sub.size(), size_t(n * n * n));
            const glm::ivec3 mc = rg.coordOf(cell);
            for (size_t s = 0; s < sub.size(); s += 1 + k % 5) {
                const glm::ivec3 sc(int(s) % n, int(s) / n % n, int(s) / (n * n));
                const glm::dvec3 size = rg.cellSize / double(n);
                const glm::dvec3 corner = rg.origin + rg.cellSize * glm::dvec3(mc) + size * glm::dvec3(sc);
                glm::dvec3 lo = corner - margin, hi = corner + size + margin;
                for (int a = 0; a < 3; ++a) {  // outwards where both are at the grid's face
                    if (mc[a] == 0 && sc[a] == 0) lo[a] = boundsLo[a];
                    if (mc[a] == rg.dims[a] - 1 && sc[a] == n - 1) hi[a] = boundsHi[a];
                }
                const amr::ExactRange::Result e = exact.over(lo, hi, accel::kGpuErrorUlps * eps);
                const accel::ValueRange& r = sub[s];
                ASSERT_EQ(e.empty(), r.empty()) << "macrocell " << cell << " sub-box " << s;
                if (e.empty()) continue;
                ++checked;
                EXPECT_LE(double(r.lo), e.roomLo) << "macrocell " << cell << " sub-box " << s;
                EXPECT_GE(double(r.hi), e.roomHi) << "macrocell " << cell << " sub-box " << s;
                const double pad = (accel::kGpuPadUlps + 2.0) * eps * std::max({e.maxAbs, std::abs(e.lo), std::abs(e.hi)});
                wider += !(double(r.lo) >= e.lo - pad && double(r.hi) <= e.hi + pad);
                const accel::ValueRange& whole = rg.ranges[cell];
                tighterThanMacrocell += double(whole.lo) < e.lo - pad || double(whole.hi) > e.hi + pad;
            }
        }
        EXPECT_GT(checked, 1000u);
        EXPECT_EQ(wider, 0u) << "of " << checked;
        // Power: the macrocell's range for its sub-boxes fails the tightness check on most of them.
        EXPECT_GT(tighterThanMacrocell, checked / 2) << "of " << checked;
    }
}

// The alpha mean is the integral of the piecewise-linear alpha over the interval (midpoint rule
// at 2^16 points), also beyond the nodes and across steps; a single value gives alpha there.
TEST(SubMajorants, AlphaMeanIsTheIntegralOverTheRange) {
    const scene::TransferFunction step({0.0f, 0.3f, 0.3f, 0.6f, 1.0f},
                                       {glm::vec4(1, 1, 1, 0.2f), glm::vec4(1, 1, 1, 0.4f), glm::vec4(1, 1, 1, 1.0f),
                                        glm::vec4(1, 1, 1, 0.0f), glm::vec4(1, 1, 1, 0.5f)});
    for (const scene::TransferFunction& tf :
         {scene::makePreset("spiky", 0.0f, 1.0f), scene::makePreset("layers", -2.0f, 5.0f), step}) {
        SCOPED_TRACE(tf.name());
        const scene::AlphaMean mean(tf);
        std::mt19937 rng(3);
        std::uniform_real_distribution<float> u(tf.firstPosition() - 1.0f, tf.lastPosition() + 1.0f);
        for (int k = 0; k < 200; ++k) {
            float lo = u(rng), hi = u(rng);
            if (lo > hi) std::swap(lo, hi);
            const int steps = 1 << 16;
            double sum = 0;
            for (int i = 0; i < steps; ++i) sum += tf.evaluate(float(lo + (hi - lo) * (i + 0.5) / steps)).a;
            EXPECT_NEAR(mean(lo, hi), sum / steps, 2e-4) << "[" << lo << ", " << hi << "]";
        }
        EXPECT_FLOAT_EQ(float(mean(0.25f, 0.25f)), tf.evaluate(0.25f).a);
    }
}

// Every quantized sub-majorant bounds its sub-box: M q / 255 >= the alpha maximum over the
// sub-box's range (so sigma <= m wherever the range holds), with q = 0 exactly where that maximum
// is 0; one step lower (q - 1) fails it on some sub-boxes (the check has power). The budget holds,
// the loosest macrocells are refined first, and foggy (smooth: no macrocell loose) refines none.
TEST(SubMajorants, QuantizedSubMajorantsBoundTheirSubBoxes) {
    AMRVK_REQUIRE_DATA(test::kEnzoDataSet);
    const Fixture f = sceneOf(test::readEnzoDensity(), "auto");
    const scene::Volume& v = *f.volume;
    const accel::RangeGrid& rg = *f.scene->grid;
    const accel::SubRangeMaker maker(*f.scene->brickGrid, v.bricks, v.brickValues());
    const scene::TransferFunction spiky = scene::makePreset("spiky", v.percentiles);
    const uint64_t budget = 1u << 20;
    const double chord = scene::chordOf(rg, double(amr::cellWidth(v.minLevel())));
    const scene::SubMajorantGrid g =
        scene::buildSubMajorants(rg, maker, spiky, {.maxDivision = 8, .budgetBytes = budget, .chordInFinestCells = chord});
    ASSERT_GT(g.refined, 100u);
    EXPECT_LE(g.memoryBytes() - rg.cellCount() * sizeof(uint32_t), budget);
    EXPECT_GT(g.wanted, budget);  // the budget, not the looseness, stopped it
    const scene::AlphaMean mean(spiky);
    double leastRefined = INFINITY, mostUnrefined = 0;
    size_t boxes = 0, below = 0;
    std::vector<accel::ValueRange> sub;
    for (size_t cell = 0; cell < rg.ranges.size(); ++cell) {
        const accel::ValueRange& r = rg.ranges[cell];
        const float M = spiky.maxAlpha(r.lo, r.hi);
        const auto [n, offset] = g.refinementOf(cell);
        // The lookups a chord saves at a division of 2 (the first step's gain, per byte alike).
        const double R = M > 0 && r.lo < r.hi ? double(M) / std::max(mean(r.lo, r.hi), 1e-9) : 1.0;
        const double saved = double(M) * chord * (1.0 - std::max(1.0 / R, 0.5));
        if (n == 1) {
            mostUnrefined = std::max(mostUnrefined, saved);
            continue;
        }
        leastRefined = std::min(leastRefined, saved);
        maker.ranges(cell, n, sub);
        for (size_t s = 0; s < sub.size(); ++s) {
            const float a = spiky.maxAlpha(sub[s].lo, sub[s].hi);
            const uint32_t q = g.q(cell, s);
            ++boxes;
            EXPECT_GE(double(M) * q / 255.0, double(a)) << "macrocell " << cell << " sub-box " << s;
            EXPECT_EQ(q == 0, !(a > 0.0f)) << "macrocell " << cell << " sub-box " << s;
            below += q > 0 && double(M) * (q - 1) / 255.0 < double(a);
        }
    }
    EXPECT_GT(boxes, 10000u);
    EXPECT_GT(below, boxes / 100);  // q is the smallest step that bounds, not a loose one
    EXPECT_GE(leastRefined, mostUnrefined * 0.99);  // where a byte saves the most first
    const scene::SubMajorantGrid foggy = scene::buildSubMajorants(
        rg, maker, scene::makePreset("foggy", v.percentiles), {.maxDivision = 8, .budgetBytes = budget, .chordInFinestCells = chord});
    EXPECT_EQ(foggy.refined, 0u);  // alpha <= 0.05: no chord saves half a lookup
}
