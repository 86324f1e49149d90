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
