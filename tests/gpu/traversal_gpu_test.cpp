// Majorant traversals on the GPU (domain_traversal.glsl, traversal.glsl), checked against brute
// force over every box: segments are contiguous, front to back, cover the ray's overlap with the
// data, and each segment's majorant is the maximum over the active boxes containing its points;
// the sw and rq back-ends give bit-identical segments and reconstructed values; a TF edit that
// empties regions changes the traversal structure but never a reconstructed value. grid-bvh steps
// like grid-dda where every macrocell is active and skips culled runs between active ones.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <random>

#include "accel/brick_sampler.h"
#include "accel/dda.h"
#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu_fixture.h"
#include "kernels.h"
#include "model_fixtures.h"
#include "render/renderer.h"
#include "render_fixtures.h"
#include "scene/tf_presets.h"
#include "shared/render_params.h"
#include "shared/test_push.h"

using namespace amrvk;

namespace {

constexpr uint32_t kMaxSegments = 512;

struct Segment {
    uint32_t id;
    float maj, t0, t1;
};

struct Ray {
    glm::vec3 o;
    glm::vec3 d;
};

// Random rays through the data plus the hard cases of the DDA tests: axis-parallel rays on
// lattice planes (signed zero components), rays starting inside, on faces and at corners.
std::vector<Ray> testRays(glm::vec3 hi, uint32_t seed) {
    std::vector<Ray> rays;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < 160; ++i) {
        glm::vec3 target = hi * glm::vec3(u(rng), u(rng), u(rng));
        glm::vec3 dir = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) - 0.5f);
        rays.push_back({target - dir * (2.0f * glm::length(hi)), dir});
    }
    for (int i = 0; i < 40; ++i) {  // starting inside
        glm::vec3 o = hi * glm::vec3(u(rng), u(rng), u(rng));
        rays.push_back({o, glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) - 0.5f)});
    }
    const glm::vec3 c = glm::floor(hi * 0.5f);
    for (float s : {1.0f, -1.0f}) {
        rays.push_back({glm::vec3(-1.0f, c.y, c.z), glm::vec3(s, 0.0f, -0.0f)});
        rays.push_back({glm::vec3(c.x, c.y, 0.0f), glm::vec3(-0.0f, 0.0f, s)});
        rays.push_back({glm::vec3(0.0f, 0.0f, 0.0f), glm::normalize(glm::vec3(s, 1.0f, 1.0f))});
        rays.push_back({hi, glm::normalize(glm::vec3(-1.0f, -1.0f, s))});
        rays.push_back({glm::vec3(c.x, -5.0f, 8.0f), glm::vec3(0.0f, s, 0.0f)});
        rays.push_back({glm::vec3(c.x + 0.5f, c.y, -3.0f), glm::normalize(glm::vec3(0.0f, s, 1.0f))});
    }
    return rays;
}

// 48^3 finest cells, macrocells of 4^3 (--grid 12); macrocell (x, y, z) is chosen when
// chosen[x + 12 (y + 12 z)]. A chosen macrocell holds value 1 in its inner 2^3 cells, whose tent
// supports stay inside it; every other value is 0. Under chosenOnlyTf() exactly the chosen
// macrocells are active.
std::shared_ptr<const scene::Volume> chosenMacrocells(const std::vector<char>& chosen) {
    amr::Model m = test::makeUniformBox(glm::ivec3(48), 0, 0.0f);
    for (size_t i = 0; i < m.cells.size(); ++i) {
        const glm::ivec3 p = m.cells[i].lower, mc = p / 4, in = p % 4;
        const bool inner = glm::all(glm::greaterThanEqual(in, glm::ivec3(1))) && glm::all(glm::lessThanEqual(in, glm::ivec3(2)));
        if (inner && chosen[size_t(mc.x + 12 * (mc.y + 12 * mc.z))]) m.fields[0].values[i] = 1.0f;
    }
    return scene::makeVolume(std::move(m));
}

scene::TransferFunction chosenOnlyTf() {  // 0 up to 0.5
    return scene::TransferFunction({0.0f, 0.5f, 1.0f},
                                   {glm::vec4(1, 1, 1, 0), glm::vec4(1, 1, 1, 0), glm::vec4(1, 1, 1, 1)}, "chosen");
}

