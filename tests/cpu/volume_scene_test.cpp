// VolumeScene builds only what a structure configuration uses and frees what a new configuration
// no longer needs ("model only what a scene needs").
#include <gtest/gtest.h>

#include <algorithm>

#include "core/error.h"
#include "model_fixtures.h"
#include "scene/volume_scene.h"

using namespace amrvk;

namespace {
bool holds(const scene::VolumeScene& s, const std::string& name) {
    const auto bytes = s.hostBytes();
    return std::any_of(bytes.begin(), bytes.end(), [&](const auto& e) { return e.first == name && e.second > 0; });
}

}  // namespace

TEST(VolumeScene, BuildsOnlyWhatTheConfigurationUsesAndFreesTheRest) {
    amr::Model m = test::makeThreeLevelCloud();
    scene::VolumeScene s = scene::makeVolumeScene(m, m.defaultField());
    scene::StructureConfig c;  // grid-dda, grid, sw
    s.configure(c);
    EXPECT_TRUE(holds(s, "bricks") && holds(s, "brickGrid") && holds(s, "macrocells"));
    EXPECT_FALSE(holds(s, "abrs") || holds(s, "traversalBoxes") || holds(s, "samplerBoxes") || holds(s, "samplerBvh"));

    c.sampler = scene::SamplerKind::ExtBrick;
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
    EXPECT_EQ(s.domains.boxes.size(), s.bricks.bricks.size());
    EXPECT_EQ(s.domains.ranges.size(), s.bricks.bricks.size());

    c.traversal = scene::TraversalKind::KdTree;
    c.kdLeaves = 64;
    s.configure(c);
    EXPECT_TRUE(s.domains.boxes.empty()) << "kd-tree boxes depend on the TF: the renderer builds them";
    EXPECT_TRUE(holds(s, "supportRangeQuery"));
    const amr::Box3l all = s.bounds;
    EXPECT_FALSE(s.supportRangeQuery().query({glm::dvec3(all.lower), glm::dvec3(all.upper)}).empty());

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
    EXPECT_EQ(scene::resolveBackend(scene::Backend::Auto, true, "gpu"), scene::Backend::Rq);
    EXPECT_EQ(scene::resolveBackend(scene::Backend::Auto, false, "cpu"), scene::Backend::Sw);
    try {
        scene::resolveBackend(scene::Backend::Rq, false, "lavapipe-old");
        FAIL() << "rq on a device without ray query must fail";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("lavapipe-old"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("VK_KHR_ray_query"), std::string::npos);
    }
}
