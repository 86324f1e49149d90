// VolumeScene builds exactly what the structure plan of a configuration lists and frees what a new
// configuration no longer needs ("model only what a scene needs"); the plan is the one place that
// decides it; the volume owns (and reorders) the model it is given; auto back-ends fit the device.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "accel/bricks.h"
#include "accel/bricks_file.h"
#include "core/error.h"
#include "model_fixtures.h"
#include "scene/structure_plan.h"
#include "scene/volume_scene.h"

using namespace amrvk;

namespace {
bool holds(const scene::VolumeScene& s, const std::string& name) {
    const auto bytes = s.hostBytes();
    return std::any_of(bytes.begin(), bytes.end(), [&](const auto& e) { return e.first == name && e.second > 0; });
}

}  // namespace

TEST(VolumeScene, BuildsOnlyWhatTheConfigurationUsesAndFreesTheRest) {
    scene::StructureConfig c;  // grid-dda, grid, sw
    scene::VolumeScene s(scene::makeVolume(test::makeThreeLevelCloud()), c);
    EXPECT_TRUE(holds(s, "bricks") && holds(s, "brickGrid") && holds(s, "macrocells"));
    EXPECT_FALSE(holds(s, "abrs") || holds(s, "traversalBoxes") || holds(s, "samplerBoxes") || holds(s, "samplerBvh"));

    c.sampler = scene::SamplerKind::ExtBrick;
    s.configure(c);
    // The brick grid stays on the host for the sub-majorants (not on the device: the ext-brick sampler).
    EXPECT_TRUE(holds(s, "bricks") && holds(s, "samplerBvh") && holds(s, "macrocells") && holds(s, "brickGrid"));
    EXPECT_FALSE(holds(s, "abrs") || holds(s, "traversalBoxes"));
    c.subMajorants = 0;
    s.configure(c);
    EXPECT_TRUE(holds(s, "bricks") && holds(s, "samplerBvh") && holds(s, "macrocells"));
    EXPECT_FALSE(holds(s, "brickGrid") || holds(s, "abrs") || holds(s, "traversalBoxes"));

    c.traversal = scene::TraversalKind::Abr;
    c.sampler = scene::SamplerKind::Abr;
    c.backend = scene::Backend::Rq;
    s.configure(c);
    EXPECT_TRUE(holds(s, "abrs") && holds(s, "traversalBoxes") && holds(s, "samplerBoxes"));
    EXPECT_FALSE(holds(s, "macrocells") || holds(s, "samplerBvh") || holds(s, "brickGrid"));
    EXPECT_EQ(s.domains.boxes.size(), s.abrs->abrs.size());
    EXPECT_EQ(s.samplerBoxes.size(), s.abrs->abrs.size());

    c.traversal = scene::TraversalKind::Brick;
    c.sampler = scene::SamplerKind::ExtBrick;
    c.backend = scene::Backend::Sw;
    s.configure(c);
    EXPECT_FALSE(holds(s, "abrs") || holds(s, "samplerBoxes") || holds(s, "macrocells"));
    EXPECT_EQ(s.domains.boxes.size(), s.volume().bricks.bricks.size());
    EXPECT_EQ(s.domains.ranges.size(), s.volume().bricks.bricks.size());

    c.traversal = scene::TraversalKind::KdTree;
    c.kdLeaves = 64;
    s.configure(c);
    EXPECT_TRUE(s.domains.boxes.empty()) << "kd-tree boxes depend on the TF: the renderer builds them";
    EXPECT_TRUE(holds(s, "supportRangeQuery"));
    const amr::Box3l all = s.volume().bounds();
    EXPECT_FALSE(s.supportRanges->query({glm::dvec3(all.lower), glm::dvec3(all.upper)}).empty());

    c.traversal = scene::TraversalKind::GridBvh;
    s.configure(c);
    EXPECT_FALSE(holds(s, "supportRangeQuery") || holds(s, "traversalBoxes"));
    EXPECT_TRUE(holds(s, "macrocells"));
}

