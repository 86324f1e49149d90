#version 460
// The accumulated image as a window shows it: the per-pixel mean ((sumHi + sumLo) / count, in
// float: enough for 8 bits; pixels without a sample yet are black), scaled bilinearly from the
// render size to the picture's rectangle in the window (a preview rendered smaller is magnified),
// times the exposure, clamped, sRGB encoded to 8 bits (the curve of core/image_io's encodeSrgb8)
// and packed for a B8G8R8A8_UNORM image. Window pixels outside the rectangle get clearColor.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "shared/display_gpu.h"
#include "shared/render_params.h"
layout(push_constant, scalar) uniform Push { DisplayPush pc; };
layout(buffer_reference, scalar) readonly buffer AccumRef { AccumPixelGpu v[]; };
layout(buffer_reference, scalar) buffer PixelsRW { uint v[]; };
layout(local_size_x = 8, local_size_y = 8) in;

vec3 meanAt(ivec2 p) {
    p = clamp(p, ivec2(0), ivec2(pc.srcWidth, pc.srcHeight) - 1);
    uint i = uint(p.y) * pc.srcWidth + uint(p.x);
    vec4 sum = AccumRef(pc.accum).v[i].sumHi + AccumRef(pc.accum).v[i].sumLo;
    return sum.w > 0.0 ? sum.rgb / sum.w : vec3(0.0);
}

// sRGB code 0..255 of a linear value clamped to [0, 1] (NaN -> 0). CPU twin: encodeSrgb8.
float encodeSrgb(float linear) {
    float c = linear > 0.0 ? min(linear, 1.0) : 0.0;
    float s = c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1.0 / 2.4) - 0.055;
    return floor(clamp(s, 0.0, 1.0) * 255.0 + 0.5);
}

void main() {
    uvec2 d = gl_GlobalInvocationID.xy;
    if (d.x >= pc.dstWidth || d.y >= pc.dstHeight) return;
    uint at = d.y * pc.dstWidth + d.x;
    if (d.x < pc.rectX || d.y < pc.rectY || d.x - pc.rectX >= pc.rectWidth || d.y - pc.rectY >= pc.rectHeight) {
        PixelsRW(pc.target).v[at] = pc.clearColor;
        return;
    }
    vec2 r = vec2(d - uvec2(pc.rectX, pc.rectY));
    vec2 src = (r + 0.5) * vec2(pc.srcWidth, pc.srcHeight) / vec2(pc.rectWidth, pc.rectHeight) - 0.5;
    ivec2 i0 = ivec2(floor(src));
    vec2 f = src - vec2(i0);
    vec3 c = mix(mix(meanAt(i0), meanAt(i0 + ivec2(1, 0)), f.x), mix(meanAt(i0 + ivec2(0, 1)), meanAt(i0 + ivec2(1, 1)), f.x),
                 f.y) * pc.exposure;
    uint cr = uint(encodeSrgb(c.r)), g = uint(encodeSrgb(c.g)), b = uint(encodeSrgb(c.b));
    PixelsRW(pc.target).v[at] = b | (g << 8) | (cr << 16) | (255u << 24);
}
