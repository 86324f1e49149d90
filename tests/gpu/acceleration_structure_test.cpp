// AabbAccelerationStructure + VK_KHR_ray_query (tests/shaders/test_ray_query.comp), each result
// checked against brute force over all boxes on the CPU: point queries (closed containment),
// segment candidates, nearest entry through rayQueryGenerateIntersectionEXT, culling by NaN minX
// with rebuilds (and the zero-width alternative), the empty structure, memory accounting and the
// error without ray queries. Boxes are AMR-brick-like: coordinates in [0, 1000] on a 0.5 grid, some
// sharing faces exactly, some overlapping. Fixed seeds. Lines starting "[ rq" report driver behaviour.
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <set>

#include "core/error.h"
#include "gpu/acceleration_structure.h"
#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu_fixture.h"
#include "shared/test_push.h"

using namespace amrvk;

namespace {

using Box = VkAabbPositionsKHR;
static_assert(sizeof(Box) == 24);

float lo(const Box& b, int a) { return (&b.minX)[a]; }
float hi(const Box& b, int a) { return (&b.maxX)[a]; }
float& lo(Box& b, int a) { return (&b.minX)[a]; }
float& hi(Box& b, int a) { return (&b.maxX)[a]; }

struct Ray {
    glm::vec3 o;
    float tMin;
    glm::vec3 d;
    float tMax;
};
static_assert(sizeof(Ray) == 32);

constexpr uint32_t kBoxSeed = 20240611;
constexpr uint32_t kPoint = 0, kSegment = 1, kNearest = 2, kSkipFlat = 4;  // test_ray_query modes
constexpr double kTEps = 1e-2;  // t tolerance (voxel units) between float and double slab arithmetic
const glm::vec3 kDiagonal = glm::normalize(glm::vec3(1.0f, 0.7f, 0.4f));

// Random bricks, face-sharing neighbours and overlapping copies, all in [0, 1000] on a 0.5 grid.
std::vector<Box> makeBoxes(uint32_t seed) {
    std::mt19937 rng(seed);
    auto snap = [](float x) { return std::round(x * 2.0f) * 0.5f; };
    std::uniform_real_distribution<float> corner(0.0f, 900.0f), size(0.5f, 100.0f), unit(0.0f, 1.0f);
    std::vector<Box> boxes;
    for (int i = 0; i < 240; ++i) {
        Box b{};
        for (int a = 0; a < 3; ++a) {
            lo(b, a) = snap(corner(rng));
            hi(b, a) = std::min(1000.0f, lo(b, a) + std::max(0.5f, snap(size(rng))));
        }
        boxes.push_back(b);
    }
    for (int i = 0; i < 50; ++i) {  // neighbours sharing a face exactly (half of them partially)
        Box b = boxes[size_t(i) * 3];
        const int axis = i % 3, other = (axis + 1) % 3;
        const float s = std::max(0.5f, snap(size(rng)));
        if (hi(b, axis) + s <= 1000.0f) {
            lo(b, axis) = hi(b, axis);
            hi(b, axis) += s;
        } else {
            hi(b, axis) = lo(b, axis);
            lo(b, axis) -= s;
        }
        if (i % 2 && hi(b, other) + 10.0f <= 1000.0f) {
            lo(b, other) += 10.0f;
            hi(b, other) += 10.0f;
        }
        boxes.push_back(b);
    }
    for (int i = 0; i < 20; ++i) {  // overlapping: a copy shifted by up to half its size
        Box b = boxes[size_t(i) * 7 + 1];
        for (int a = 0; a < 3; ++a) {
            const float shift = snap((hi(b, a) - lo(b, a)) * 0.5f * unit(rng));
            if (hi(b, a) + shift <= 1000.0f) {
                lo(b, a) += shift;
                hi(b, a) += shift;
            }
        }
        boxes.push_back(b);
    }
    return boxes;
}

bool contains(const Box& b, glm::vec3 p) {
    for (int a = 0; a < 3; ++a)
        if (!(p[a] >= lo(b, a) && p[a] <= hi(b, a))) return false;
    return true;
}

// Exact (double) relation of a box to the segment [tMin, tMax] of a ray.
struct SegmentRelation {
    double lo = 1, hi = 0;   // closed slab interval clipped to [tMin, tMax]; empty when lo > hi
    bool interior = false;   // the open box meets the segment over a positive length
    bool grazesMax = false;  // the ray lies in the plane of a max face (zero direction component)
};

SegmentRelation relate(const Box& b, const Ray& r) {
    double t0 = -INFINITY, t1 = INFINITY;
    bool open = true, onMax = false;
    for (int a = 0; a < 3; ++a) {
        const double o = r.o[a], d = r.d[a], mn = lo(b, a), mx = hi(b, a);
        if (d == 0.0) {
            if (!(o >= mn && o <= mx)) return {};
            open = open && o > mn && o < mx;
            onMax = onMax || o == mx;
        } else {
            const double u = (mn - o) / d, v = (mx - o) / d;
            t0 = std::max(t0, std::min(u, v));
            t1 = std::min(t1, std::max(u, v));
        }
    }
    SegmentRelation s;
    s.lo = std::max(t0, double(r.tMin));
    s.hi = std::min(t1, double(r.tMax));
    s.interior = open && s.lo < s.hi;
    s.grazesMax = onMax;
    return s;
}

// must: the open box meets the segment over more than kTEps; may: within kTEps of the closed box.
bool mustReport(const SegmentRelation& s) { return s.interior && s.hi - s.lo > kTEps; }
bool mayReport(const SegmentRelation& s) { return s.hi - s.lo >= -kTEps; }

// Query points: random, the 27 corner/edge/face/centre points of every third box, and outside.
std::vector<glm::vec3> makePoints(const std::vector<Box>& boxes, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-20.0f, 1020.0f);
    std::vector<glm::vec3> pts;
    for (int i = 0; i < 1500; ++i) pts.emplace_back(u(rng), u(rng), u(rng));
    for (size_t b = 0; b < boxes.size(); b += 3)
        for (int c = 0; c < 27; ++c) {
            glm::vec3 p;
            for (int a = 0, k = c; a < 3; ++a, k /= 3)
                p[a] = k % 3 == 0 ? lo(boxes[b], a) : k % 3 == 2 ? hi(boxes[b], a) : 0.5f * (lo(boxes[b], a) + hi(boxes[b], a));
            pts.push_back(p);
        }
    for (glm::vec3 p : {glm::vec3(-10.0f), glm::vec3(1500.0f, 500.0f, 500.0f), glm::vec3(500.0f, -0.5f, 500.0f),
                        glm::vec3(1000.5f), glm::vec3(-0.0f)})
        pts.push_back(p);
    return pts;
}