class TraversalGpu : public test::GpuTest {
protected:
    // Segments of every ray (rays in local voxel space, t in [0, inf)); `steps`, when given, gets
    // each ray's traversal steps (DDA steps plus box queries).
    std::vector<std::vector<Segment>> segments(render::Renderer& r, scene::Backend backend,
                                               const std::vector<Ray>& rays, std::vector<uint32_t>* steps = nullptr) {
        const bool rq = backend == scene::Backend::Rq;
        std::vector<glm::vec4> packed;
        for (const Ray& ray : rays) {
            packed.emplace_back(ray.o, 0.0f);
            packed.emplace_back(ray.d, INFINITY);
        }
        const uint32_t n = uint32_t(rays.size()), stride = 2 + 4 * kMaxSegments;
        gpu::Buffer in = gpu::makeBuffer<glm::vec4>(ctx(), packed, "rays");
        gpu::Buffer out(ctx(), uint64_t(n) * stride * 4, gpu::MemoryKind::HostRead, "segments");
        gpu::ComputePipeline pipe(ctx(), gpu::loadShader(rq ? "test_segments_rq" : "test_segments"), "test_segments",
                                  sizeof(shared::TestSegmentsPush));
        shared::TestSegmentsPush push{r.paramsAddress(), in.address(), out.address(), n,
                                      uint32_t(r.config().traversal), uint32_t(backend), kMaxSegments};
        ctx().submitAndWait([&](VkCommandBuffer cmd) { pipe.dispatch(cmd, &push, (n + 31) / 32); });
        auto raw = out.download<uint32_t>();
        std::vector<std::vector<Segment>> result(n);
        if (steps) steps->assign(n, 0u);
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t count = raw[size_t(i) * stride];
            if (steps) (*steps)[i] = raw[size_t(i) * stride + 1];
            EXPECT_LE(count, kMaxSegments) << "ray " << i;
            for (uint32_t k = 0; k < std::min(count, kMaxSegments); ++k) {
                Segment s;
                std::memcpy(&s, &raw[size_t(i) * stride + 2 + 4 * k], sizeof s);
                result[i].push_back(s);
            }
        }
        return result;
    }

    // grid-bvh at --grid 12 over a chosenMacrocells() volume under chosenOnlyTf(), querying after
    // `after` culled macrocells in a row.
    std::unique_ptr<render::Renderer> chosenGridBvh(const std::shared_ptr<const scene::Volume>& volume,
                                                    scene::Backend backend, uint32_t after) {
        scene::StructureConfig cfg;
        cfg.traversal = scene::TraversalKind::GridBvh;
        cfg.backend = backend;
        cfg.grid = "12";
        auto r = std::make_unique<render::Renderer>(ctx(), volume, cfg);
        r->setTransferFunction(chosenOnlyTf());
        r->setGridBvhQueryAfter(after);
        return r;
    }

    // Values (value, weightSum, inside) of the renderer's sampler at local points.
    std::vector<float> samples(render::Renderer& r, const std::vector<glm::vec4>& pts) {
        return test::sampleAt(ctx(), r.paramsAddress(), pts, r.config().sampler, r.config().backend);
    }
};

// Boxes of the traversal in local voxel space (double) with their GPU majorants.
struct BoxSet {
    std::vector<accel::BoxD> boxes;
    std::vector<float> maj;
};

BoxSet traversalBoxes(const render::Renderer& r) {
    BoxSet s;
    const scene::VolumeScene& scene = r.scene();
    if (scene.config().traversal == scene::TraversalKind::GridBvh ||
        scene.config().traversal == scene::TraversalKind::GridDda) {
        const accel::RangeGrid& g = *scene.grid;
        const glm::dvec3 o = scene.volume().toLocal(g.origin);
        for (int z = 0; z < g.dims.z; ++z)
            for (int y = 0; y < g.dims.y; ++y)
                for (int x = 0; x < g.dims.x; ++x)
                    s.boxes.push_back({o + glm::dvec3(x, y, z) * g.cellSize, o + glm::dvec3(x + 1, y + 1, z + 1) * g.cellSize});
        s.maj = r.downloadMajorants();
    } else {
        for (const auto& b : r.traversalBoxes()) s.boxes.push_back({glm::dvec3(b.lo), glm::dvec3(b.hi)});
        s.maj = r.downloadDomainMajorants();
    }
    return s;
}

