// The display pass (passes/display.comp): the accumulated mean, tone mapped, as the 8-bit pixels a
// window shows (B8G8R8A8_UNORM swapchain images: bytes B, G, R, A; sRGB encoded in the shader), in a
// rectangle of the window (the viewer's picture area); the rest of the window gets one colour.
#ifndef AMRVK_DISPLAY_GPU_H
#define AMRVK_DISPLAY_GPU_H
#include "interop.h"

AMRVK_NAMESPACE_BEGIN

struct DisplayPush {
    uint64_t accum;     // AccumPixelGpu[srcWidth * srcHeight] (render_params.h)
    uint64_t target;    // uint[dstWidth * dstHeight], row 0 = top: b | g << 8 | r << 16 | 255 << 24
    uint srcWidth;
    uint srcHeight;
    uint dstWidth;      // the whole target (the window), pixels
    uint dstHeight;
    uint rectX;         // the picture's rectangle in the target: [rectX, rectX + rectWidth) x
    uint rectY;         // [rectY, rectY + rectHeight), inside dstWidth x dstHeight
    uint rectWidth;
    uint rectHeight;
    float exposure;     // linear radiance multiplier before the sRGB curve
    uint clearColor;    // the packed pixel written outside the rectangle (same byte order)
};
AMRVK_STATIC_ASSERT(sizeof(DisplayPush) == 56);
#ifdef __cplusplus
AMRVK_STATIC_ASSERT(offsetof(DisplayPush, accum) == 0);
AMRVK_STATIC_ASSERT(offsetof(DisplayPush, target) == 8);
AMRVK_STATIC_ASSERT(offsetof(DisplayPush, srcWidth) == 16);
AMRVK_STATIC_ASSERT(offsetof(DisplayPush, dstWidth) == 24);
AMRVK_STATIC_ASSERT(offsetof(DisplayPush, rectX) == 32);
AMRVK_STATIC_ASSERT(offsetof(DisplayPush, exposure) == 48);
AMRVK_STATIC_ASSERT(offsetof(DisplayPush, clearColor) == 52);
#endif

AMRVK_NAMESPACE_END
#endif