std::vector<Ray> pointRays(const std::vector<glm::vec3>& pts, glm::vec3 dir, float tMax) {
    std::vector<Ray> rays;
    for (glm::vec3 p : pts) rays.push_back({p, 0.0f, dir, tMax});
    return rays;
}

// Segment rays: random (some with tMin > 0 or tMax 1e30), axis-parallel with +0/-0 components in the
// planes of min and max faces, segments ending exactly at a box entry, rays starting inside boxes,
// starting on a face (leaving, entering) and zero-length segments.
std::vector<Ray> makeSegmentRays(const std::vector<Box>& boxes, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), pos(-100.0f, 1100.0f), len(0.0f, 1500.0f), t0(0.0f, 300.0f);
    auto randomDir = [&] {
        glm::vec3 d;
        do d = glm::vec3(u(rng), u(rng), u(rng));
        while (glm::length(d) < 0.1f);
        return glm::normalize(d);
    };
    std::vector<Ray> rays;
    for (int i = 0; i < 1200; ++i) {
        const float tMin = i % 2 ? t0(rng) : 0.0f;
        const float tMax = i % 5 == 0 ? 1e30f : tMin + len(rng);
        rays.push_back({{pos(rng), pos(rng), pos(rng)}, tMin, randomDir(), tMax});
    }
    for (size_t k = 0; k < boxes.size(); k += 4) {
        const Box& b = boxes[k];
        const int a = int(k / 4) % 3, a1 = (a + 1) % 3, a2 = (a + 2) % 3;
        const float zero = k % 8 ? 0.0f : -0.0f;
        for (int side = 0; side < 2; ++side) {
            glm::vec3 o, d(zero);
            o[a] = side ? 1010.0f : -10.0f;
            d[a] = side ? -1.0f : 1.0f;
            o[a1] = side ? hi(b, a1) : lo(b, a1);  // in the plane of the a1 min (max) face
            o[a2] = k % 3 == 0 ? lo(b, a2) : 0.5f * (lo(b, a2) + hi(b, a2));
            rays.push_back({o, 0.0f, d, 1e30f});
            const float entry = side ? 1010.0f - hi(b, a) : lo(b, a) + 10.0f;
            rays.push_back({o, 0.0f, d, entry});  // ends exactly where it reaches the box
        }
        glm::vec3 centre, face;
        for (int j = 0; j < 3; ++j) centre[j] = face[j] = 0.5f * (lo(b, j) + hi(b, j));
        face[a] = hi(b, a);
        glm::vec3 out(zero), in(zero);
        out[a] = 1.0f;
        in[a] = -1.0f;
        rays.push_back({centre, 0.0f, randomDir(), 1e30f});
        rays.push_back({face, 0.0f, out, 50.0f});
        rays.push_back({face, 0.0f, in, 50.0f});
        rays.push_back({face, 2.0f, randomDir(), 2.0f});
    }
    return rays;
}

