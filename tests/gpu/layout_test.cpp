// GPU layout conformance: the C++ and GLSL views of the shared structs agree on every offset.
#include <cstring>

#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu_fixture.h"
#include "shared/amr_gpu.h"
#include "shared/render_params.h"

using namespace amrvk;

namespace {
uint32_t bits(float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}
}  // namespace

class Layout : public test::GpuTest {};

TEST_F(Layout, SharedStructsMatchBetweenCppAndGlsl) {
    static_assert(offsetof(shared::RenderParams, bricks) % 8 == 0);
    shared::RenderParams p{};
    p.eye.x = 1.5f;
    p.dv.w = -2.25f;
    p.image = {640, 480, 7, 99};
    p.boundsLo.w = 0.125f;
    p.boundsHi.w = 1e4f;
    p.gridDims = {3, 4, 5, 0};
    p.gridCellSize.y = 6.5f;
    p.tfInfo.x = 17.0f;
    p.background.z = 0.75f;
    p.shading.x = -0.3f;
    p.lights[3].posOrDir.w = 1.0f;
    p.lights[7].radiance.y = 42.0f;

    auto& c = ctx();
    shared::BrickGpu bricks[2] = {{}, {{1, 2, 3, 4}, {5, 6, 7, 123456}}};
    shared::BvhNodeGpu nodes[2] = {{}, {{0, 0, 0}, 77u, {1, 2, 3.5f}, 3u}};
    shared::AbrGpu abrs[2] = {{}, {{0, 0, 0}, 11u, {9.5f, 0, 0}, 12u}};
    gpu::Buffer bb = gpu::makeBuffer<shared::BrickGpu>(c, bricks, "bricks");
    gpu::Buffer nb = gpu::makeBuffer<shared::BvhNodeGpu>(c, nodes, "nodes");
    gpu::Buffer ab = gpu::makeBuffer<shared::AbrGpu>(c, abrs, "abrs");
    p.bricks = 0x1122334455667788ull;
    p.gridMajorants = 0x99aabbccull;
    p.counters = 0xdeadbeef00000000ull;
    p.brickValues = bb.address();  // the shader reads BrickGpu[1] through this field
    p.samplerNodes = nb.address();
    p.abrs = ab.address();
    shared::AabbGpu boxes[2] = {{}, {{1, 2, 3.25f}, {4, 5.5f, 6}}};
    gpu::Buffer xb = gpu::makeBuffer<shared::AabbGpu>(c, boxes, "aabbs");
    p.domainBoxes = xb.address();
    p.samplerAccel = 0x0badf00dull;
    p.domainAccel = 0x1234567800000000ull;
    p.domainInfo = {31, 1, 0, 0};
    p.dvr.x = 0.375f;
    p.dvrLight.z = -0.5f;
    p.denseDims = {7, 8, 9, 2};
    p.denseOrigin.w = 4.0f;
    p.denseValues = 0xfeedface00000000ull;
    p.accum = 0x00000000c0ffee00ull;
    gpu::Buffer params(c, sizeof p, gpu::MemoryKind::Device, "params");
    params.upload(&p, sizeof p);
    gpu::Buffer out(c, 64 * 4, gpu::MemoryKind::HostRead, "out");
    gpu::ComputePipeline pipe(c, gpu::loadShader("test_layout"), "test_layout", 16);
    struct {
        uint64_t params, out;
    } push{params.address(), out.address()};
    c.submitAndWait([&](VkCommandBuffer cmd) { pipe.dispatch(cmd, &push, 1); });
    auto got = out.download<uint32_t>();
    std::vector<uint32_t> expect = {bits(1.5f), bits(-2.25f), 640, 99, bits(0.125f), bits(1e4f), 5,
                                    bits(6.5f), bits(17.0f), bits(0.75f), bits(-0.3f), bits(1.0f), bits(42.0f),
                                    0x55667788u, 0x11223344u, 0x99aabbccu, 0xdeadbeefu, 4, 123456, 77, 3,
                                    bits(3.5f), 11, 12, bits(9.5f), 0x0badf00du, 0x12345678u, 31, 1,
                                    bits(3.25f), bits(5.5f), bits(0.375f), bits(-0.5f), 2, bits(4.0f),
                                    0xfeedfaceu, 0xc0ffee00u};
    for (size_t i = 0; i < expect.size(); ++i) EXPECT_EQ(got[i], expect[i]) << "field " << i;
}
