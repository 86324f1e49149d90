// Cut-aways (scene/cut_away.h): the kept interval of a ray against brute force (points stepped
// along the ray, each tested against the box and the planes directly), the world -> local voxel
// conversion the shaders get (a world point is kept exactly when its local voxel point satisfies the
// GPU form), and the one-line errors for bad crops and planes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "scene/cut_away.h"
#include "test_data.h"

using namespace amrvk;
using scene::ClipPlane;
using scene::CropBox;
using scene::CutAway;

namespace {

// Kept by the definition, written out independently of scene::keeps: inside the box on every axis
// and n . (p - q) <= 0 for every plane.
bool keptByDefinition(const CutAway& c, glm::dvec3 p) {
    if (c.crop)
        for (int a = 0; a < 3; ++a)
            if (p[a] < c.crop->lo[a] || p[a] > c.crop->hi[a]) return false;
    for (const ClipPlane& q : c.clips) {
        const glm::dvec3 r = p - q.point;
        if (q.normal.x * r.x + q.normal.y * r.y + q.normal.z * r.z > 0) return false;
    }
    return true;
}

CutAway randomCut(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    CutAway c;
    if (rng() % 3 != 0) {
        glm::dvec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
        c.crop = CropBox{glm::min(a, b) - 0.05, glm::max(a, b) + 0.05};
    }
    const int planes = int(rng() % (shared::kMaxClipPlanes + 1));
    for (int i = 0; i < planes; ++i) c.clips.push_back({{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}});
    return c;
}

}  // namespace

TEST(CutAway, KeptIntervalMatchesBruteForceAlongRandomRays) {
    std::mt19937 rng(2026);
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    int raysWithKeptPart = 0, raysMissing = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const CutAway cut = randomCut(rng);
        const glm::dvec3 o(u(rng), u(rng), u(rng));
        const glm::dvec3 d = glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)));
        double t0 = 0, t1 = 6;
        const bool any = scene::keptInterval(cut, o, d, t0, t1);
        // Every step of 1e-3 along [0, 6]: kept exactly inside [t0, t1], away from its ends.
        int inside = 0;
        for (int k = 0; k <= 6000; ++k) {
            const double t = k * 1e-3;
            const bool kept = keptByDefinition(cut, o + t * d);
            EXPECT_EQ(kept, scene::keeps(cut, o + t * d));
            if (any && std::abs(t - t0) < 1e-9 + 1e-12 * t) continue;
            if (any && std::abs(t - t1) < 1e-9 + 1e-12 * t) continue;
            const bool predicted = any && t > t0 && t < t1;
            ASSERT_EQ(kept, predicted) << "trial " << trial << " t " << t << " interval [" << t0 << ", " << t1 << "]";
            inside += kept;
        }
        (any ? raysWithKeptPart : raysMissing)++;
        if (any) {
            EXPECT_GT(inside, 0);
        }
    }
    // Both outcomes occur, so the comparison covered each.
    EXPECT_GT(raysWithKeptPart, 50);
    EXPECT_GT(raysMissing, 50);
}

TEST(CutAway, RayParallelToAPlaneIsKeptOnlyBehindIt) {
    CutAway c;
    c.clips.push_back({{0.0, 0.0, 0.5}, {0.0, 0.0, 2.0}});  // removes z > 0.5
    double t0 = 0, t1 = 10;
    EXPECT_TRUE(scene::keptInterval(c, {0, 0, 0.25}, {1, 0, 0}, t0, t1));
    EXPECT_EQ(t0, 0.0);
    EXPECT_EQ(t1, 10.0);
    t0 = 0, t1 = 10;
    EXPECT_FALSE(scene::keptInterval(c, {0, 0, 0.75}, {1, 0, 0}, t0, t1));
    // Crossing it: kept up to the plane going up, from it going down.
    t0 = 0, t1 = 10;
    EXPECT_TRUE(scene::keptInterval(c, {0, 0, 0}, {0, 0, 1}, t0, t1));
    EXPECT_DOUBLE_EQ(t1, 0.5);
    t0 = 0, t1 = 10;
    EXPECT_TRUE(scene::keptInterval(c, {0, 0, 1}, {0, 0, -1}, t0, t1));
    EXPECT_DOUBLE_EQ(t0, 0.5);
}