// Kept primitive lists (modes 0/1) as sets, with totals.
struct Gathered {
    std::vector<std::set<uint32_t>> sets;
    uint64_t candidates = 0, duplicates = 0, overflows = 0;
};

Gathered gather(const std::vector<uint32_t>& raw, size_t rays, uint32_t maxOut) {
    Gathered g;
    g.sets.resize(rays);
    for (size_t i = 0; i < rays; ++i) {
        const uint32_t* r = &raw[i * (2 + maxOut)];
        g.candidates += r[1];
        g.overflows += r[0] > maxOut;
        for (uint32_t k = 0; k < std::min(r[0], maxOut); ++k) g.duplicates += !g.sets[i].insert(r[2 + k]).second;
    }
    return g;
}

struct PointCheck {
    uint64_t expected = 0, found = 0, missingInterior = 0, missingBoundary = 0, extra = 0;
};

PointCheck checkPoints(const std::vector<Box>& boxes, const std::vector<bool>& active,
                       const std::vector<glm::vec3>& pts, const Gathered& g) {
    PointCheck c;
    for (size_t i = 0; i < pts.size(); ++i)
        for (uint32_t b = 0; b < boxes.size(); ++b) {
            const bool want = active[b] && contains(boxes[b], pts[i]), got = g.sets[i].count(b) > 0;
            c.expected += want;
            c.found += want && got;
            c.extra += got && !want;
            if (want && !got) {
                bool interior = true;
                for (int a = 0; a < 3; ++a) interior = interior && pts[i][a] > lo(boxes[b], a) && pts[i][a] < hi(boxes[b], a);
                ++(interior ? c.missingInterior : c.missingBoundary);
            }
        }
    return c;
}

struct SegmentCheck {
    uint64_t must = 0, found = 0, missing = 0, outside = 0;
    // Contacts that are neither must nor excluded, reported / total:
    uint64_t point[2]{}, grazeMin[2]{}, grazeMax[2]{}, thin[2]{};
    std::string firstError;
};

SegmentCheck checkSegments(const std::vector<Box>& boxes, const std::vector<bool>& active,
                           const std::vector<Ray>& rays, const Gathered& g) {
    SegmentCheck c;
    for (size_t i = 0; i < rays.size(); ++i)
        for (uint32_t b = 0; b < boxes.size(); ++b) {
            if (!active[b]) {
                if (g.sets[i].count(b) && c.firstError.empty()) c.firstError = strCat("culled box ", b, " reported");
                c.outside += g.sets[i].count(b);
                continue;
            }
            const SegmentRelation s = relate(boxes[b], rays[i]);
            const bool must = mustReport(s), may = mayReport(s), got = g.sets[i].count(b) > 0;
            c.must += must;
            c.found += must && got;
            c.missing += must && !got;
            c.outside += got && !may;
            if (may && !must && s.lo <= s.hi) {
                uint64_t* cat = s.lo == s.hi ? c.point : !s.interior ? (s.grazesMax ? c.grazeMax : c.grazeMin) : c.thin;
                cat[0] += got;
                ++cat[1];
            }
            if (((must && !got) || (got && !may)) && c.firstError.empty())
                c.firstError = strCat("ray ", i, " o (", rays[i].o.x, ", ", rays[i].o.y, ", ", rays[i].o.z, ") d (",
                                      rays[i].d.x, ", ", rays[i].d.y, ", ", rays[i].d.z, ") t [", rays[i].tMin, ", ",
                                      rays[i].tMax, "] box ", b, ": exact [", s.lo, ", ", s.hi, "] interior ",
                                      s.interior, ", gpu ", got);
        }
    return c;
}

// True on lavapipe older than Mesa 25.1. Seen on 25.0.7: its BVH builder lets a NaN minX (inactive
// AABB) into node bounds, where x86 min() returns its second operand when either is NaN, so an
// inactive right child poisons its parent and every active box below it is lost. That 25.1 fixes
// it is an assumption: on a newer lavapipe the strict test decides.
bool knownNanCullingBug(const gpu::DeviceReport& r) {
    if (r.driver.rfind("llvmpipe", 0) != 0) return false;
    const size_t at = r.driver.find("Mesa ");
    if (at == std::string::npos) return false;
    int major = 0, minor = 0;
    if (std::sscanf(r.driver.c_str() + at, "Mesa %d.%d", &major, &minor) != 2) return false;
    return major < 25 || (major == 25 && minor < 1);
}