TEST(VolumeScene, ConfigurationNamesAndErrors) {
    EXPECT_EQ(scene::parseTraversal("kdtree"), scene::TraversalKind::KdTree);
    EXPECT_EQ(std::string(scene::traversalName(scene::TraversalKind::GridBvh)), "grid-bvh");
    EXPECT_EQ(scene::allTraversals().size(), 6u);
    EXPECT_THROW(scene::parseTraversal("octree"), Error);
    EXPECT_THROW(scene::parseBackend("cuda"), Error);
    try {
        scene::StructureConfig rq;
        rq.backend = scene::Backend::Rq;
        scene::resolveBackend(rq, {"lavapipe-old", true, false});
        FAIL() << "rq on a device without ray query must fail";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("lavapipe-old"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("VK_KHR_ray_query"), std::string::npos);
    }
}

TEST(VolumeScene, AutoBackendFitsTheDevice) {
    // Measured: ray queries are 3-4x slower than the software BVH on lavapipe; not measured faster
    // on any GPU yet. Where nothing uses a box hierarchy the back-ends are the same shader work.
    const scene::DeviceTraits cpuRq{"llvmpipe", true, true}, gpuRq{"gpu", false, true}, gpuNoRq{"old", false, false};
    scene::StructureConfig c;
    c.backend = scene::Backend::Auto;
    c.traversal = scene::TraversalKind::Abr;
    c.sampler = scene::SamplerKind::Abr;
    for (const scene::DeviceTraits& d : {cpuRq, gpuRq, gpuNoRq}) {
        const scene::BackendChoice b = scene::resolveBackend(c, d);
        EXPECT_EQ(b.backend, scene::Backend::Sw) << d.name;
        EXPECT_NE(b.why.find("--backend auto: sw"), std::string::npos) << b.why;
    }
    EXPECT_NE(scene::resolveBackend(c, cpuRq).why.find("CPU devices"), std::string::npos);
    c.traversal = scene::TraversalKind::GridDda;
    c.sampler = scene::SamplerKind::Grid;
    EXPECT_NE(scene::resolveBackend(c, gpuRq).why.find("no box hierarchy"), std::string::npos);
    c.backend = scene::Backend::Rq;  // given: kept, with no reason
    const scene::BackendChoice given = scene::resolveBackend(c, cpuRq);
    EXPECT_EQ(given.backend, scene::Backend::Rq);
    EXPECT_TRUE(given.why.empty());
}

TEST(VolumeScene, ThePlanDecidesEveryStructure) {
    // For every combination and back-end the scene holds exactly what planOf lists, and the build
    // time it reports counts exactly those structures.
    const std::shared_ptr<const scene::Volume> v = scene::makeVolume(test::makeThreeLevelCloud());
    scene::StructureConfig c;
    c.grid = "8";
    c.kdLeaves = 32;
    scene::VolumeScene s(v, c);
    std::vector<scene::SamplerKind> samplers = scene::allSamplers();
    samplers.push_back(scene::SamplerKind::Dense);
    size_t checked = 0;
    for (scene::TraversalKind t : scene::allTraversals())
        for (scene::SamplerKind k : samplers)
            for (scene::Backend b : {scene::Backend::Sw, scene::Backend::Rq}) {
                c.traversal = t;
                c.sampler = k;
                c.backend = b;
                const scene::StructurePlan p = c.plan();
                if (!scene::traitsOf(k).amr && !scene::traitsOf(t).macrocellRanges) {
                    EXPECT_THROW(s.configure(c), Error) << c.label();
                    continue;
                }
                s.configure(c);
                SCOPED_TRACE(c.label());
                EXPECT_EQ(s.abrs.has_value(), p.abrs);
                EXPECT_EQ(!s.samplerBvh.nodes.empty(), p.samplerBvh);
                EXPECT_EQ(!s.samplerBoxes.empty(), p.samplerBoxes);
                EXPECT_EQ(s.brickGrid.has_value(), p.brickGrid);
                EXPECT_EQ(s.dense.has_value(), p.denseGrid);
                EXPECT_EQ(s.grid.has_value(), p.macrocellRanges);
                EXPECT_EQ(!s.domains.boxes.empty(), p.staticBoxes);
                EXPECT_EQ(s.supportRanges.has_value(), p.supportRangeQuery);
                // Build seconds: bricks + the lookup's structure + (ABRs) + (ranges) + (boxes).
                double expected = v->bricks.buildSeconds + (p.abrs ? s.buildSeconds.abrs : 0.0);
                expected += p.denseGrid ? s.buildSeconds.dense : p.brickGrid ? s.buildSeconds.brickGrid : s.buildSeconds.samplerBvh;
                if (p.macrocellRanges) expected += s.buildSeconds.grid;
                if (p.staticBoxes || p.supportRangeQuery) expected += s.buildSeconds.domains;
                EXPECT_DOUBLE_EQ(s.combinationBuildSeconds(), expected);
                ++checked;
            }
    EXPECT_EQ(checked, 2u * (6 * 3 + 2));  // every AMR combination, dense with the two grid traversals
}

