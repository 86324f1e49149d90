// The macrocell DDA: segments are contiguous, cover exactly the ray's overlap with the grid, and
// visit exactly the macrocells a brute-force point test finds along the ray (double precision),
// including the hard rays: axis-parallel with +0 and -0 components, rays in macrocell planes,
// through corners, starting inside the grid.
#include <gtest/gtest.h>

#include <random>

#include "accel/dda.h"

using namespace amrvk::accel;

namespace {

DdaGrid grid() { return {{-2.0, 1.0, 0.5}, {1.5, 2.0, 0.75}, {8, 5, 6}}; }

// Ray/box overlap computed independently (slab test in divisions, double; a ray in an upper face
// plane misses, as in accel/ray_box.h).
bool overlap(const DdaGrid& g, glm::dvec3 o, glm::dvec3 d, double& t0, double& t1) {
    glm::dvec3 lo = g.origin, hi = g.origin + g.cellSize * glm::dvec3(g.dims);
    t0 = 0;
    t1 = 1e30;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0) {
            if (o[a] < lo[a] || o[a] >= hi[a]) return false;
            continue;
        }
        double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
    }
    return t0 <= t1;
}

void checkRay(glm::dvec3 o, glm::dvec3 d, const char* what) {
    DdaGrid g = grid();
    auto segs = ddaSegments<double>(g, o, d, 0.0, 1e30);
    double e0, e1;
    bool hits = overlap(g, o, d, e0, e1);
    if (!hits) {
        EXPECT_TRUE(segs.empty()) << what;
        return;
    }
    ASSERT_FALSE(segs.empty()) << what;
    EXPECT_NEAR(segs.front().t0, e0, 1e-9) << what;
    EXPECT_NEAR(segs.back().t1, e1, 1e-9) << what;
    for (size_t i = 0; i < segs.size(); ++i) {
        EXPECT_LE(segs[i].t0, segs[i].t1) << what;
        if (i > 0) {
            EXPECT_EQ(segs[i].t0, segs[i - 1].t1) << what << " segment " << i;
        }
        // The segment's midpoint lies in (or on the boundary of) its macrocell.
        double tm = 0.5 * (segs[i].t0 + segs[i].t1);
        glm::dvec3 p = (o + d * tm - g.origin) / g.cellSize;
        uint32_t c = segs[i].cell;
        glm::ivec3 cell(int(c % 8), int(c / 8 % 5), int(c / 40));
        for (int a = 0; a < 3; ++a) {
            EXPECT_GE(p[a], cell[a] - 1e-9) << what << " axis " << a;
            EXPECT_LE(p[a], cell[a] + 1 + 1e-9) << what << " axis " << a;
        }
    }
}

}  // namespace

TEST(Dda, RandomRaysAreContiguousAndCovering) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1.0, 1.0), pos(-5.0, 15.0);
    for (int i = 0; i < 5000; ++i) {
        glm::dvec3 d(u(rng), u(rng), u(rng));
        if (glm::length(d) < 1e-3) continue;
        checkRay({pos(rng), pos(rng), pos(rng)}, glm::normalize(d), "random");
    }
}

TEST(Dda, AxisParallelRaysWithSignedZeros) {
    for (double zero : {0.0, -0.0}) {
        checkRay({-10.0, 2.3, 1.1}, {1.0, zero, zero}, "+x");
        checkRay({20.0, 2.3, 1.1}, {-1.0, zero, -zero}, "-x");
        checkRay({0.1, -10.0, 1.1}, {zero, 1.0, zero}, "+y");
        checkRay({0.1, 2.0, 10.0}, {zero, -zero, -1.0}, "-z");
    }
    auto segs = ddaSegments<double>(grid(), {-10.0, 2.3, 1.1}, {1.0, -0.0, 0.0}, 0.0, 1e30);
    EXPECT_EQ(segs.size(), 8u);  // one per macrocell along x
}

TEST(Dda, RaysInMacrocellPlanesAndThroughCorners) {
    // y = 3.0 and z = 2.0 are macrocell planes (origin 1.0 + 1 * 2.0; 0.5 + 2 * 0.75).
    checkRay({-10.0, 3.0, 2.0}, {1.0, 0.0, 0.0}, "in two planes");
    checkRay({-2.0, 1.0, 0.5}, glm::normalize(glm::dvec3(1.5, 2.0, 0.75)), "through corners");
    checkRay({10.0, 11.0, 5.0}, glm::normalize(glm::dvec3(-1.5, -2.0, -0.75)), "through corners backwards");
    checkRay({-2.0, 1.0, 0.5}, {0.0, 0.0, 1.0}, "along an edge");
}

TEST(Dda, CameraInsideTheGrid) {
    checkRay({3.0, 4.0, 2.2}, glm::normalize(glm::dvec3(0.3, -0.5, 0.8)), "inside");
    checkRay({3.0, 4.0, 2.0}, {0.0, 0.0, -1.0}, "inside on a plane");
    auto segs = ddaSegments<double>(grid(), {3.0, 4.0, 2.2}, {1.0, 0.0, 0.0}, 0.0, 1e30);
    ASSERT_FALSE(segs.empty());
    EXPECT_EQ(segs.front().t0, 0.0);
}

TEST(Dda, RespectsTMinAndTMax) {
    auto segs = ddaSegments<double>(grid(), {-10.0, 2.3, 1.1}, {1.0, 0.0, 0.0}, 9.0, 11.0);
    ASSERT_FALSE(segs.empty());
    EXPECT_EQ(segs.front().t0, 9.0);
    EXPECT_EQ(segs.back().t1, 11.0);
}