TEST(CutAway, GpuFormKeepsTheSameLocalVoxelPointsAsTheWorldCut) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    // Anisotropic and mirrored voxel spacing, a world offset and a local origin.
    const amr::Transform xf{{10.0, -4.0, 2.5}, {0.125, -0.25, 0.5}};
    const glm::dvec3 localOrigin(64.0, -32.0, 8.0);
    int kept = 0, removed = 0;
    for (int trial = 0; trial < 200; ++trial) {
        CutAway world = randomCut(rng);
        auto toWorld = [&](glm::dvec3 p) { return xf.origin + glm::dvec3(2.0) * p; };  // spread over +-2 around the origin
        if (world.crop) world.crop = CropBox{toWorld(world.crop->lo), toWorld(world.crop->hi)};
        for (ClipPlane& c : world.clips) c.point = toWorld(c.point);
        const shared::CutAwayGpu g = scene::cutAwayGpu(world, xf, localOrigin);
        EXPECT_EQ(g.planeCount, world.clips.size());
        EXPECT_EQ((g.flags & shared::kCutCrop) != 0, world.crop.has_value());
        for (int k = 0; k < 200; ++k) {
            const glm::dvec3 w = toWorld({u(rng), u(rng), u(rng)});
            const glm::dvec3 local = (w - xf.origin) / xf.scale - localOrigin;
            bool gpuKeeps = true;
            if (g.flags & shared::kCutCrop)
                for (int a = 0; a < 3; ++a) gpuKeeps = gpuKeeps && local[a] >= g.cropLo[a] && local[a] <= g.cropHi[a];
            for (uint32_t i = 0; i < g.planeCount; ++i)
                gpuKeeps = gpuKeeps && glm::dot(glm::dvec3(g.planes[i]), local) <= double(g.planes[i].w);
            const bool expected = keptByDefinition(world, w);
            // Float rounding of the GPU form may flip points within 1e-5 of a boundary; no others.
            bool nearBoundary = false;
            if (world.crop)
                for (int a = 0; a < 3; ++a)
                    nearBoundary |= std::abs(w[a] - world.crop->lo[a]) < 1e-5 || std::abs(w[a] - world.crop->hi[a]) < 1e-5;
            for (const ClipPlane& c : world.clips)
                nearBoundary |= std::abs(glm::dot(glm::normalize(c.normal), w - c.point)) < 1e-5;
            if (!nearBoundary) {
                EXPECT_EQ(gpuKeeps, expected) << "trial " << trial;
            }
            (expected ? kept : removed)++;
        }
    }
    EXPECT_GT(kept, 1000);
    EXPECT_GT(removed, 1000);
}

TEST(CutAway, BadCutsGiveOneLineErrors) {
    auto errorFor = [](const CutAway& c) { return test::errorOf([&] { scene::validateCutAway(c); }); };
    CutAway c;
    c.crop = CropBox{{0, 0, 0}, {1, 0, 1}};
    EXPECT_NE(errorFor(c).find("--crop: lower corner 0 is not below upper corner 0 on axis y"), std::string::npos)
        << errorFor(c);
    c.crop = CropBox{{0, 0, 0}, {1, 1, NAN}};
    EXPECT_NE(errorFor(c).find("--crop: corners must be finite"), std::string::npos);
    c = {};
    c.clips.push_back({{0, 0, 0}, {0, 0, 0}});
    EXPECT_NE(errorFor(c).find("--clip: the normal 0 0 0 points nowhere"), std::string::npos);
    c.clips.assign(shared::kMaxClipPlanes + 1, ClipPlane{});
    EXPECT_NE(errorFor(c).find("--clip: at most 4 planes (got 5)"), std::string::npos);
    c.clips.assign(1, ClipPlane{{0, INFINITY, 0}, {1, 0, 0}});
    EXPECT_NE(errorFor(c).find("--clip: point and normal must be finite"), std::string::npos);
    // A valid cut passes.
    c = {};
    c.crop = CropBox{{0, 0, 0}, {1, 1, 1}};
    c.clips.assign(shared::kMaxClipPlanes, ClipPlane{});
    EXPECT_NO_THROW(scene::validateCutAway(c));
}

