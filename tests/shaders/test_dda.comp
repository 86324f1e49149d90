#version 460
// Runs ddaInit (or ddaStart in a given macrocell) and ddaNext (or ddaNextSkipping over the
// params' block majorants) for one ray per invocation and
// writes up to kMaxSegs segments (cell, t0, t1) so tests/gpu/dda_gpu_test.cpp can compare them
// with the CPU twin.
#include "lib/common.glsl"
#include "lib/majorant_dda.glsl"
#include "shared/test_push.h"
layout(push_constant, scalar) uniform Push { TestDdaPush tp; };
layout(local_size_x = 32) in;
const uint kMaxSegs = 64u;
const uint kDdaEmptyBlock = 0xffffffffu;  // accel::kDdaEmptyBlock: the segment of a skipped block

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= tp.rayCount) return;
    gParams = ParamsRef(tp.params);
    Vec4Ref rays = Vec4Ref(tp.rays);
    uint stride = tp.startCells == 1u ? 3u : 2u;
    vec4 o = rays.v[stride * i], d = rays.v[stride * i + 1u];
    FloatRW out_ = FloatRW(tp.results);
    uint base = i * (1u + 3u * kMaxSegs);
    uint n = 0u;
    DdaState s;
    bool started = true;
    if (tp.startCells == 1u)
        ddaStart(o.xyz, d.xyz, ivec3(rays.v[stride * i + 2u].xyz), o.w, d.w, s);
    else
        started = ddaInit(o.xyz, d.xyz, o.w, d.w, s);
    if (started) {
        uint cell;
        float t0, t1;
        bool empty = false;
        while (n < kMaxSegs &&
               (tp.startCells == 2u ? ddaNextSkipping(o.xyz, d.xyz, s, cell, t0, t1, empty) : ddaNext(s, cell, t0, t1))) {
            out_.v[base + 1u + 3u * n] = uintBitsToFloat(empty ? kDdaEmptyBlock : cell);
            out_.v[base + 2u + 3u * n] = t0;
            out_.v[base + 3u + 3u * n] = t1;
            ++n;
        }
    }
    out_.v[base] = uintBitsToFloat(n);
}
