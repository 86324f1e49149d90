#pragma once
// The display pass: the renderer's accumulated mean as 8-bit sRGB pixels for a window
// (passes/display.comp), scaled bilinearly into a rectangle of the window (the viewer's picture
// area, viewer/logic/viewer_layout.h) so a smaller preview fills it; the window's other pixels get
// one colour. Recorded into the caller's command buffer, before the copy into the swapchain image.
#include <vulkan/vulkan.h>

#include <cstdint>

#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu/context.h"

namespace amrvk::render {

// Where the picture goes in the target, in target pixels (row 0 = top), and what the rest gets.
struct DisplayTarget {
    int width = 0, height = 0;                                // the whole target
    int rectX = 0, rectY = 0, rectWidth = 0, rectHeight = 0;  // inside it, not empty
    uint32_t clearColor = 0xff000000u;                        // packed b | g << 8 | r << 16 | a << 24
};

class DisplayPass {
public:
    explicit DisplayPass(gpu::Context& ctx);
    // target: at least width x height uints (B, G, R, A bytes), row 0 = top.
    void record(VkCommandBuffer cmd, uint64_t accumAddress, int srcWidth, int srcHeight, const gpu::Buffer& target,
                const DisplayTarget& where, float exposure = 1.0f) const;
    // The picture over the whole target.
    void record(VkCommandBuffer cmd, uint64_t accumAddress, int srcWidth, int srcHeight, const gpu::Buffer& target,
                int dstWidth, int dstHeight, float exposure = 1.0f) const {
        record(cmd, accumAddress, srcWidth, srcHeight, target, {dstWidth, dstHeight, 0, 0, dstWidth, dstHeight},
               exposure);
    }

private:
    gpu::ComputePipeline mPipeline;
};

}  // namespace amrvk::render