// Issue 34, point 5: the normal's length overflowed (1e308, and 1e154 per component) or underflowed
// (1e-200), so the plane was ignored or refused as 0 0 0. Any finite non-zero normal cuts as its
// direction does: the same GPU plane, the same points kept, the same interval.
TEST(CutAway, HugeAndTinyNormalsCutAsTheirDirection) {
    const amr::Transform xf{{10.0, -4.0, 2.5}, {0.125, -0.25, 0.5}};
    const glm::dvec3 localOrigin(64.0, -32.0, 8.0), point(10.5, -4.5, 3.0);
    const glm::dvec3 o = point - glm::dvec3(0.3, 0.2, 0.1), d = glm::normalize(glm::dvec3(1.0, 2.0, 3.0));
    for (const glm::dvec3 direction : {glm::dvec3(1.0, 1.0, 1.0), glm::dvec3(1.0, -1.0, 0.0)}) {
        CutAway unit;
        unit.clips.push_back({point, direction});
        const shared::CutAwayGpu expected = scene::cutAwayGpu(unit, xf, localOrigin);
        double u0 = -10, u1 = 10;
        const bool unitAny = scene::keptInterval(unit, o, d, u0, u1);
        for (const double s : {1e308, 1e200, 1e154, 1e-154, 1e-200, 1e-300, 4.9e-324}) {
            CutAway c;
            c.clips.push_back({point, s * direction});
            EXPECT_NO_THROW(scene::validateCutAway(c)) << s;
            const shared::CutAwayGpu g = scene::cutAwayGpu(c, xf, localOrigin);
            EXPECT_TRUE(g.planes[0] == expected.planes[0]) << s;
            for (const glm::dvec3 p : {point + 0.1 * direction, point - 0.1 * direction})
                EXPECT_EQ(scene::keeps(c, p), scene::keeps(unit, p)) << s;
            double t0 = -10, t1 = 10;
            EXPECT_EQ(scene::keptInterval(c, o, d, t0, t1), unitAny) << s;
            EXPECT_DOUBLE_EQ(t0, u0) << s;
            EXPECT_DOUBLE_EQ(t1, u1) << s;
        }
    }
    // Only an exact zero (either sign) is refused.
    CutAway c;
    c.clips.push_back({{0, 0, 0}, {0.0, -0.0, 0.0}});
    EXPECT_NE(test::errorOf([&] { scene::validateCutAway(c); }).find("--clip: the normal 0 0 0 points nowhere"),
              std::string::npos);
}

TEST(CutAway, UnitNormalNeitherOverflowsNorUnderflows) {
    const double r = 1.0 / std::sqrt(3.0);
    for (const double s : {1.0, 1e308, 1.7e308, 1e154, 1e-200, 1e-300, 4.9e-324}) {
        const glm::dvec3 n = scene::unitNormal(glm::dvec3(s, -s, s));
        EXPECT_NEAR(n.x, r, 1e-15) << s;
        EXPECT_NEAR(n.y, -r, 1e-15) << s;
        EXPECT_NEAR(n.z, r, 1e-15) << s;
        EXPECT_NEAR(glm::length(n), 1.0, 1e-15) << s;
    }
    // Components of very different size: the largest sets the direction.
    EXPECT_EQ(scene::unitNormal({1e308, 1e-308, 0.0}), glm::dvec3(1.0, 0.0, 0.0));
    EXPECT_EQ(scene::unitNormal({0.0, 0.0, -1e-320}), glm::dvec3(0.0, 0.0, -1.0));
    EXPECT_EQ(scene::unitNormal({0.0, -0.0, 0.0}), glm::dvec3(0.0));
}

