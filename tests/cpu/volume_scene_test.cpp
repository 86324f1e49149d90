// VolumeScene builds only what a structure configuration uses and frees what a new configuration
// no longer needs ("model only what a scene needs").
#include <gtest/gtest.h>

#include <algorithm>

#include "core/error.h"
#include "model_fixtures.h"
#include "render/volume_scene.h"

using namespace amrvk;

namespace {
bool holds(const render::VolumeScene& s, const std::string& name) {
    const auto bytes = s.hostBytes();
    return std::any_of(bytes.begin(), bytes.end(), [&](const auto& e) { return e.first == name && e.second > 0; });
}

}  // namespace

TEST(VolumeScene, BuildsOnlyWhatTheConfigurationUsesAndFreesTheRest) {
    const amr::Model m = test::makeThreeLevelCloud();
    render::VolumeScene s = render::makeVolumeScene(m, m.defaultField());
    render::StructureConfig c;  // grid-dda, ext-brick, sw
    s.configure(c);
    EXPECT_TRUE(holds(s, "bricks") && holds(s, "samplerBvh") && holds(s, "macrocells"));
    EXPECT_FALSE(holds(s, "abrs") || holds(s, "traversalBoxes") || holds(s, "samplerBoxes"));

    c.traversal = render::TraversalKind::Abr;
    c.sampler = render::SamplerKind::Abr;
    c.backend = render::Backend::Rq;
    s.configure(c);
    EXPECT_TRUE(holds(s, "abrs") && holds(s, "traversalBoxes") && holds(s, "samplerBoxes"));
    EXPECT_FALSE(holds(s, "macrocells") || holds(s, "samplerBvh"));
    EXPECT_EQ(s.domains.boxes.size(), s.abrs->abrs.size());
    EXPECT_EQ(s.samplerBoxes.size(), s.abrs->abrs.size());

    c.traversal = render::TraversalKind::Brick;
    c.sampler = render::SamplerKind::ExtBrick;
    c.backend = render::Backend::Sw;
    s.configure(c);
    EXPECT_FALSE(holds(s, "abrs") || holds(s, "samplerBoxes") || holds(s, "macrocells"));
    EXPECT_EQ(s.domains.boxes.size(), s.bricks.bricks.size());
    EXPECT_EQ(s.domains.ranges.size(), s.bricks.bricks.size());

    c.traversal = render::TraversalKind::KdTree;
    c.kdLeaves = 64;
    s.configure(c);
    EXPECT_TRUE(s.domains.boxes.empty()) << "kd-tree boxes exist only once a TF is known";
    s.rebuildKdTree([](float lo, float hi) { return lo <= hi ? 0.5f : 0.0f; });
    EXPECT_TRUE(holds(s, "kdTree") && holds(s, "supportRangeQuery"));
    EXPECT_EQ(s.domains.boxes.size(), 64u);

    c.traversal = render::TraversalKind::GridBvh;
    s.configure(c);
    EXPECT_FALSE(holds(s, "kdTree") || holds(s, "supportRangeQuery") || holds(s, "traversalBoxes"));
    EXPECT_TRUE(holds(s, "macrocells"));
}

TEST(VolumeScene, ConfigurationNamesAndErrors) {
    EXPECT_EQ(render::parseTraversal("kdtree"), render::TraversalKind::KdTree);
    EXPECT_EQ(std::string(render::traversalName(render::TraversalKind::GridBvh)), "grid-bvh");
    EXPECT_EQ(render::allTraversals().size(), 6u);
    EXPECT_THROW(render::parseTraversal("octree"), Error);
    EXPECT_THROW(render::parseBackend("cuda"), Error);
    EXPECT_EQ(render::resolveBackend(render::Backend::Auto, true, "gpu"), render::Backend::Rq);
    EXPECT_EQ(render::resolveBackend(render::Backend::Auto, false, "cpu"), render::Backend::Sw);
    try {
        render::resolveBackend(render::Backend::Rq, false, "lavapipe-old");
        FAIL() << "rq on a device without ray query must fail";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("lavapipe-old"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("VK_KHR_ray_query"), std::string::npos);
    }
}
