// The GLSL DDA (majorant_dda.glsl) against its CPU twin (accel/dda.h) run in float: identical
// segment lists for random rays and for the hard rays (axis-parallel with +0/-0, rays in
// macrocell planes, through corners, starting inside the grid), and for walks started in a given
// macrocell (ddaStart, as grid-bvh resumes), and for grid-dda's walk that crosses blocks of
// inactive macrocells in one step (ddaNextSkipping).
#include <random>

#include "accel/dda.h"
#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu_fixture.h"
#include "shared/test_push.h"
#include "shared/render_params.h"

using namespace amrvk;

namespace {

// Rays as test_dda reads them without start cells: (origin, tMin), (direction, tMax).
struct RayList {
    std::vector<glm::vec4> v;
    void add(glm::vec3 o, glm::vec3 d, float tMin = 0.0f, float tMax = INFINITY) {
        v.emplace_back(o, tMin);
        v.emplace_back(d, tMax);
    }
    // Up to `count` rays in all: the rest random, from origins in [-5, 15]^3.
    void fillRandom(size_t count, unsigned seed) {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<float> u(-1.0f, 1.0f), pos(-5.0f, 15.0f);
        while (v.size() < 2 * count) {
            glm::vec3 d(u(rng), u(rng), u(rng));
            if (glm::length(d) > 1e-3f) add({pos(rng), pos(rng), pos(rng)}, glm::normalize(d));
        }
    }
};

}  // namespace

class DdaGpu : public test::GpuTest {
protected:
    // Runs test_dda over `rays` (2 vec4 per ray, or 3 with startCells) and compares every segment
    // with accel::ddaSegments (or ddaSegmentsFrom) in float; returns the mismatches (at most 11).
    // With blockShift > 0 the walk is ddaNextSkipping over `blockMajorants` (one per block).
    size_t compareWithTwin(const accel::DdaGrid& grid, const std::vector<glm::vec4>& rays, bool startCells,
                           int blockShift = 0, const std::vector<float>& blockMajorants = {}) {
        const uint32_t perRay = startCells ? 3 : 2;
        const uint32_t count = uint32_t(rays.size() / perRay), maxSegs = 64, stride = 1 + 3 * maxSegs;
        auto& c = ctx();
        shared::RenderParams p{};
        p.scene.gridDims = grid.dims;
        p.scene.gridOrigin = glm::vec3(grid.origin);
        p.scene.gridCellSize = glm::vec3(grid.cellSize);
        p.scene.gridBlockShift = uint32_t(blockShift);
        p.majorants.gridBlocks = blockShift > 0 ? 1u : 0u;
        // The macrocells' majorants (unread by the walk), then the blocks'.
        std::vector<float> majorants(size_t(grid.dims.x) * size_t(grid.dims.y) * size_t(grid.dims.z), 1.0f);
        majorants.insert(majorants.end(), blockMajorants.begin(), blockMajorants.end());
        gpu::Buffer majorantBuf = gpu::makeBuffer<float>(c, majorants, "majorants");
        p.majorants.gridMajorants = majorantBuf.address();
        gpu::Buffer params(c, sizeof p, gpu::MemoryKind::Device, "params");
        params.upload(&p, sizeof p);
        gpu::Buffer rayBuf = gpu::makeBuffer<glm::vec4>(c, rays, "rays");
        gpu::Buffer out(c, uint64_t(count) * stride * 4, gpu::MemoryKind::HostRead, "segments");
        gpu::ComputePipeline pipe(c, gpu::loadShader("test_dda"), "test_dda", sizeof(shared::TestDdaPush));
        shared::TestDdaPush push{params.address(), rayBuf.address(), out.address(), count,
                                 startCells ? 1u : blockShift > 0 ? 2u : 0u};
        auto blockActive = [&](uint32_t b) { return blockMajorants[b] > 0.0f; };
        c.submitAndWait([&](VkCommandBuffer cmd) { pipe.dispatch(cmd, &push, (count + 31) / 32); });
        auto got = out.download<float>();
        size_t mismatches = 0;
        for (uint32_t i = 0; i < count && mismatches <= 10; ++i) {
            glm::vec4 o = rays[perRay * i], d = rays[perRay * i + 1];
            auto cpu = startCells ? accel::ddaSegmentsFrom<float>(grid, glm::vec3(o), glm::vec3(d),
                                                                   glm::ivec3(glm::vec3(rays[perRay * i + 2])), o.w, d.w)
                       : blockShift > 0 ? accel::ddaSegmentsSkipping<float>(grid, blockShift, glm::vec3(o), glm::vec3(d),
                                                                           o.w, d.w, blockActive)
                                  : accel::ddaSegments<float>(grid, glm::vec3(o), glm::vec3(d), o.w, d.w);
            if (cpu.size() > maxSegs) cpu.resize(maxSegs);
            uint32_t n;
            std::memcpy(&n, &got[i * stride], 4);
            EXPECT_EQ(n, cpu.size()) << "ray " << i;
            if (n != cpu.size()) {
                ++mismatches;
                continue;
            }
            for (uint32_t k = 0; k < n; ++k) {
                uint32_t cell;
                std::memcpy(&cell, &got[i * stride + 1 + 3 * k], 4);
                float t0 = got[i * stride + 2 + 3 * k], t1 = got[i * stride + 3 + 3 * k];
                bool same = cell == cpu[k].cell && t0 == cpu[k].t0 && t1 == cpu[k].t1;
                mismatches += !same;
                EXPECT_TRUE(same) << "ray " << i << " segment " << k << ": gpu (" << cell << ", " << t0 << ", "
                                  << t1 << ") cpu (" << cpu[k].cell << ", " << cpu[k].t0 << ", " << cpu[k].t1 << ")";
                if (mismatches > 10) break;
            }
        }
        return mismatches;
    }
};

