// The GLSL DDA (majorant_dda.glsl) against its CPU twin (accel/dda.h) run in float: identical
// segment lists for random rays and for the hard rays (axis-parallel with +0/-0, rays in
// macrocell planes, through corners, starting inside the grid).
#include <random>

#include "accel/dda.h"
#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu_fixture.h"
#include "shared/test_push.h"
#include "shared/render_params.h"

using namespace amrvk;

class DdaGpu : public test::GpuTest {};

TEST_F(DdaGpu, SegmentsEqualTheCpuTwin) {
    accel::DdaGrid grid{{-2.0, 1.0, 0.5}, {1.5, 2.0, 0.75}, {8, 5, 6}};
    std::vector<glm::vec4> rays;  // (origin, tMin), (direction, tMax)
    auto add = [&](glm::vec3 o, glm::vec3 d, float tMin = 0.0f, float tMax = INFINITY) {
        rays.emplace_back(o, tMin);
        rays.emplace_back(d, tMax);
    };
    for (float z : {0.0f, -0.0f}) {
        add({-10.0f, 2.3f, 1.1f}, {1.0f, z, z});
        add({20.0f, 2.3f, 1.1f}, {-1.0f, z, -z});
        add({0.1f, 2.0f, 10.0f}, {z, -z, -1.0f});
    }
    add({-10.0f, 3.0f, 2.0f}, {1.0f, 0.0f, 0.0f});
    add({-2.0f, 1.0f, 0.5f}, glm::normalize(glm::vec3(1.5f, 2.0f, 0.75f)));
    add({3.0f, 4.0f, 2.2f}, glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f)));
    add({-10.0f, 2.3f, 1.1f}, {1.0f, 0.0f, 0.0f}, 9.0f, 11.0f);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), pos(-5.0f, 15.0f);
    while (rays.size() < 2 * 2000) {
        glm::vec3 d(u(rng), u(rng), u(rng));
        if (glm::length(d) > 1e-3f) add({pos(rng), pos(rng), pos(rng)}, glm::normalize(d));
    }
    const uint32_t count = uint32_t(rays.size() / 2), maxSegs = 64, stride = 1 + 3 * maxSegs;

    auto& c = ctx();
    shared::RenderParams p{};
    p.scene.gridDims = grid.dims;
    p.scene.gridOrigin = glm::vec3(grid.origin);
    p.scene.gridCellSize = glm::vec3(grid.cellSize);
    gpu::Buffer params(c, sizeof p, gpu::MemoryKind::Device, "params");
    params.upload(&p, sizeof p);
    gpu::Buffer rayBuf = gpu::makeBuffer<glm::vec4>(c, rays, "rays");
    gpu::Buffer out(c, uint64_t(count) * stride * 4, gpu::MemoryKind::HostRead, "segments");
    gpu::ComputePipeline pipe(c, gpu::loadShader("test_dda"), "test_dda", sizeof(shared::TestDdaPush));
    shared::TestDdaPush push{params.address(), rayBuf.address(), out.address(), count, 0};
    c.submitAndWait([&](VkCommandBuffer cmd) { pipe.dispatch(cmd, &push, (count + 31) / 32); });
    auto got = out.download<float>();
    size_t mismatches = 0;
    for (uint32_t i = 0; i < count; ++i) {
        glm::vec4 o = rays[2 * i], d = rays[2 * i + 1];
        auto cpu = accel::ddaSegments<float>(grid, glm::vec3(o), glm::vec3(d), o.w, d.w);
        uint32_t n;
        std::memcpy(&n, &got[i * stride], 4);
        ASSERT_EQ(n, cpu.size()) << "ray " << i;
        for (uint32_t k = 0; k < n; ++k) {
            uint32_t cell;
            std::memcpy(&cell, &got[i * stride + 1 + 3 * k], 4);
            float t0 = got[i * stride + 2 + 3 * k], t1 = got[i * stride + 3 + 3 * k];
            bool same = cell == cpu[k].cell && t0 == cpu[k].t0 && t1 == cpu[k].t1;
            mismatches += !same;
            EXPECT_TRUE(same) << "ray " << i << " segment " << k << ": gpu (" << cell << ", " << t0 << ", "
                              << t1 << ") cpu (" << cpu[k].cell << ", " << cpu[k].t0 << ", " << cpu[k].t1 << ")";
            if (mismatches > 10) return;
        }
    }
}