// Brute force: max majorant over active boxes containing p, or -1 when p is within `eps` of a
// face of an active box (ambiguous in float) ; 0 when no active box contains p.
double bruteMajorant(const BoxSet& s, glm::dvec3 p, double eps) {
    double best = 0.0;
    for (size_t i = 0; i < s.boxes.size(); ++i) {
        if (!(s.maj[i] > 0.0f)) continue;
        const auto& b = s.boxes[i];
        const glm::dvec3 dlo = p - b.lo, dhi = b.hi - p;
        const double inner = std::min({dlo.x, dlo.y, dlo.z, dhi.x, dhi.y, dhi.z});
        if (std::abs(inner) <= eps) return -1.0;
        if (inner > 0) best = std::max(best, double(s.maj[i]));
    }
    return best;
}

// Rays whose segment lists differ from the reference's in any bit (the first three are reported).
size_t differingRays(const std::vector<std::vector<Segment>>& segs, const std::vector<std::vector<Segment>>& reference) {
    size_t diffs = 0;
    for (size_t i = 0; i < segs.size(); ++i) {
        bool same = segs[i].size() == reference[i].size();
        for (size_t k = 0; same && k < segs[i].size(); ++k)
            same = std::memcmp(&segs[i][k], &reference[i][k], sizeof(Segment)) == 0;
        if (!same && diffs++ < 3) ADD_FAILURE() << "ray " << i << ": sw and rq segments differ";
    }
    return diffs;
}

// The first back-end's segments become the reference; a later back-end's (rq after sw) must equal
// them bit for bit.
void expectSameAsFirstBackEnd(std::vector<std::vector<Segment>>& reference, std::vector<std::vector<Segment>> segs) {
    if (reference.empty())
        reference = std::move(segs);
    else
        EXPECT_EQ(differingRays(segs, reference), 0u);
}

// Checks one ray's segments against brute force; returns the number of faults reported.
int checkRay(const BoxSet& boxes, glm::dvec3 hi, const Ray& ray, const std::vector<Segment>& segs) {
    const glm::dvec3 o(ray.o), d(ray.d);
    // Clip to the data bounds [0, hi] in double.
    double tIn = 0.0, tOut = INFINITY;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0) {
            if (o[a] < 0.0 || o[a] > hi[a]) tOut = -1.0;
            continue;
        }
        double t0 = (0.0 - o[a]) / d[a], t1 = (hi[a] - o[a]) / d[a];
        tIn = std::max(tIn, std::min(t0, t1));
        tOut = std::min(tOut, std::max(t0, t1));
    }
    int faults = 0;
    auto fault = [&](const std::string& what) {
        if (faults++ < 3) ADD_FAILURE() << what;
    };
    const double eps = 1e-3 * (1.0 + glm::length(o) + std::abs(tOut < INFINITY ? tOut : 0.0));
    // Probes along the ray: inside a segment the majorant must equal brute force; outside every
    // segment no active box may contain the point.
    double prevEnd = -INFINITY;
    for (const Segment& s : segs) {
        if (!(s.t1 > s.t0)) fault("empty or reversed segment [" + std::to_string(s.t0) + ", " + std::to_string(s.t1) + "]");
        if (s.t0 < prevEnd) fault("segments overlap or go backwards");
        if (prevEnd > -INFINITY && s.t0 > prevEnd) {  // a gap: nothing active inside it
            const double m = bruteMajorant(boxes, o + d * (0.5 * (prevEnd + s.t0)), eps);
            if (m > 0.0) fault("gap at t " + std::to_string(prevEnd) + " hides a box with majorant " + std::to_string(m));
        }
        if (s.t1 - s.t0 > 4 * eps) {
            for (double f : {0.5, 0.25, 0.75}) {
                const double m = bruteMajorant(boxes, o + d * (s.t0 + f * (s.t1 - s.t0)), eps);
                if (m >= 0.0 && std::abs(m - s.maj) > 1e-7 * std::max(1.0, m))
                    fault("segment [" + std::to_string(s.t0) + ", " + std::to_string(s.t1) + "] majorant " +
                          std::to_string(s.maj) + ", brute force " + std::to_string(m));
            }
        }
        prevEnd = s.t1;
    }
    // Before the first and after the last segment: no active box within the data bounds.
    if (tOut > tIn + 4 * eps) {
        const double first = segs.empty() ? tOut : segs.front().t0, last = segs.empty() ? tOut : segs.back().t1;
        if (first > tIn + 2 * eps && bruteMajorant(boxes, o + d * (0.5 * (tIn + first)), eps) > 0.0)
            fault("an active box before the first segment");
        if (last < tOut - 2 * eps && bruteMajorant(boxes, o + d * (0.5 * (last + tOut)), eps) > 0.0)
            fault("an active box after the last segment");
    }
    // Every active box the ray crosses within the data bounds over more than 4 eps has the middle
    // of its crossing inside a segment (the probes above see only the middle of each gap).
    for (size_t i = 0; i < boxes.boxes.size(); ++i) {
        if (!(boxes.maj[i] > 0.0f)) continue;
        const accel::BoxD& b = boxes.boxes[i];
        double e = tIn, x = tOut;
        bool onFace = false;
        for (int a = 0; a < 3; ++a) {
            if (d[a] == 0.0) {
                onFace |= std::abs(o[a] - b.lo[a]) <= eps || std::abs(o[a] - b.hi[a]) <= eps;
                if (o[a] < b.lo[a] || o[a] >= b.hi[a]) x = -INFINITY;
                continue;
            }
            const double t0 = (b.lo[a] - o[a]) / d[a], t1 = (b.hi[a] - o[a]) / d[a];
            e = std::max(e, std::min(t0, t1));
            x = std::min(x, std::max(t0, t1));
        }
        if (onFace || !(x - e > 4 * eps)) continue;
        const double m = 0.5 * (e + x);
        if (std::none_of(segs.begin(), segs.end(), [&](const Segment& s) { return s.t0 - eps <= m && m <= s.t1 + eps; }))
            fault("active box " + std::to_string(i) + " crossed over [" + std::to_string(e) + ", " + std::to_string(x) +
                  "] lies in no segment");
    }
    return faults;
}

}  // namespace

