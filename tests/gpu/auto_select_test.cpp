// --traversal auto's rule for a finer macrocell grid (render/auto_select.h, step 4a), on probes
// made up here: a combination's grid is doubled, up to the cap, only while its finest measured
// grid is its best; other combinations, predicted probes and stopped probes do not count. No
// device is used (the rule is host code; it lives in the GPU binary with the rest of render/).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "render/auto_select.h"

using namespace amrvk;

namespace {

render::AutoProbe probe(scene::TraversalKind t, const std::string& grid, double efficiency, bool predicted = false) {
    render::AutoProbe p;
    p.config.traversal = t;
    p.config.sampler = scene::SamplerKind::Grid;
    p.config.backend = scene::Backend::Sw;
    p.config.grid = grid;
    p.efficiency = efficiency;
    p.predicted = predicted;
    return p;
}

const scene::TraversalKind kDda = scene::TraversalKind::GridDda;
const scene::TraversalKind kBvh = scene::TraversalKind::GridBvh;

}  // namespace

TEST(AutoSelect, FinerGridOnlyWhileTheFinestMeasuredGridIsTheBest) {
    const scene::StructureConfig dda = probe(kDda, "auto", 0).config;
    // Enzo's case: 130 (the finest of 16, 33, auto's 65 and 130) is grid-dda's best -> 256.
    std::vector<render::AutoProbe> probes = {probe(kDda, "auto", 1.0), probe(kDda, "16", 0.4), probe(kDda, "33", 0.8),
                                             probe(kDda, "130", 1.2)};
    EXPECT_EQ(render::nextFinerGrid(probes, dda, 130, 256), 256);
    EXPECT_EQ(render::nextFinerGrid(probes, dda, 100, 1024), 0) << "no probe at 100";
    // 256 measured and better still: at the cap, nothing finer.
    probes.push_back(probe(kDda, "256", 1.5));
    EXPECT_EQ(render::nextFinerGrid(probes, dda, 256, 256), 0);
    EXPECT_EQ(render::nextFinerGrid(probes, dda, 256, 1024), 512);
    // 256 measured and worse: the doubling stops.
    probes.back().efficiency = 1.1;
    EXPECT_EQ(render::nextFinerGrid(probes, dda, 256, 1024), 0);
}

TEST(AutoSelect, FinerGridJudgesEachCombinationByItsOwnProbes) {
    const scene::StructureConfig dda = probe(kDda, "auto", 0).config;
    const scene::StructureConfig bvh = probe(kBvh, "auto", 0).config;
    std::vector<render::AutoProbe> probes = {probe(kDda, "auto", 1.0), probe(kDda, "64", 1.2), probe(kBvh, "auto", 3.0),
                                             probe(kBvh, "64", 2.0)};
    EXPECT_EQ(render::nextFinerGrid(probes, dda, 64, 256), 128) << "grid-bvh's better probes do not count";
    EXPECT_EQ(render::nextFinerGrid(probes, bvh, 64, 256), 0) << "grid-bvh's best is its default grid";
    // A predicted probe (the cost model, not rendered) cannot stop it; a stopped probe (efficiency
    // 0) at the finest grid cannot start it.
    probes.push_back(probe(kDda, "auto", 9.0, true));
    EXPECT_EQ(render::nextFinerGrid(probes, dda, 64, 256), 128);
    probes[1].efficiency = 0;
    EXPECT_EQ(render::nextFinerGrid(probes, dda, 64, 256), 0);
}

TEST(AutoSelect, FinerGridStepsAreAtLeastOneAndAHalfTimes) {
    const scene::StructureConfig dda = probe(kDda, "auto", 0).config;
    // The 10^6 cloud: auto's 125, probed at 250; 256 would be a step of 1.02x.
    const std::vector<render::AutoProbe> probes = {probe(kDda, "auto", 1.0), probe(kDda, "250", 1.1)};
    EXPECT_EQ(render::nextFinerGrid(probes, dda, 250, 256), 0);
    EXPECT_EQ(render::nextFinerGrid(probes, dda, 250, 375), 375);
    EXPECT_EQ(render::nextFinerGrid(probes, dda, 250, 374), 0);
}

// Step 5: ties within the tolerance go to the fewest structures, then to the most efficient, the
// default grid no more than another: Enzo spiky's second run of benchmarks section 26.
TEST(AutoSelect, TiesGoToFewerStructuresThenTheMostEfficientWhateverTheGrid) {
    std::vector<render::AutoProbe> probes = {probe(kDda, "auto", 1271), probe(kBvh, "auto", 1237),
                                             probe(kDda, "130", 1234), probe(kBvh, "130", 1367),
                                             probe(kDda, "256", 1357), probe(kBvh, "256", 1218),
                                             probe(kDda, "auto", 5000, true)};
    const render::AutoProbe* pick = render::pickAmongTies(probes, 0.1);
    ASSERT_NE(pick, nullptr);
    // grid-bvh (its culling BVH) builds more than grid-dda; of grid-dda's ties, 256 is the best.
    EXPECT_EQ(pick->config.traversal, kDda);
    EXPECT_EQ(pick->config.grid, "256");
    // Outside the tolerance only the best is left, whatever it builds.
    pick = render::pickAmongTies(probes, 0.005);
    ASSERT_NE(pick, nullptr);
    EXPECT_EQ(pick->config.traversal, kBvh);
    EXPECT_EQ(pick->config.grid, "130");
    // abr/abr (ABRs and their boxes) ties with grid-dda at 0.95 of it and loses; at 0.85 it is alone.
    render::AutoProbe abr = probe(scene::TraversalKind::Abr, "auto", 2000);
    abr.config.sampler = scene::SamplerKind::Abr;
    probes.push_back(abr);
    probes.push_back(probe(kDda, "33", 1900));
    pick = render::pickAmongTies(probes, 0.1);
    ASSERT_NE(pick, nullptr);
    EXPECT_EQ(pick->config.traversal, kDda);
    EXPECT_EQ(pick->config.grid, "33");
    probes.back().efficiency = 1700;
    pick = render::pickAmongTies(probes, 0.1);
    ASSERT_NE(pick, nullptr);
    EXPECT_EQ(pick->config.traversal, scene::TraversalKind::Abr);
    EXPECT_EQ(render::pickAmongTies({probe(kDda, "auto", 9, true)}, 0.1), nullptr) << "nothing measured";
}