class AccelerationStructure : public test::GpuTest {
protected:
    void SetUp() override {
        GpuTest::SetUp();
        if (!ctx().hasRayQuery()) GTEST_SKIP() << "device '" << ctx().deviceReport().name << "' has no VK_KHR_ray_query";
    }

    static gpu::Buffer aabbBuffer(const std::vector<Box>& boxes, const std::string& name) {
        gpu::Buffer b(ctx(), std::max<uint64_t>(boxes.size() * sizeof(Box), 16), gpu::MemoryKind::Device, name,
                      VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR);
        if (!boxes.empty()) b.upload(boxes.data(), boxes.size() * sizeof(Box));
        return b;
    }

    static gpu::AabbAccelerationStructure built(const gpu::Buffer& aabbs, uint32_t count, const std::string& name) {
        gpu::AabbAccelerationStructure as(ctx(), count, name);
        ctx().submitAndWait([&](VkCommandBuffer cmd) { as.build(cmd, aabbs); });
        return as;
    }

    static void rebuild(gpu::AabbAccelerationStructure& as, gpu::Buffer& aabbs, const std::vector<Box>& boxes) {
        aabbs.upload(boxes.data(), boxes.size() * sizeof(Box));
        ctx().submitAndWait([&](VkCommandBuffer cmd) { as.build(cmd, aabbs); });
    }

    // Runs test_ray_query in `mode` for every ray; returns 2 + maxOut uints per ray.
    static std::vector<uint32_t> query(const gpu::AabbAccelerationStructure& as, const gpu::Buffer& filterBoxes,
                                       const std::vector<Ray>& rays, uint32_t mode, uint32_t maxOut) {
        static gpu::ComputePipeline pipe(ctx(), gpu::loadShader("test_ray_query"), "test_ray_query",
                                         sizeof(shared::TestRayQueryPush));
        gpu::Buffer rayBuf(ctx(), rays.size() * sizeof(Ray), gpu::MemoryKind::Device, "rqRays");
        rayBuf.upload(rays.data(), rays.size() * sizeof(Ray));
        const uint32_t count = uint32_t(rays.size());
        gpu::Buffer out(ctx(), uint64_t(count) * (2 + maxOut) * 4, gpu::MemoryKind::HostRead, "rqOut");
        shared::TestRayQueryPush push{as.tlasAddress(), filterBoxes.address(), rayBuf.address(), out.address(),
                                      count, mode, maxOut, 0};
        ctx().submitAndWait([&](VkCommandBuffer cmd) { pipe.dispatch(cmd, &push, (count + 31) / 32); });
        return out.download<uint32_t>();
    }

    static Gathered points(const gpu::AabbAccelerationStructure& as, const gpu::Buffer& filter,
                           const std::vector<glm::vec3>& pts, uint32_t flags = 0) {
        return gather(query(as, filter, pointRays(pts, kDiagonal, 1e-30f), kPoint | flags, 32), pts.size(), 32);
    }
    static Gathered segments(const gpu::AabbAccelerationStructure& as, const gpu::Buffer& filter,
                             const std::vector<Ray>& rays, uint32_t flags = 0) {
        return gather(query(as, filter, rays, kSegment | flags, 128), rays.size(), 128);
    }
};

void printSegmentCheck(const char* what, size_t rays, const SegmentCheck& c, const Gathered& g) {
    std::printf("[ rq segment ] %s: %zu rays, must %llu found %llu; reported/total: point contacts %llu/%llu, "
                "grazing min face %llu/%llu, grazing max face %llu/%llu, overlap <= eps %llu/%llu; duplicates %llu, "
                "candidates %llu\n",
                what, rays, (unsigned long long)c.must, (unsigned long long)c.found, (unsigned long long)c.point[0],
                (unsigned long long)c.point[1], (unsigned long long)c.grazeMin[0], (unsigned long long)c.grazeMin[1],
                (unsigned long long)c.grazeMax[0], (unsigned long long)c.grazeMax[1], (unsigned long long)c.thin[0],
                (unsigned long long)c.thin[1], (unsigned long long)g.duplicates, (unsigned long long)g.candidates);
}

}  // namespace