TEST_F(TraversalGpu, SegmentsMatchBruteForceAndBothBackEnds) {
    const std::shared_ptr<const scene::Volume> volume = scene::makeVolume(test::makeThreeLevelCloud());
    const scene::TransferFunction tf = test::zeroBelowMiddleTf(*volume);  // many boxes empty (culled)
    for (scene::TraversalKind t : scene::allTraversals()) {
        if (t == scene::TraversalKind::GridDda) continue;  // tests/gpu/dda_gpu_test.cpp
        std::vector<std::vector<Segment>> reference;
        for (scene::Backend b : test::availableBackends(ctx())) {
            scene::StructureConfig cfg;
            cfg.traversal = t;
            cfg.backend = b;
            cfg.grid = "12";
            cfg.kdLeaves = 300;
            SCOPED_TRACE(cfg.label());
            render::Renderer r(ctx(), volume, cfg);
            r.setTransferFunction(tf);
            const BoxSet boxes = traversalBoxes(r);
            EXPECT_GT(r.activeTraversalBoxes(), 0u);
            EXPECT_LT(r.activeTraversalBoxes(), boxes.boxes.size()) << "the TF should empty some boxes";
            const glm::dvec3 hi(volume->bounds().upper - volume->bounds().lower);
            const std::vector<Ray> rays = testRays(glm::vec3(hi), 11);
            auto segs = segments(r, b, rays);
            size_t multi = 0;
            int faults = 0;
            for (size_t i = 0; i < rays.size() && faults < 10; ++i) {
                multi += segs[i].size() >= 2;
                faults += checkRay(boxes, hi, rays[i], segs[i]);
            }
            EXPECT_GT(multi, rays.size() / 10) << "rays should cross several boxes";
            expectSameAsFirstBackEnd(reference, segs);
        }
    }
}