TEST(VolumeScene, ConfigsDifferingInAnyFieldAreDifferent) {
    // Every field takes part in equality: a session that differs only in --kd-leaves or
    // --dense-max-mib must rebuild (the viewer compares configs to decide).
    const scene::StructureConfig a;
    std::vector<scene::StructureConfig> changed(6, a);
    changed[0].sampler = scene::SamplerKind::Abr;
    changed[1].traversal = scene::TraversalKind::Abr;
    changed[2].backend = scene::Backend::Rq;
    changed[3].grid = "64";
    changed[4].kdLeaves = a.kdLeaves + 1;
    changed[5].denseMaxBytes = a.denseMaxBytes + 1;
    for (const scene::StructureConfig& c : changed) EXPECT_FALSE(c == a) << c.labelWithGrid();
    EXPECT_TRUE(scene::StructureConfig(a) == a);
}

TEST(VolumeScene, TheVolumeOwnsTheModelItReorders) {
    // makeVolume takes the model by value: the brick build's reordering happens to the volume's
    // copy, never to data a caller still holds.
    amr::Model m = test::makeThreeLevelCloud();
    const amr::Model original = m;
    const std::shared_ptr<const scene::Volume> v = scene::makeVolume(original);
    EXPECT_EQ(original.cells.size(), m.cells.size());
    bool same = true;
    for (size_t i = 0; i < m.cells.size(); ++i)
        same = same && m.cells[i].lower == original.cells[i].lower && m.cells[i].level == original.cells[i].level;
    EXPECT_TRUE(same) << "the caller's model is untouched";
    EXPECT_EQ(v->model.cells.size(), m.cells.size());
    bool reordered = false;
    for (size_t i = 0; i < m.cells.size() && !reordered; ++i) reordered = v->model.cells[i].lower != m.cells[i].lower;
    EXPECT_TRUE(reordered) << "the volume's cells are in brick order (a different order for this cloud)";
    EXPECT_EQ(v->brickValues().data(), v->field().values.data());
    EXPECT_THROW(scene::makeVolume(m, "no-such-field"), Error);
}