// Point queries: a ray (p, any direction, tMin 0, tMax 1e-30) gathers the candidates and the shader
// keeps the boxes whose closed bounds contain p: equal to brute force, including p on faces, edges
// and corners. tMax 0 is reported but not required: lavapipe then drops boxes touching p.
TEST_F(AccelerationStructure, PointQueriesEqualBruteForce) {
    const auto boxes = makeBoxes(kBoxSeed);
    const auto pts = makePoints(boxes, 7);
    gpu::Buffer aabbs = aabbBuffer(boxes, "rqAabbs");
    auto as = built(aabbs, uint32_t(boxes.size()), "rqPoint");
    const std::vector<bool> all(boxes.size(), true);
    struct Config {
        const char* name;
        glm::vec3 dir;
        float tMax;
        bool required;  // must equal brute force
    };
    const Config configs[] = {
        {"diagonal, tMax 1e-30", kDiagonal, 1e-30f, true},
        {"-diagonal, tMax 1e-30", -kDiagonal, 1e-30f, true},
        {"diagonal, tMax 1e-3", kDiagonal, 1e-3f, true},
        {"+x (+0, +0), tMax 1e-30", {1.0f, 0.0f, 0.0f}, 1e-30f, true},
        {"-z (-0, -0), tMax 1e-30", {-0.0f, -0.0f, -1.0f}, 1e-30f, true},
        {"diagonal, tMax 0", kDiagonal, 0.0f, false},
        {"+x (+0, +0), tMax 0", {1.0f, 0.0f, 0.0f}, 0.0f, false},
    };
    for (const Config& cfg : configs) {
        const uint32_t maxOut = 32;
        auto g = gather(query(as, aabbs, pointRays(pts, cfg.dir, cfg.tMax), kPoint, maxOut), pts.size(), maxOut);
        const PointCheck c = checkPoints(boxes, all, pts, g);
        std::printf("[ rq point   ] %-24s %zu points: containing pairs %llu, found %llu, missed interior %llu, "
                    "missed on the boundary %llu; duplicates %llu, candidates %llu\n",
                    cfg.name, pts.size(), (unsigned long long)c.expected, (unsigned long long)c.found,
                    (unsigned long long)c.missingInterior, (unsigned long long)c.missingBoundary,
                    (unsigned long long)g.duplicates, (unsigned long long)g.candidates);
        EXPECT_EQ(g.overflows, 0u) << cfg.name;
        EXPECT_EQ(c.extra, 0u) << cfg.name;
        EXPECT_EQ(c.missingInterior, 0u) << cfg.name;
        EXPECT_GT(c.expected, pts.size() / 2) << "too few containing boxes to mean anything";
        if (cfg.required) {
            EXPECT_EQ(c.found, c.expected) << cfg.name;
        }
    }
}

// Segment candidates: every box whose interior the segment crosses over a positive length is
// reported; the shader's closed-slab filter keeps nothing outside [tMin, tMax]. Contacts of zero
// length or in a face plane may go either way (counted in the report line).
TEST_F(AccelerationStructure, SegmentCandidatesCoverBruteForce) {
    const auto boxes = makeBoxes(kBoxSeed);
    const auto rays = makeSegmentRays(boxes, 11);
    gpu::Buffer aabbs = aabbBuffer(boxes, "rqAabbs");
    auto as = built(aabbs, uint32_t(boxes.size()), "rqSegment");
    const auto g = segments(as, aabbs, rays);
    const SegmentCheck c = checkSegments(boxes, std::vector<bool>(boxes.size(), true), rays, g);
    printSegmentCheck("all boxes", rays.size(), c, g);
    EXPECT_EQ(g.overflows, 0u);
    EXPECT_EQ(c.missing, 0u) << c.firstError;
    EXPECT_EQ(c.outside, 0u) << c.firstError;
    EXPECT_GT(c.must, rays.size() / 3) << "too few crossings to mean anything";
}

// rayQueryGenerateIntersectionEXT(entry) for each nearer box shrinks the query; the committed
// intersection is the nearest box entry of brute force (boxes crossed over a positive length).
TEST_F(AccelerationStructure, GenerateIntersectionFindsNearestEntry) {
    const auto boxes = makeBoxes(kBoxSeed);
    const auto rays = makeSegmentRays(boxes, 13);
    gpu::Buffer aabbs = aabbBuffer(boxes, "rqAabbs");
    auto as = built(aabbs, uint32_t(boxes.size()), "rqNearest");
    const uint32_t maxOut = 2;
    const auto raw = query(as, aabbs, rays, kNearest, maxOut);
    uint64_t hits = 0, candidates = 0, errors = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const uint32_t* r = &raw[i * (2 + maxOut)];
        candidates += r[1];
        float t;
        std::memcpy(&t, &r[3], 4);
        double nearest = INFINITY;  // over boxes that must be reported
        for (const Box& b : boxes)
            if (const SegmentRelation s = relate(b, rays[i]); mustReport(s)) nearest = std::min(nearest, s.lo);
        bool ok = r[0] == 0 ? std::isinf(nearest) : r[2] < boxes.size();
        if (r[0] != 0 && ok) {
            ++hits;  // the committed box may be any reportable box whose entry is the nearest
            const SegmentRelation s = relate(boxes[r[2]], rays[i]);
            ok = mayReport(s) && std::abs(s.lo - double(t)) <= kTEps && double(t) <= nearest + kTEps &&
                 t >= rays[i].tMin && t <= rays[i].tMax;
        }
        if (!ok && ++errors <= 5)
            ADD_FAILURE() << "ray " << i << " o (" << rays[i].o.x << ", " << rays[i].o.y << ", " << rays[i].o.z
                          << ") d (" << rays[i].d.x << ", " << rays[i].d.y << ", " << rays[i].d.z << ") t ["
                          << rays[i].tMin << ", " << rays[i].tMax << "]: gpu " << (r[0] ? "hit" : "miss") << " box "
                          << r[2] << " t " << t << ", brute-force nearest entry " << nearest;
    }
    const auto all = segments(as, aabbs, rays);
    std::printf("[ rq nearest ] %zu rays, %llu hits; candidates %llu with shrinking, %llu without\n", rays.size(),
                (unsigned long long)hits, (unsigned long long)candidates, (unsigned long long)all.candidates);
    EXPECT_EQ(errors, 0u);
    EXPECT_GT(hits, rays.size() / 4);
}

