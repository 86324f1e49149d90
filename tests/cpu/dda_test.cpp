// The macrocell DDA: segments are contiguous, cover exactly the ray's overlap with the grid, and
// visit exactly the macrocells a brute-force point test finds along the ray (double precision),
// including the hard rays: axis-parallel with +0 and -0 components, rays in macrocell planes,
// through corners, starting inside the grid.
#include <gtest/gtest.h>

#include <algorithm>
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

namespace {

// The plain walk's segments that lie in active blocks against the walk across blocks, both in
// double with zero-length slivers (corners and edges) dropped: the same macrocells in the same
// order with ends equal up to rounding (a walk restarted past a skipped block computes its planes
// afresh). Returns the rays that differ; adds up the steps of both walks.
template <typename Active, typename SkipActive>
int blockWalkMismatches(const DdaGrid& g, int shift, glm::dvec3 o, glm::dvec3 d, const Active& active,
                        const SkipActive& skipActive, uint64_t& plainSteps, uint64_t& skipSteps) {
    const glm::ivec3 blocks = ddaBlockDims(g, shift);
    auto blockOf = [&](uint32_t cell) {
        const glm::ivec3 c(int(cell % uint32_t(g.dims.x)), int(cell / uint32_t(g.dims.x) % uint32_t(g.dims.y)),
                           int(cell / uint32_t(g.dims.x * g.dims.y)));
        const glm::ivec3 b = c >> shift;
        return uint32_t(b.x + blocks.x * (b.y + blocks.y * b.z));
    };
    std::vector<DdaSegment<double>> want, got;
    const auto plain = ddaSegments<double>(g, o, d, 0.0, 1e30);
    plainSteps += plain.size();
    for (const auto& s : plain)
        if (active(blockOf(s.cell)) && s.t1 - s.t0 > 1e-12) want.push_back(s);
    const auto walk = ddaSegmentsSkipping<double>(g, shift, o, d, 0.0, 1e30, skipActive);
    skipSteps += walk.size();
    for (const auto& s : walk) {
        if (s.cell == kDdaEmptyBlock) continue;
        EXPECT_TRUE(active(blockOf(s.cell))) << "a segment inside an inactive block";
        if (s.t1 - s.t0 > 1e-12) got.push_back(s);
    }
    if (want.size() != got.size()) return 1;
    for (size_t i = 0; i < want.size(); ++i)
        if (want[i].cell != got[i].cell || std::abs(want[i].t0 - got[i].t0) > 1e-9 ||
            std::abs(want[i].t1 - got[i].t1) > 1e-9)
            return 1;
    return 0;
}

}  // namespace

// grid-dda's walk across blocks (ddaNextSkipping) keeps every segment of the plain walk inside an
// active block and nothing else, for random rays and the hard ones (axis-parallel with +0/-0, in
// block planes, through block corners, from inside), on grids whose far blocks are cut, in far
// fewer steps; and the comparison has power: a walk that skips one active block is caught.
TEST(Dda, WalkAcrossBlocksKeepsEveryActiveSegment) {
    const DdaGrid g{{-2.0, 1.0, 0.5}, {0.5, 0.75, 0.4}, {29, 17, 23}};
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> u(-1.0, 1.0), pos(-5.0, 20.0), unit(0.0, 1.0);
    for (int shift : {1, 2, 3}) {
        const glm::ivec3 blocks = ddaBlockDims(g, shift);
        std::vector<uint8_t> mask(size_t(blocks.x * blocks.y * blocks.z));
        for (uint8_t& m : mask) m = unit(rng) < 0.3;
        auto active = [&](uint32_t b) { return mask[b] != 0; };
        std::vector<std::pair<glm::dvec3, glm::dvec3>> rays;
        for (double zero : {0.0, -0.0}) {
            rays.push_back({{-10.0, 2.3, 1.1}, {1.0, zero, zero}});
            rays.push_back({{30.0, 1.0 + 0.75 * (1 << shift), 0.5 + 0.4 * (1 << shift)}, {-1.0, zero, -zero}});
            rays.push_back({{0.0, 2.0, 15.0}, {zero, -zero, -1.0}});
        }
        rays.push_back({{-2.0, 1.0, 0.5}, glm::normalize(glm::dvec3(0.5, 0.75, 0.4))});  // block corners
        rays.push_back({{3.0, 6.0, 4.0}, glm::normalize(glm::dvec3(0.3, -0.5, 0.8))});    // from inside
        while (rays.size() < 4000) {
            glm::dvec3 d(u(rng), u(rng), u(rng));
            if (glm::length(d) > 1e-3) rays.push_back({{pos(rng), pos(rng), pos(rng)}, glm::normalize(d)});
        }
        uint64_t plainSteps = 0, skipSteps = 0;
        int mismatches = 0;
        for (const auto& [o, d] : rays)
            mismatches += blockWalkMismatches(g, shift, o, d, active, active, plainSteps, skipSteps);
        EXPECT_EQ(mismatches, 0) << "shift " << shift;
        EXPECT_LT(double(skipSteps), 0.8 * double(plainSteps)) << "shift " << shift;
        // Power: the walk told that one active block is inactive loses its segments.
        const uint32_t dropped = uint32_t(std::find(mask.begin(), mask.end(), uint8_t(1)) - mask.begin());
        ASSERT_LT(dropped, mask.size());
        auto wrong = [&](uint32_t b) { return b != dropped && mask[b] != 0; };
        int caught = 0;
        uint64_t p = 0, q = 0;
        for (const auto& [o, d] : rays) caught += blockWalkMismatches(g, shift, o, d, active, wrong, p, q);
        EXPECT_GT(caught, 0) << "shift " << shift;
    }
}