// grid-dda crosses blocks of macrocells whose majorants are all 0 in one step: the block
// majorants are the max of their macrocells', some blocks are empty under a TF that is zero below
// the middle of the range, and the segments with majorant > 0 match brute force over the macrocells: no gap
// hides an active macrocell, every active macrocell a ray crosses lies in a segment.
TEST_F(TraversalGpu, GridDdaCrossesEmptyBlocksWithoutLosingAnActiveMacrocell) {
    const std::shared_ptr<const scene::Volume> volume = scene::makeVolume(test::makeThreeLevelCloud());
    const scene::TransferFunction tf = test::zeroBelowMiddleTf(*volume);
    scene::StructureConfig cfg;
    cfg.traversal = scene::TraversalKind::GridDda;
    cfg.grid = "32";
    render::Renderer r(ctx(), volume, cfg);
    r.setGridBlockUse(render::MajorantPass::GridBlockUse::Always);  // whatever the share of empty blocks
    r.setTransferFunction(tf);
    ASSERT_TRUE(r.majorantPass().gridBlocksUsed());
    const accel::RangeGrid& g = *r.scene().grid;
    const int shift = accel::ddaBlockShift(g.dims);
    ASSERT_GT(shift, 0) << "a grid of 32 has blocks";
    const glm::ivec3 blocks = accel::ddaBlockDims({.dims = g.dims}, shift);
    const std::vector<float> cells = r.downloadMajorants(), blockMaj = r.downloadBlockMajorants();
    ASSERT_EQ(blockMaj.size(), size_t(blocks.x) * size_t(blocks.y) * size_t(blocks.z));
    std::vector<float> want(blockMaj.size(), 0.0f);
    for (size_t i = 0; i < cells.size(); ++i) {
        const glm::ivec3 b = g.coordOf(i) >> shift;
        float& m = want[size_t(b.x) + size_t(blocks.x) * (size_t(b.y) + size_t(blocks.y) * size_t(b.z))];
        m = std::max(m, cells[i]);
    }
    EXPECT_EQ(blockMaj, want);
    const size_t empty = size_t(std::count(blockMaj.begin(), blockMaj.end(), 0.0f));
    EXPECT_GT(empty, 0u) << "the TF should empty some blocks";
    EXPECT_LT(empty, blockMaj.size());
    const BoxSet boxes = traversalBoxes(r);
    const glm::dvec3 hi(volume->bounds().upper - volume->bounds().lower);
    const std::vector<Ray> rays = testRays(glm::vec3(hi), 11);
    const auto segs = segments(r, scene::Backend::Sw, rays);
    size_t multi = 0;
    int faults = 0;
    for (size_t i = 0; i < rays.size() && faults < 10; ++i) {
        std::vector<Segment> active;  // what the tracker uses
        for (const Segment& s : segs[i])
            if (s.maj > 0.0f && s.t1 > s.t0) active.push_back(s);
        multi += active.size() >= 2;
        faults += checkRay(boxes, hi, rays[i], active);
    }
    EXPECT_GT(multi, rays.size() / 10) << "rays should cross several active macrocells";
}

// grid-bvh continues from the current macrocell: where every macrocell is active it is grid-dda's
// walk, bit for bit (a walk that queried its boxes per segment would end segments on the exact
// box faces, which the DDA's accumulated plane crossings round apart from).
TEST_F(TraversalGpu, GridBvhStepsLikeGridDdaWhereEveryMacrocellIsActive) {
    const std::shared_ptr<const scene::Volume> volume = scene::makeVolume(test::makeUniformBox(glm::ivec3(24), 0, 1.0f));
    const glm::dvec3 hi(volume->bounds().upper - volume->bounds().lower);
    const std::vector<Ray> rays = testRays(glm::vec3(hi), 5);
    scene::StructureConfig dda;
    dda.grid = "8";
    render::Renderer rd(ctx(), volume, dda);
    rd.setTransferFunction(test::constantTf(glm::vec3(1.0f), 1.0f));
    std::vector<std::vector<Segment>> expected = segments(rd, scene::Backend::Sw, rays);
    for (auto& segs : expected)  // grid-dda yields a start on a face as an empty segment; grid-bvh skips it
        std::erase_if(segs, [](const Segment& s) { return !(s.t1 > s.t0); });
    for (scene::Backend b : test::availableBackends(ctx())) {
        scene::StructureConfig cfg = dda;
        cfg.traversal = scene::TraversalKind::GridBvh;
        cfg.backend = b;
        SCOPED_TRACE(cfg.label());
        render::Renderer r(ctx(), volume, cfg);
        r.setTransferFunction(test::constantTf(glm::vec3(1.0f), 1.0f));
        ASSERT_EQ(r.activeTraversalBoxes(), 512u);
        const auto segs = segments(r, b, rays);
        size_t diffs = 0, crossings = 0;
        for (size_t i = 0; i < rays.size(); ++i) {
            crossings += expected[i].size();
            bool same = segs[i].size() == expected[i].size();
            for (size_t k = 0; same && k < segs[i].size(); ++k)
                same = std::memcmp(&segs[i][k], &expected[i][k], sizeof(Segment)) == 0;
            if (!same && diffs++ < 3) ADD_FAILURE() << "ray " << i << ": grid-bvh and grid-dda segments differ";
        }
        EXPECT_EQ(diffs, 0u);
        EXPECT_GT(crossings, 5 * rays.size()) << "rays should cross many macrocells";
    }
}