// minX = NaN makes a box inactive after a rebuild: never reported, even though the shader's filter
// (reading the unculled boxes) would keep it. Restoring the data and rebuilding brings every box
// back. Same structure, memory and address throughout.
TEST_F(AccelerationStructure, NanCulledBoxesAreNeverReported) {
    const auto boxes = makeBoxes(kBoxSeed);
    const auto pts = makePoints(boxes, 17);
    const auto rays = makeSegmentRays(boxes, 19);
    gpu::Buffer aabbs = aabbBuffer(boxes, "rqAabbs");
    const gpu::Buffer unculled = aabbBuffer(boxes, "rqUnculled");
    auto as = built(aabbs, uint32_t(boxes.size()), "rqCull");
    const uint64_t address = as.tlasAddress(), bytes = as.memoryBytes();
    const std::vector<bool> all(boxes.size(), true);
    const auto reference = segments(as, unculled, rays);

    std::vector<Box> culled = boxes;
    std::vector<bool> active(boxes.size(), true);
    for (size_t b = 1; b < boxes.size(); b += 2) {
        culled[b].minX = std::numeric_limits<float>::quiet_NaN();
        active[b] = false;
    }
    rebuild(as, aabbs, culled);
    auto gp = points(as, unculled, pts);
    auto gs = segments(as, unculled, rays);
    uint64_t culledReported = 0;
    for (const auto* sets : {&gp.sets, &gs.sets})
        for (const auto& s : *sets)
            for (uint32_t b : s) culledReported += !active[b];
    EXPECT_EQ(culledReported, 0u);
    const PointCheck pc = checkPoints(boxes, active, pts, gp);
    std::printf("[ rq culling ] NaN minX on odd boxes: point pairs %llu of %llu found, culled boxes reported %llu\n",
                (unsigned long long)pc.found, (unsigned long long)pc.expected, (unsigned long long)culledReported);

    rebuild(as, aabbs, boxes);
    const PointCheck back = checkPoints(boxes, all, pts, points(as, unculled, pts));
    EXPECT_EQ(back.found, back.expected);
    const auto restored = segments(as, unculled, rays);
    EXPECT_EQ(restored.sets, reference.sets) << "rebuilding the original data gives other segment sets";
    EXPECT_EQ(as.tlasAddress(), address);
    EXPECT_EQ(as.memoryBytes(), bytes);

    std::vector<Box> none = boxes;  // every box inactive: nothing at all
    for (Box& b : none) b.minX = std::numeric_limits<float>::quiet_NaN();
    rebuild(as, aabbs, none);
    EXPECT_EQ(segments(as, unculled, rays).candidates, 0u);
}

