#pragma once
// Dispatch helpers for the test kernels in tests/shaders whose results several tests compare.
#include <cstdint>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu/shader_library.h"
#include "scene/structure_config.h"
#include "shared/test_push.h"

namespace amrvk::test {

// sampleField at local-voxel points (xyz of each vec4) with the renderer's parameters:
// (value, weightSum, inside) per point. rq needs the test_sample_rq variant.
inline std::vector<float> sampleAt(gpu::Context& ctx, uint64_t paramsAddress, const std::vector<glm::vec4>& points,
                                   scene::SamplerKind sampler, scene::Backend backend) {
    const uint32_t n = uint32_t(points.size());
    gpu::Buffer in = gpu::makeBuffer<glm::vec4>(ctx, points, "points");
    gpu::Buffer out(ctx, uint64_t(n) * 12, gpu::MemoryKind::HostRead, "samples");
    const bool rq = backend == scene::Backend::Rq;
    gpu::ComputePipeline pipe(ctx, gpu::loadShader(rq ? "test_sample_rq" : "test_sample"), "test_sample",
                              sizeof(shared::TestSamplePush));
    shared::TestSamplePush push{paramsAddress, in.address(), out.address(), n, uint32_t(sampler), uint32_t(backend), 0};
    ctx.submitAndWait([&](VkCommandBuffer cmd) { pipe.dispatch(cmd, &push, (n + 31) / 32); });
    return out.download<float>();
}

}  // namespace amrvk::test