// Macrocells active or culled at random (half each), so rays alternate between runs of active
// macrocells (stepped by the DDA) and runs of culled ones (stepped, or skipped by one box query
// after gridBvhQueryAfter of them; 1: every run is queried): segments against brute force, and
// sw = rq bit for bit.
TEST_F(TraversalGpu, GridBvhSkipsCulledMacrocellsBetweenActiveOnes) {
    std::mt19937 rng(21);
    std::vector<char> chosen(12 * 12 * 12);
    for (char& c : chosen) c = char(rng() % 2);
    size_t chosenCount = 0;
    for (char c : chosen) chosenCount += c;
    const std::shared_ptr<const scene::Volume> volume = chosenMacrocells(chosen);
    const glm::dvec3 hi(volume->bounds().upper - volume->bounds().lower);
    const std::vector<Ray> rays = testRays(glm::vec3(hi), 17);
    for (uint32_t after : {1u, 4u, accel::kGridBvhQueryAfter}) {
        std::vector<std::vector<Segment>> reference;  // sw's segments
        for (scene::Backend b : test::availableBackends(ctx())) {
            SCOPED_TRACE(std::string(scene::backendName(b)) + ", query after " + std::to_string(after));
            const std::unique_ptr<render::Renderer> rp = chosenGridBvh(volume, b, after);
            render::Renderer& r = *rp;
            ASSERT_EQ(r.activeTraversalBoxes(), chosenCount);
            const BoxSet boxes = traversalBoxes(r);
            const auto segs = segments(r, b, rays);
            // Rays that skip a culled run between two segments, and rays that step from one active
            // macrocell straight into the next.
            size_t skipping = 0, stepping = 0;
            int faults = 0;
            for (size_t i = 0; i < rays.size() && faults < 10; ++i) {
                bool gap = false, step = false;
                for (size_t k = 1; k < segs[i].size(); ++k) {
                    gap |= segs[i][k].t0 > segs[i][k - 1].t1;
                    step |= segs[i][k].t0 == segs[i][k - 1].t1 && segs[i][k].id != segs[i][k - 1].id;
                }
                skipping += gap;
                stepping += step;
                faults += checkRay(boxes, hi, rays[i], segs[i]);
            }
            EXPECT_GT(skipping, rays.size() / 2) << "rays should skip culled macrocells";
            EXPECT_GT(stepping, rays.size() / 2) << "rays should step between active macrocells";
            expectSameAsFirstBackEnd(reference, segs);
        }
    }
}

