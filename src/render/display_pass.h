#pragma once
// The display pass: the renderer's accumulated mean as 8-bit sRGB pixels for a window
// (passes/display.comp), scaled bilinearly to the window size so a smaller preview fills it.
// Recorded into the caller's command buffer, before the copy into the swapchain image.
#include <vulkan/vulkan.h>

#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu/context.h"

namespace amrvk::render {

class DisplayPass {
public:
    explicit DisplayPass(gpu::Context& ctx);
    // target: at least dstWidth x dstHeight uints (B, G, R, A bytes), row 0 = top.
    void record(VkCommandBuffer cmd, uint64_t accumAddress, int srcWidth, int srcHeight, const gpu::Buffer& target,
                int dstWidth, int dstHeight, float exposure = 1.0f) const;

private:
    gpu::ComputePipeline mPipeline;
};

}  // namespace amrvk::render