TEST(VolumeScene, ReleasedCellsLeaveTheSameBricksValuesAndRanges) {
    // VolumeOptions::releaseCells (one-shot renders): the cell array is freed after the brick
    // build, and every structure of the paper's samplers is what the volume with its cells builds;
    // what needs the cells refuses instead of reading an empty array.
    const std::shared_ptr<const scene::Volume> kept = scene::makeVolume(test::makeThreeLevelCloud());
    const std::shared_ptr<const scene::Volume> v =
        scene::makeVolume(test::makeThreeLevelCloud(), "", {.releaseCells = true});
    EXPECT_TRUE(v->cellsReleased);
    EXPECT_FALSE(kept->cellsReleased);
    EXPECT_TRUE(v->model.cells.empty());
    EXPECT_EQ(v->model.cells.bytes(), 0u) << "the memory is freed, not just the size";
    EXPECT_EQ(v->cellCount, kept->model.cells.size());
    EXPECT_EQ(kept->cellCount, kept->model.cells.size());
    EXPECT_EQ(kept->model.cells.bytesPerCell(), 8u) << "the cloud's cells are held in 8 bytes each";
    EXPECT_EQ(v->modelBytes() + kept->cellCount * kept->model.cells.bytesPerCell(), kept->modelBytes());
    ASSERT_EQ(v->bricks.bricks.size(), kept->bricks.bricks.size());
    ASSERT_EQ(v->brickValues().size(), kept->brickValues().size());
    EXPECT_TRUE(std::equal(v->brickValues().begin(), v->brickValues().end(), kept->brickValues().begin()));
    scene::StructureConfig c;  // grid-dda/grid: macrocell ranges and brick lists
    scene::VolumeScene a(kept, c), b(v, c);
    ASSERT_EQ(a.grid->ranges.size(), b.grid->ranges.size());
    for (size_t i = 0; i < a.grid->ranges.size(); ++i) {
        EXPECT_EQ(a.grid->ranges[i].lo, b.grid->ranges[i].lo) << i;
        EXPECT_EQ(a.grid->ranges[i].hi, b.grid->ranges[i].hi) << i;
    }
    c.sampler = scene::SamplerKind::Dense;
    EXPECT_THROW(b.configure(c), Error);
}

TEST(VolumeScene, GivenBricksKeepTheModelOrderAndGiveTheSameRanges) {
    // `amrvk info --bricks FILE`: a volume over bricks read from a file (the model in its own order,
    // the field copied into slot order, NaN for an empty slot) builds every plan's structures, and
    // the macrocell ranges do not depend on who made the bricks.
    const std::shared_ptr<const scene::Volume> built = scene::makeVolume(test::makeThreeLevelCloud());
    const std::filesystem::path file = std::filesystem::path(testing::TempDir()) / "given.bricks";
    accel::writeBricksFile(file, built->bricks);
    amr::Model copy = built->model;  // already in brick order: the file's cell ids are slot numbers
    for (size_t i = 0, j = copy.cells.size(); i + 1 < j; ++i, --j) copy.cells.swapCells(i, j - 1);  // reversed,
    // a different file order, values with it
    for (amr::Field& f : copy.fields) std::reverse(f.values.begin(), f.values.end());
    const uint32_t n = uint32_t(copy.cells.size());
    accel::BrickSet given = accel::readBricksFile(file, built->model);
    for (uint32_t& id : given.cellIds) id = n - 1 - id;  // the same bricks over the reversed cells
    const std::shared_ptr<const scene::Volume> v = scene::makeVolume(std::move(copy), "", std::move(given));
    EXPECT_NE(v->brickValues().data(), v->field().values.data()) << "slot order is a copy";
    ASSERT_EQ(v->brickValues().size(), built->brickValues().size());
    EXPECT_TRUE(std::equal(v->brickValues().begin(), v->brickValues().end(), built->brickValues().begin()));
    EXPECT_EQ(v->model.cells.front().lower, built->model.cells.back().lower) << "the model keeps its order";

    scene::StructureConfig c;  // grid-dda/grid: macrocell ranges
    scene::VolumeScene a(built, c), b(v, c);
    ASSERT_EQ(a.grid->ranges.size(), b.grid->ranges.size());
    for (size_t i = 0; i < a.grid->ranges.size(); ++i) {
        EXPECT_EQ(a.grid->ranges[i].lo, b.grid->ranges[i].lo) << i;
        EXPECT_EQ(a.grid->ranges[i].hi, b.grid->ranges[i].hi) << i;
    }
    c.traversal = scene::TraversalKind::Abr;
    b.configure(c);
    ASSERT_TRUE(b.abrs.has_value());
    EXPECT_EQ(b.domains.ranges.size(), b.abrs->abrs.size());
    std::filesystem::remove(file);
}