// grid-bvh steps a culled run of L macrocells (L steps) while L < K = gridBvhQueryAfter, and
// otherwise steps K of them and skips the rest with one box query. Rays along the x axis through
// macrocell centres, both ways, over rows with culled runs of every length 1-11: the steps are
// counted exactly by a walk over the row on the host, and the segments (the row's active
// macrocells in order) do not depend on K.
TEST_F(TraversalGpu, GridBvhStepsShortCulledRunsAndQueriesLongOnes) {
    std::mt19937 rng(5);
    std::vector<char> chosen(12 * 12 * 12);
    for (char& c : chosen) c = char(rng() % 10 < 3);
    for (int x = 0; x < 12; ++x) chosen[size_t(x + 12 * (0 + 12 * 0))] = x == 0;  // a run of 11 to the far face
    size_t chosenCount = 0;
    for (char c : chosen) chosenCount += c;
    const std::shared_ptr<const scene::Volume> volume = chosenMacrocells(chosen);
    std::vector<Ray> rays;
    std::vector<std::vector<uint32_t>> rows;  // the macrocell ids each ray passes, in order
    for (int z = 0; z < 12; ++z)
        for (int y = 0; y < 12; ++y)
            for (int dir : {1, -1}) {
                const glm::vec3 c(0.0f, float(4 * y + 2), float(4 * z + 2));
                const glm::vec3 o = dir > 0 ? c - glm::vec3(1, 0, 0) : c + glm::vec3(49, 0, 0);  // outside
                rays.push_back({o, glm::vec3(float(dir), 0, 0)});
                std::vector<uint32_t>& row = rows.emplace_back();
                for (int k = 0; k < 12; ++k) row.push_back(uint32_t((dir > 0 ? k : 11 - k) + 12 * (y + 12 * z)));
            }
    // Host walk: a step per macrocell entered; the K-th culled one of a run adds a query that jumps
    // to the next active macrocell (or ends the ray).
    auto expectedSteps = [&](const std::vector<uint32_t>& row, uint32_t after) {
        uint32_t steps = 0, culled = 0;
        for (size_t k = 0; k < row.size(); ++k) {
            ++steps;
            if (chosen[row[k]]) {
                culled = 0;
                continue;
            }
            if (++culled < after) continue;
            ++steps;  // the query
            culled = 0;
            while (k + 1 < row.size() && !chosen[row[k + 1]]) ++k;
        }
        return steps;
    };
    size_t longRuns = 0;  // runs of 5 culled macrocells or more: where K = 5 makes a difference
    for (const auto& row : rows)
        for (size_t k = 0, run = 0; k < row.size(); ++k) {
            run = chosen[row[k]] ? 0 : run + 1;
            longRuns += run == 5;
        }
    EXPECT_GE(longRuns, 10u);
    // 11: only the longest runs are queried; the default (32 > 11 macrocells) never queries here.
    for (scene::Backend b : test::availableBackends(ctx()))
        for (uint32_t after : {1u, 2u, 5u, 11u, accel::kGridBvhQueryAfter}) {
            SCOPED_TRACE(std::string(scene::backendName(b)) + ", query after " + std::to_string(after));
            const std::unique_ptr<render::Renderer> rp = chosenGridBvh(volume, b, after);
            render::Renderer& r = *rp;
            ASSERT_EQ(r.activeTraversalBoxes(), chosenCount);
            std::vector<uint32_t> steps;
            const auto segs = segments(r, b, rays, &steps);
            size_t wrongSteps = 0, wrongSegments = 0;
            for (size_t i = 0; i < rays.size(); ++i) {
                std::vector<uint32_t> active, seen;
                for (uint32_t id : rows[i])
                    if (chosen[id]) active.push_back(id);
                for (const Segment& s : segs[i]) seen.push_back(s.id);
                if (seen != active && wrongSegments++ < 3)
                    ADD_FAILURE() << "ray " << i << ": segments are not the row's active macrocells";
                const uint32_t expected = expectedSteps(rows[i], after);
                if (steps[i] != expected && wrongSteps++ < 3)
                    ADD_FAILURE() << "ray " << i << ": " << steps[i] << " steps, expected " << expected;
            }
            EXPECT_EQ(wrongSegments, 0u);
            EXPECT_EQ(wrongSteps, 0u);
        }
}