// The active boxes of a NaN-culled structure are all still found (Vulkan: inactive primitives do not
// affect the others). Fails on lavapipe of Mesa 25.0.7 (see knownNanCullingBug): skipped there
// with the measured loss, so an upgrade that fixes it makes this test strict again.
TEST_F(AccelerationStructure, NanCullingKeepsActiveBoxes) {
    const auto boxes = makeBoxes(kBoxSeed);
    const auto pts = makePoints(boxes, 17);
    const auto rays = makeSegmentRays(boxes, 19);
    gpu::Buffer aabbs = aabbBuffer(boxes, "rqAabbs");
    const gpu::Buffer unculled = aabbBuffer(boxes, "rqUnculled");
    auto as = built(aabbs, uint32_t(boxes.size()), "rqCullActive");
    uint64_t lostPairs = 0, lostCrossings = 0, pairs = 0, crossings = 0;
    std::string firstError;
    for (int pattern = 0; pattern < 3; ++pattern) {  // odd boxes, the last box only, the first half
        std::vector<Box> culled = boxes;
        std::vector<bool> active(boxes.size(), true);
        for (size_t b = 0; b < boxes.size(); ++b) {
            const bool cull = pattern == 0 ? b % 2 == 1 : pattern == 1 ? b + 1 == boxes.size() : b < boxes.size() / 2;
            if (!cull) continue;
            culled[b].minX = std::numeric_limits<float>::quiet_NaN();
            active[b] = false;
        }
        rebuild(as, aabbs, culled);
        const PointCheck pc = checkPoints(boxes, active, pts, points(as, unculled, pts));
        const SegmentCheck sc = checkSegments(boxes, active, rays, segments(as, unculled, rays));
        pairs += pc.expected;
        lostPairs += pc.expected - pc.found;
        crossings += sc.must;
        lostCrossings += sc.missing;
        EXPECT_EQ(pc.extra + sc.outside, 0u) << "pattern " << pattern << ": " << sc.firstError;
        if (firstError.empty() && sc.missing) firstError = strCat("pattern ", pattern, ": ", sc.firstError);
    }
    std::printf("[ rq culling ] active boxes lost after NaN culling: point pairs %llu of %llu, segment crossings "
                "%llu of %llu\n",
                (unsigned long long)lostPairs, (unsigned long long)pairs, (unsigned long long)lostCrossings,
                (unsigned long long)crossings);
    if ((lostPairs || lostCrossings) && knownNanCullingBug(ctx().deviceReport()))
        GTEST_SKIP() << "known lavapipe bug (" << ctx().deviceReport().driver << "): inactive AABBs poison BVH node "
                     << "bounds; lost " << lostPairs << " of " << pairs << " point pairs, " << lostCrossings << " of "
                     << crossings << " crossings. Cull with zero-width boxes instead (ZeroWidthCullingAlternative)";
    EXPECT_EQ(lostPairs, 0u);
    EXPECT_EQ(lostCrossings, 0u) << firstError;
}

// Portable alternative to NaN culling that works on lavapipe 25.0: a culled box becomes the
// zero-width point box at its min corner (still active, never crossed over a positive length) and
// the shader skips boxes with !(minX < maxX). Active boxes equal brute force; culled are never kept.
TEST_F(AccelerationStructure, ZeroWidthCullingAlternative) {
    const auto boxes = makeBoxes(kBoxSeed);
    const auto pts = makePoints(boxes, 29);
    const auto rays = makeSegmentRays(boxes, 31);
    std::vector<Box> culled = boxes;
    std::vector<bool> active(boxes.size(), true);
    for (size_t b = 1; b < boxes.size(); b += 2) {
        culled[b] = Box{boxes[b].minX, boxes[b].minY, boxes[b].minZ, boxes[b].minX, boxes[b].minY, boxes[b].minZ};
        active[b] = false;
    }
    gpu::Buffer aabbs = aabbBuffer(culled, "rqAabbs");
    const gpu::Buffer unculled = aabbBuffer(boxes, "rqUnculled");
    auto as = built(aabbs, uint32_t(boxes.size()), "rqZeroWidth");

    const auto gp = points(as, aabbs, pts, kSkipFlat);
    const PointCheck pc = checkPoints(boxes, active, pts, gp);
    EXPECT_EQ(pc.found, pc.expected);
    EXPECT_EQ(pc.extra, 0u);
    const auto gs = segments(as, aabbs, rays, kSkipFlat);
    const SegmentCheck sc = checkSegments(boxes, active, rays, gs);
    EXPECT_EQ(sc.missing, 0u) << sc.firstError;
    EXPECT_EQ(sc.outside, 0u) << sc.firstError;
    // Culled boxes still reach the shader as candidates, but only at their corner point.
    uint64_t culledCandidates = 0;
    for (const auto& s : segments(as, unculled, rays).sets)
        for (uint32_t b : s) culledCandidates += !active[b];
    std::printf("[ rq culling ] zero-width culling: point pairs %llu of %llu, crossings %llu of %llu; culled "
                "boxes reaching the shader on %llu ray segments\n",
                (unsigned long long)pc.found, (unsigned long long)pc.expected, (unsigned long long)sc.found,
                (unsigned long long)sc.must, (unsigned long long)culledCandidates);
}

