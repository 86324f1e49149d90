#include "render/display_pass.h"

#include "core/error.h"
#include "gpu/shader_library.h"
#include "shared/display_gpu.h"

namespace amrvk::render {

DisplayPass::DisplayPass(gpu::Context& ctx)
    : mPipeline(ctx, gpu::loadShader("display"), "display", sizeof(shared::DisplayPush)) {}

void DisplayPass::record(VkCommandBuffer cmd, uint64_t accumAddress, int srcWidth, int srcHeight,
                         const gpu::Buffer& target, int dstWidth, int dstHeight, float exposure) const {
    AMRVK_CHECK(srcWidth > 0 && srcHeight > 0 && dstWidth > 0 && dstHeight > 0, "internal: empty display size");
    AMRVK_CHECK(target.size() >= uint64_t(dstWidth) * uint64_t(dstHeight) * 4, "internal: display buffer too small");
    shared::DisplayPush push{accumAddress,     target.address(),         uint32_t(srcWidth), uint32_t(srcHeight),
                             uint32_t(dstWidth), uint32_t(dstHeight), exposure,           0};
    mPipeline.dispatch(cmd, &push, (uint32_t(dstWidth) + 7) / 8, (uint32_t(dstHeight) + 7) / 8);
}

}  // namespace amrvk::render