TEST_F(TraversalGpu, SwAndRqReconstructIdenticalValues) {
    if (!ctx().hasRayQuery()) GTEST_SKIP() << "device has no VK_KHR_ray_query";
    const std::shared_ptr<const scene::Volume> volume = scene::makeVolume(test::makeThreeLevelCloud());
    for (scene::SamplerKind s : scene::allSamplers()) {
        std::vector<float> values[2];
        std::vector<glm::vec4> pts;
        for (scene::Backend b : {scene::Backend::Sw, scene::Backend::Rq}) {
            scene::StructureConfig cfg;
            cfg.sampler = s;
            cfg.backend = b;
            cfg.grid = "8";
            if (pts.empty()) {
                // Random points plus every corner, edge and face centre of each brick domain.
                std::mt19937 rng(3);
                const glm::dvec3 hi(volume->bounds().upper - volume->bounds().lower);
                std::uniform_real_distribution<double> u(0.0, 1.0);
                for (int i = 0; i < 4000; ++i) pts.emplace_back(glm::vec3(hi * glm::dvec3(u(rng), u(rng), u(rng))), 0.0f);
                for (const auto& box : accel::brickDomainBoxes(volume->bricks))
                    for (int k = 0; k < 27; ++k) {
                        glm::dvec3 f(k % 3 * 0.5, k / 3 % 3 * 0.5, k / 9 * 0.5);
                        pts.emplace_back(glm::vec3(box.lo + (box.hi - box.lo) * f - glm::dvec3(volume->localOrigin)), 0.0f);
                    }
            }
            render::Renderer r(ctx(), volume, cfg);
            r.setTransferFunction(scene::makePreset("ramp", volume->valueLo(), volume->valueHi()));
            values[b == scene::Backend::Rq] = samples(r, pts);
        }
        SCOPED_TRACE(scene::samplerName(s));
        ASSERT_EQ(values[0].size(), values[1].size());
        size_t diffs = 0, inside = 0;
        for (size_t i = 0; i < values[0].size(); i += 3) {
            inside += values[0][i + 2] != 0.0f;
            if (std::memcmp(&values[0][i], &values[1][i], 3 * sizeof(float)) != 0 && diffs++ < 5)
                ADD_FAILURE() << "point (" << pts[i / 3].x << ", " << pts[i / 3].y << ", " << pts[i / 3].z << "): sw "
                              << values[0][i] << "/" << values[0][i + 1] << ", rq " << values[1][i] << "/"
                              << values[1][i + 1];
        }
        EXPECT_EQ(diffs, 0u);
        EXPECT_GT(inside, values[0].size() / 6) << "most probes should lie in the medium";
    }
}

// Upstream shares geometry between traversal and sampling and returns empty bounds for boxes with
// majorant 0, so culled bricks vanish from reconstruction and values depend on the TF
// (exabrick-reference.md 3.3). Here only the traversal structure is culled.
using UpstreamBug_TfCulledSamplingBvh = TraversalGpu;
TEST_F(UpstreamBug_TfCulledSamplingBvh, EmptyingTheTfChangesTheStructureNotTheValues) {
    const std::shared_ptr<const scene::Volume> volume = scene::makeVolume(test::makeThreeLevelCloud());
    const amr::FieldStats& st = volume->fieldStats;
    const float q = st.minValue + 0.7f * (st.maxValue - st.minValue);
    const scene::TransferFunction full = scene::makePreset("ramp", st.minValue, st.maxValue);
    const scene::TransferFunction sparse({st.minValue, q, st.maxValue},
                                          {glm::vec4(1, 1, 1, 0), glm::vec4(1, 1, 1, 0), glm::vec4(1, 1, 1, 1)}, "top");
    std::vector<glm::vec4> pts;
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (const scene::StructureConfig& cfg : test::allStructureConfigs(ctx(), "10", 200)) {
        SCOPED_TRACE(cfg.label());
        if (pts.empty()) {
            const glm::dvec3 hi(volume->bounds().upper - volume->bounds().lower);
            for (int i = 0; i < 3000; ++i) pts.emplace_back(glm::vec3(hi * glm::dvec3(u(rng), u(rng), u(rng))), 0.0f);
        }
        render::Renderer r(ctx(), volume, cfg);
        r.setTransferFunction(full);
        const uint64_t activeFull = r.activeTraversalBoxes();
        const std::vector<float> before = samples(r, pts);
        r.setTransferFunction(sparse);
        const std::vector<float> after = samples(r, pts);
        if (cfg.traversal != scene::TraversalKind::GridDda) {
            EXPECT_LT(r.activeTraversalBoxes(), activeFull) << "the edit should cull boxes";
            EXPECT_GT(r.activeTraversalBoxes(), 0u);
        }
        EXPECT_EQ(std::memcmp(before.data(), after.data(), before.size() * sizeof(float)), 0)
            << "a TF edit changed reconstructed values";
    }
}
