// Cut-aways on the GPU (scene/cut_away.h, lib/cut_away.glsl), proved two independent ways:
//  - analytic: a constant medium cut by a crop box and oblique clip planes has the transmittance
//    exp(-sigma x the length of each ray kept by the cut), the length found by brute force (points
//    stepped along the ray, each tested against the box and the planes), for every traversal;
//  - statistical: where the field does not change across the cut, a crop (or a clip plane) along
//    cell faces renders the same picture as the data with the cut cells removed (tile z-test), and
//    the same test rejects a cut one coarse cell off (its power).
#include <cmath>

#include "gpu_fixture.h"
#include "image_compare.h"
#include "render/renderer.h"
#include "render_fixtures.h"
#include "scene/camera.h"
#include "scene/cut_away.h"

using namespace amrvk;

namespace {

using CutAwayGpu = test::GpuTest;

// Tiles (x channels) whose mean differs from `expected` (exact, no variance) beyond the z-test
// (Sidak-corrected, family-wise alpha) plus absTol.
int tilesDifferingFrom(const scene::RenderOutput& o, const std::vector<glm::dvec3>& expected, int tile, double absTol) {
    const int w = o.mean.width, h = o.mean.height, tx = (w + tile - 1) / tile, ty = (h + tile - 1) / tile;
    const double z = test::sidakZ(1e-4, size_t(tx) * ty * 3);
    int failures = 0;
    for (int by = 0; by < ty; ++by)
        for (int bx = 0; bx < tx; ++bx)
            for (int c = 0; c < 3; ++c) {
                double m = 0, e = 0, var = 0;
                int n = 0;
                for (int y = by * tile; y < std::min(h, (by + 1) * tile); ++y)
                    for (int x = bx * tile; x < std::min(w, (bx + 1) * tile); ++x, ++n) {
                        const size_t i = size_t(y) * w + x;
                        m += o.mean.pixels[i][c];
                        e += expected[i][c];
                        var += test::sampleVariance(o, i, c) / o.spp;
                    }
                if (std::abs(m - e) / n > z * std::sqrt(var) / n + absTol) ++failures;
            }
    return failures;
}

// Expected ae radiance bg x T per pixel (4x4 sub-rays), T = exp(-sigma L), L = the length of the
// ray inside the data box [0, dims] (voxel space) and kept by `cut` (world), by 4000 midpoint steps.
std::vector<glm::dvec3> expectedAe(const scene::RenderSettings& s, const amr::Transform& xf, glm::dvec3 dims,
                                   double sigma, const scene::CutAway& cut, glm::dvec3 bg) {
    const scene::RayBasis rb = scene::makeRayBasis(s.camera, s.width, s.height, xf);
    std::vector<glm::dvec3> out(size_t(s.width) * s.height);
    for (int y = 0; y < s.height; ++y)
        for (int x = 0; x < s.width; ++x) {
            double sumT = 0;
            for (int k = 0; k < 16; ++k) {
                const glm::dvec3 d = glm::normalize(rb.dir00 + (x + (k % 4 + 0.5) / 4) * rb.du + (y + (k / 4 + 0.5) / 4) * rb.dv);
                // The ray's span over the data box, from each axis' slab (voxel space).
                double t0 = 0, t1 = 1e30;
                for (int a = 0; a < 3; ++a) {
                    if (d[a] == 0) continue;
                    double ta = (0 - rb.eye[a]) / d[a], tb = (dims[a] - rb.eye[a]) / d[a];
                    t0 = std::max(t0, std::min(ta, tb));
                    t1 = std::min(t1, std::max(ta, tb));
                }
                double kept = 0;
                if (t0 < t1) {
                    const int steps = 4000;
                    const double dt = (t1 - t0) / steps;
                    for (int j = 0; j < steps; ++j)
                        if (scene::keeps(cut, xf.toWorld(rb.eye + (t0 + (j + 0.5) * dt) * d))) kept += dt;
                }
                sumT += std::exp(-sigma * kept);
            }
            out[size_t(y) * s.width + x] = bg * (sumT / 16.0);
        }
    return out;
}

}  // namespace

