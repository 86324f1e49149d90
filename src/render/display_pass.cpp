#include "render/display_pass.h"

#include "core/error.h"
#include "gpu/shader_library.h"
#include "shared/display_gpu.h"

namespace amrvk::render {

DisplayPass::DisplayPass(gpu::Context& ctx)
    : mPipeline(ctx, gpu::loadShader("display"), "display", sizeof(shared::DisplayPush)) {}

void DisplayPass::record(VkCommandBuffer cmd, uint64_t accumAddress, int srcWidth, int srcHeight,
                         const gpu::Buffer& target, const DisplayTarget& w, float exposure) const {
    AMRVK_CHECK(srcWidth > 0 && srcHeight > 0 && w.width > 0 && w.height > 0, "internal: empty display size");
    AMRVK_CHECK(w.rectX >= 0 && w.rectY >= 0 && w.rectWidth > 0 && w.rectHeight > 0 &&
                    w.rectX + w.rectWidth <= w.width && w.rectY + w.rectHeight <= w.height,
                "internal: display rectangle ", w.rectX, ",", w.rectY, " ", w.rectWidth, "x", w.rectHeight,
                " is empty or outside ", w.width, "x", w.height);
    AMRVK_CHECK(target.size() >= uint64_t(w.width) * uint64_t(w.height) * 4, "internal: display buffer too small");
    const shared::DisplayPush push{accumAddress,           target.address(),  uint32_t(srcWidth),
                                   uint32_t(srcHeight),    uint32_t(w.width), uint32_t(w.height),
                                   uint32_t(w.rectX),      uint32_t(w.rectY), uint32_t(w.rectWidth),
                                   uint32_t(w.rectHeight), exposure,          w.clearColor};
    mPipeline.dispatch(cmd, &push, (uint32_t(w.width) + 7) / 8, (uint32_t(w.height) + 7) / 8);
}

}  // namespace amrvk::render