// count == 0: a valid empty structure (top level with no instance) that shaders may trace.
TEST_F(AccelerationStructure, EmptyStructureIsTraceable) {
    auto& mem = ctx().memory();
    const uint64_t before = mem.currentBytes();
    {
        gpu::AabbAccelerationStructure as(ctx(), 0, "rqEmpty");
        EXPECT_TRUE(as.valid());
        EXPECT_NE(as.tlasAddress(), 0u);
        EXPECT_EQ(as.count(), 0u);
        const gpu::Buffer unused;  // the AABB buffer is not read when count == 0
        ctx().submitAndWait([&](VkCommandBuffer cmd) { as.build(cmd, unused); });
        const auto boxes = makeBoxes(kBoxSeed);
        const gpu::Buffer filter = aabbBuffer(boxes, "rqFilter");
        const auto g = segments(as, filter, makeSegmentRays(boxes, 23));
        EXPECT_EQ(g.candidates, 0u);
        EXPECT_GT(as.memoryBytes(), 0u);
        EXPECT_EQ(mem.perResource().count("rqEmpty.blas"), 0u);  // no bottom level at all
    }
    EXPECT_EQ(mem.currentBytes(), before);
}

// Memory: counted per name in ctx.memory(), equal to memoryBytes(), moved once, freed on destruction.
TEST_F(AccelerationStructure, MemoryIsAccountedAndMovable) {
    auto& mem = ctx().memory();
    const auto boxes = makeBoxes(kBoxSeed);
    const gpu::Buffer aabbs = aabbBuffer(boxes, "rqAabbs");
    const uint64_t before = mem.currentBytes();
    {
        gpu::AabbAccelerationStructure as(ctx(), uint32_t(boxes.size()), "rqMemory");
        uint64_t named = 0;
        const auto usage = mem.perResource();
        for (const char* suffix : {".blas", ".tlas", ".scratch", ".instances"}) {
            const auto it = usage.find(std::string("rqMemory") + suffix);
            ASSERT_NE(it, usage.end()) << suffix;
            EXPECT_GT(it->second.current, 0u) << suffix;
            named += it->second.current;
        }
        EXPECT_EQ(as.memoryBytes(), named);
        EXPECT_EQ(mem.currentBytes(), before + as.memoryBytes());
        EXPECT_GE(as.memoryBytes(), boxes.size() * sizeof(Box));

        const uint64_t address = as.tlasAddress(), bytes = as.memoryBytes();
        gpu::AabbAccelerationStructure moved = std::move(as);
        EXPECT_FALSE(as.valid());  // NOLINT(bugprone-use-after-move): the moved-from state is specified
        EXPECT_EQ(as.tlasAddress(), 0u);
        EXPECT_EQ(as.memoryBytes(), 0u);
        EXPECT_EQ(moved.tlasAddress(), address);
        EXPECT_EQ(moved.memoryBytes(), bytes);
        EXPECT_EQ(mem.currentBytes(), before + bytes);
        ctx().submitAndWait([&](VkCommandBuffer cmd) { moved.build(cmd, aabbs); });

        gpu::AabbAccelerationStructure assigned;
        assigned = std::move(moved);
        EXPECT_EQ(assigned.tlasAddress(), address);
        EXPECT_EQ(mem.currentBytes(), before + bytes);
    }
    EXPECT_EQ(mem.currentBytes(), before);
    EXPECT_EQ(mem.perResource().at("rqMemory.blas").current, 0u);
}

// Misuse gives one clear error: building a default-constructed structure, a too-short AABB buffer.
TEST_F(AccelerationStructure, MisuseIsReported) {
    gpu::AabbAccelerationStructure none;
    EXPECT_FALSE(none.valid());
    EXPECT_EQ(none.tlasAddress(), 0u);
    EXPECT_EQ(none.memoryBytes(), 0u);
    const gpu::Buffer small(ctx(), 24, gpu::MemoryKind::Device, "rqSmall",
                            VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR);
    gpu::AabbAccelerationStructure two(ctx(), 2, "rqTwo");
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
        EXPECT_THROW(none.build(cmd, small), Error);
        try {
            two.build(cmd, small);
            ADD_FAILURE() << "a 24-byte buffer for 2 boxes was accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("48 needed"), std::string::npos) << e.what();
        }
    });
}

// Without ray queries (here: a context that leaves them off), construction fails with one line
// naming the structure and the missing extension. Runs on any device.
TEST(AccelerationStructureNoRayQuery, ConstructionFailsClearly) {
    gpu::ContextOptions o;
    o.disableRayQuery = true;
    gpu::Context ctx(o);
    ASSERT_FALSE(ctx.hasRayQuery());
    try {
        gpu::AabbAccelerationStructure as(ctx, 16, "rqNoDevice");
        FAIL() << "constructed without ray-query support";
    } catch (const Error& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("rqNoDevice"), std::string::npos) << m;
        EXPECT_NE(m.find("VK_KHR_ray_query"), std::string::npos) << m;
    }
    EXPECT_EQ(ctx.memory().currentBytes(), 0u);
    EXPECT_EQ(ctx.validationErrors(), 0u) << ctx.lastValidationMessage();
}