// keepsNothingOf (issue 52, point 7: two opposite clip planes gave a black picture without a
// word): known answers, then random cuts of the box [-1, 1]^3 against brute force over a 24^3
// lattice of points. A lattice point kept with room to spare proves the region is not empty; a
// region the function calls non-empty must hold a kept point near the lattice's resolution (its
// vertex is kept, checked by keptByDefinition). Both answers occur, so neither is assumed.
TEST(CutAway, KeepsNothingOfMatchesKnownRegionsAndBruteForce) {
    const glm::dvec3 lo(-1.0), hi(1.0);
    auto clip = [](glm::dvec3 p, glm::dvec3 n) { return ClipPlane{p, n}; };
    CutAway gap;  // x <= -0.2 and x >= 0.2: nothing
    gap.clips = {clip({-0.2, 0, 0}, {1, 0, 0}), clip({0.2, 0, 0}, {-1, 0, 0})};
    EXPECT_TRUE(scene::keepsNothingOf(gap, lo, hi));
    CutAway sheet;  // x <= 0.5 and x >= 0.5: a sheet of no volume
    sheet.clips = {clip({0.5, 0, 0}, {1, 0, 0}), clip({0.5, 0, 0}, {-1, 0, 0})};
    EXPECT_TRUE(scene::keepsNothingOf(sheet, lo, hi));
    CutAway slab = sheet;  // a slab 1e-6 thick is kept
    slab.clips[0].point.x += 1e-6;
    EXPECT_FALSE(scene::keepsNothingOf(slab, lo, hi));
    CutAway corner;  // x + y + z >= 2.9: a small corner near (1, 1, 1)
    corner.clips = {clip({0.97, 0.97, 0.97}, {-1, -1, -1})};
    EXPECT_FALSE(scene::keepsNothingOf(corner, lo, hi));
    corner.clips[0].point = glm::dvec3(1.01);  // x + y + z >= 3.03: beyond the corner
    EXPECT_TRUE(scene::keepsNothingOf(corner, lo, hi));
    CutAway outside;
    outside.crop = CropBox{{2, 2, 2}, {3, 3, 3}};
    EXPECT_TRUE(scene::keepsNothingOf(outside, lo, hi));
    EXPECT_FALSE(scene::keepsNothingOf(CutAway{}, lo, hi));

    std::mt19937 rng(11);
    int empty = 0, kept = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const CutAway c = randomCut(rng);
        bool found = false;
        const int n = 24;
        for (int i = 0; i < n && !found; ++i)
            for (int j = 0; j < n && !found; ++j)
                for (int k = 0; k < n && !found; ++k) {
                    const glm::dvec3 p = lo + (glm::dvec3(i, j, k) + 0.5) * (hi - lo) / double(n);
                    found = keptByDefinition(c, p);
                }
        const bool nothing = scene::keepsNothingOf(c, lo, hi);
        if (found) {
            EXPECT_FALSE(nothing) << "trial " << trial << ": a lattice point is kept";
        }
        if (!nothing && !found) {
            // Thinner than the lattice: its kept volume is real but small; the region grown by a
            // lattice step must hold a lattice point.
            CutAway grown = c;
            if (grown.crop) {
                grown.crop->lo -= 0.1;
                grown.crop->hi += 0.1;
            }
            for (ClipPlane& q : grown.clips) q.point += 0.1 * scene::unitNormal(q.normal);
            bool near = false;
            for (int i = 0; i < n && !near; ++i)
                for (int j = 0; j < n && !near; ++j)
                    for (int k = 0; k < n && !near; ++k)
                        near = keptByDefinition(grown, lo + (glm::dvec3(i, j, k) + 0.5) * (hi - lo) / double(n));
            EXPECT_TRUE(near) << "trial " << trial << ": called non-empty, nothing kept near";
        }
        nothing ? ++empty : ++kept;
    }
    EXPECT_GT(empty, 20);
    EXPECT_GT(kept, 20);
}