TEST_F(DdaGpu, SegmentsEqualTheCpuTwin) {
    accel::DdaGrid grid{{-2.0, 1.0, 0.5}, {1.5, 2.0, 0.75}, {8, 5, 6}};
    RayList rays;
    for (float z : {0.0f, -0.0f}) {
        rays.add({-10.0f, 2.3f, 1.1f}, {1.0f, z, z});
        rays.add({20.0f, 2.3f, 1.1f}, {-1.0f, z, -z});
        rays.add({0.1f, 2.0f, 10.0f}, {z, -z, -1.0f});
    }
    rays.add({-10.0f, 3.0f, 2.0f}, {1.0f, 0.0f, 0.0f});
    rays.add({-2.0f, 1.0f, 0.5f}, glm::normalize(glm::vec3(1.5f, 2.0f, 0.75f)));
    rays.add({3.0f, 4.0f, 2.2f}, glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f)));
    rays.add({-10.0f, 2.3f, 1.1f}, {1.0f, 0.0f, 0.0f}, 9.0f, 11.0f);
    rays.fillRandom(2000, 5);
    EXPECT_EQ(compareWithTwin(grid, rays.v, false), 0u);
}

// ddaStart, grid-bvh's resumption after a box query: the walk from a given macrocell at a given t
// equals the twin's, for the macrocell holding the point and for its neighbours (a point on a face
// rounds to either side).
TEST_F(DdaGpu, StartInAGivenMacrocellEqualsTheCpuTwin) {
    accel::DdaGrid grid{{-2.0, 1.0, 0.5}, {1.5, 2.0, 0.75}, {8, 5, 6}};
    std::vector<glm::vec4> rays;  // (origin, t), (direction, tMax), (macrocell, 0)
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), unit(0.0f, 1.0f);
    std::uniform_int_distribution<int> shift(-1, 1);
    const glm::vec3 lo(grid.origin), size(grid.cellSize);
    while (rays.size() < 3 * 2000) {
        glm::vec3 d(u(rng), u(rng), u(rng));
        if (glm::length(d) < 1e-3f) continue;
        d = glm::normalize(d);
        if (rays.size() % 7 == 0) d.y = (rays.size() % 2) ? 0.0f : -0.0f;  // never steps in y
        // A point inside the grid (every fifth on a macrocell face), reached at t = 4 from o.
        glm::vec3 p = lo + size * glm::vec3(grid.dims) * glm::vec3(unit(rng), unit(rng), unit(rng));
        if (rays.size() % 5 == 0) p.x = lo.x + size.x * float(1 + int(unit(rng) * 6.0f));
        const float t = 4.0f;
        const glm::vec3 o = p - d * t;
        glm::ivec3 cell = accel::ddaCellAt<float>(grid, o, d, t) + glm::ivec3(shift(rng), shift(rng), shift(rng));
        cell = glm::clamp(cell, glm::ivec3(0), grid.dims - 1);
        rays.emplace_back(o, t);
        rays.emplace_back(d, unit(rng) < 0.2f ? t + 3.0f * unit(rng) : INFINITY);
        rays.emplace_back(glm::vec3(cell), 0.0f);
    }
    EXPECT_EQ(compareWithTwin(grid, rays, true), 0u);
}

// grid-dda's walk over blocks (ddaNextSkipping): on a grid of 2 x 3 x 2 blocks of 4^3 macrocells
// (the last ones cut at the far faces), half of them inactive, the segment lists of random rays,
// axis-parallel ones with +0/-0 and rays in block planes equal the twin's in float.
TEST_F(DdaGpu, WalkAcrossBlocksEqualsTheCpuTwin) {
    const accel::DdaGrid grid{{-2.0, 1.0, 0.5}, {0.5, 0.75, 0.4}, {7, 11, 6}};
    const int shift = 2;
    const glm::ivec3 blocks = accel::ddaBlockDims(grid, shift);
    ASSERT_EQ(blocks, glm::ivec3(2, 3, 2));
    std::vector<float> blockMajorants(size_t(blocks.x * blocks.y * blocks.z));
    for (size_t b = 0; b < blockMajorants.size(); ++b) blockMajorants[b] = (b * 7 % 3 == 0) ? 0.0f : 0.5f;
    RayList rays;
    for (float z : {0.0f, -0.0f}) {
        rays.add({-10.0f, 2.3f, 1.1f}, {1.0f, z, z});
        rays.add({20.0f, 4.0f, 1.3f}, {-1.0f, z, -z});  // y = 4.0: a block plane
        rays.add({0.0f, 2.0f, 10.0f}, {z, -z, -1.0f});
    }
    rays.add({-2.0f, 1.0f, 0.5f}, glm::normalize(glm::vec3(3.5f, 8.25f, 2.4f)));  // from a corner
    rays.add({-10.0f, 2.3f, 1.1f}, {1.0f, 0.0f, 0.0f}, 9.0f, 11.0f);
    rays.fillRandom(3000, 11);
    EXPECT_EQ(compareWithTwin(grid, rays.v, false, shift, blockMajorants), 0u);
}
