// The display pass (passes/display.comp): the accumulated mean, tone mapped, as the 8-bit pixels a
// window shows (B8G8R8A8_UNORM swapchain images: bytes B, G, R, A; sRGB encoded in the shader).
#ifndef AMRVK_DISPLAY_GPU_H
#define AMRVK_DISPLAY_GPU_H
#include "interop.h"

AMRVK_NAMESPACE_BEGIN

struct DisplayPush {
    uint64_t accum;     // AccumPixelGpu[srcWidth * srcHeight] (render_params.h)
    uint64_t target;    // uint[dstWidth * dstHeight], row 0 = top: b | g << 8 | r << 16 | 255 << 24
    uint srcWidth;
    uint srcHeight;
    uint dstWidth;
    uint dstHeight;
    float exposure;     // linear radiance multiplier before the sRGB curve
    uint pad;
};
AMRVK_STATIC_ASSERT(sizeof(DisplayPush) == 40);
#ifdef __cplusplus
AMRVK_STATIC_ASSERT(offsetof(DisplayPush, accum) == 0);
AMRVK_STATIC_ASSERT(offsetof(DisplayPush, target) == 8);
AMRVK_STATIC_ASSERT(offsetof(DisplayPush, srcWidth) == 16);
AMRVK_STATIC_ASSERT(offsetof(DisplayPush, dstWidth) == 24);
AMRVK_STATIC_ASSERT(offsetof(DisplayPush, exposure) == 32);
#endif

AMRVK_NAMESPACE_END
#endif