TEST_F(CutAwayGpu, ConstantMediumHasTheTransmittanceOfTheKeptChord) {
    const glm::ivec3 dims(24);
    const amr::Transform xf{{1.0, 2.0, 3.0}, glm::dvec3(0.5)};
    const auto world = [&](glm::dvec3 voxel) { return xf.toWorld(voxel); };
    const double sigma = 0.08;  // per voxel: TF alpha 1 x density scale, level-0 cells
    const glm::dvec3 bg(1.0, 0.5, 0.25);

    scene::CutAway crop, planes, both;
    crop.crop = scene::CropBox{world({4.3, 2.0, 6.5}), world({19.6, 18.0, 22.0})};
    planes.clips = {{world({12, 12, 12}), {1.0, 1.0, 0.5}}, {world({8, 8, 8}), {-0.2, 0.3, -1.0}}};
    both.crop = crop.crop;
    both.clips = {planes.clips[0]};
    const std::pair<const char*, scene::CutAway> cuts[] = {{"crop", crop}, {"planes", planes}, {"crop+plane", both}};

    std::vector<scene::StructureConfig> configs;
    for (scene::TraversalKind t : scene::allTraversals()) {
        scene::StructureConfig c = test::gridDda(scene::SamplerKind::ExtBrick, "8");
        c.traversal = t;
        c.kdLeaves = 64;
        configs.push_back(c);
    }
    configs.push_back(test::gridDda(scene::SamplerKind::Dense, "8"));
    if (ctx().hasRayQuery()) {
        scene::StructureConfig c = test::gridDda(scene::SamplerKind::Abr, "8");
        c.traversal = scene::TraversalKind::Abr;
        c.backend = scene::Backend::Rq;
        configs.push_back(c);
    }

    amr::Model m = test::makeUniformBox(dims, 0, 1.0f);
    m.voxelToWorld = xf;
    scene::RenderSettings s;
    s.mode = scene::Mode::Ae;
    s.width = s.height = 32;
    s.ambient = bg;
    s.densityScale = sigma;
    s.camera = scene::defaultCamera(world(glm::dvec3(0)), world(glm::dvec3(dims)));
    for (const auto& [name, cut] : cuts) {
        const std::vector<glm::dvec3> expected = expectedAe(s, xf, glm::dvec3(dims), sigma, cut, bg);
        const std::vector<glm::dvec3> uncut = expectedAe(s, xf, glm::dvec3(dims), sigma, {}, bg);
        for (const scene::StructureConfig& config : configs) {
            auto r = test::makeRenderer(ctx(), m, config);
            r->setTransferFunction(test::constantTf(glm::vec3(0.0f), 1.0f));
            scene::RenderSettings cs = s;
            cs.cut = cut;
            const scene::RenderOutput o = r->render(cs, 64);
            EXPECT_EQ(o.stats.counter(shared::kCounterMajorantViolations), 0u);
            EXPECT_EQ(tilesDifferingFrom(o, expected, 4, 2e-3), 0) << name << " " << config.label();
            // Power: the picture of the uncut box is rejected.
            EXPECT_GT(tilesDifferingFrom(o, uncut, 4, 2e-3), 10) << name << " " << config.label();
        }
    }
}

namespace {

// [0, 32)^3 voxels: level-0 cells for x < 8, level-1 cells (width 2) beyond. The field depends on
// y and z only where the cell centre has 12 <= x <= 20, so it does not change across x = 16.
amr::Model twoLevelSlabModel(int removeFromX) {
    amr::Model m;
    m.source = "two-level-slab";
    m.format = "test";
    m.voxelToWorld = {{-1.0, 0.5, 2.0}, glm::dvec3(1.0 / 32.0)};
    std::vector<float> values;
    auto add = [&](glm::ivec3 lower, int level) {
        if (lower.x >= removeFromX) return;
        const double w = double(1 << level);
        const glm::dvec3 c = glm::dvec3(lower) + 0.5 * w;
        double v = 0.5 + 0.3 * std::sin(0.35 * c.y) * std::cos(0.25 * c.z);
        if (c.x < 12 || c.x > 20) v += 0.25 * std::sin(0.5 * c.x);
        m.cells.push_back({lower, level});
        values.push_back(float(v));
    };
    for (int z = 0; z < 32; ++z)
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 8; ++x) add({x, y, z}, 0);
    for (int z = 0; z < 32; z += 2)
        for (int y = 0; y < 32; y += 2)
            for (int x = 8; x < 32; x += 2) add({x, y, z}, 1);
    m.fields.push_back({"v", std::move(values)});
    m.availableFields = {"v"};
    return m;
}

}  // namespace

TEST_F(CutAwayGpu, CropAlongCellFacesEqualsTheDataWithTheCutCellsRemoved) {
    const amr::Transform xf = twoLevelSlabModel(32).voxelToWorld;
    const scene::TransferFunction tf({0.0f, 1.2f}, {glm::vec4(0.9f, 0.6f, 0.3f, 0.2f), glm::vec4(0.3f, 0.6f, 0.9f, 1.0f)},
                                     "two-node");
    scene::RenderSettings s;
    s.mode = scene::Mode::Ms;
    s.width = s.height = 40;
    s.densityScale = 0.15;
    s.ambient = glm::dvec3(0.4);
    s.lights.push_back({false, {0.6, 0.8, 1.0}, glm::dvec3(2.0)});
    s.camera.eye = xf.toWorld({70.0, 50.0, 45.0});
    s.camera.target = xf.toWorld({16.0, 16.0, 16.0});
    s.camera.up = {0.0, 0.0, 1.0};
    s.camera.fovYDegrees = 45.0;

    auto render = [&](const amr::Model& m, const scene::CutAway& cut, uint32_t seed) {
        auto r = test::makeRenderer(ctx(), m, test::gridDda(scene::SamplerKind::ExtBrick, "8"));
        r->setTransferFunction(tf);
        scene::RenderSettings cs = s;
        cs.cut = cut;
        cs.seed = seed;
        const scene::RenderOutput o = r->render(cs, 96);
        EXPECT_EQ(o.stats.counter(shared::kCounterMajorantViolations), 0u);
        return o;
    };
    const amr::Model whole = twoLevelSlabModel(32);
    scene::CutAway crop, clip;
    crop.crop = scene::CropBox{xf.toWorld({-1.0, -1.0, -1.0}), xf.toWorld({16.0, 33.0, 33.0})};
    clip.clips = {{xf.toWorld({16.0, 0.0, 0.0}), {1.0, 0.0, 0.0}}};
    const scene::RenderOutput removed = render(twoLevelSlabModel(16), {}, 11);
    const scene::RenderOutput cropped = render(whole, crop, 12);
    const scene::RenderOutput clipped = render(whole, clip, 13);
    test::expectSameImage(cropped, removed, 5, "crop-vs-removed");
    test::expectSameImage(clipped, removed, 5, "clip-vs-removed");
    // Power: one coarse cell column more (removed from x = 18) is told apart.
    const scene::RenderOutput removedLater = render(twoLevelSlabModel(18), {}, 14);
    EXPECT_GT(test::countDifferingTiles(cropped, removedLater, 5, 1e-4, 1e-6), 0);
}
