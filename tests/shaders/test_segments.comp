#version 460
// Majorant segments of rays, as the tracker sees them: per ray r, out[r * stride] = segment count
// n (capped at maxSegments; the true count when larger), out[r * stride + 1] = traversal steps
// (traversalNext's count), then n records (id, majorant bits, t0 bits, t1 bits). Traversal and
// back-end come from the push constants. Built twice: test_segments (sw) and test_segments_rq
// (-DAMRVK_RAY_QUERY).
#ifdef AMRVK_RAY_QUERY
#extension GL_EXT_ray_query : require
#endif
#include "lib/common.glsl"
#include "lib/majorant_dda.glsl"
#include "lib/domain_traversal.glsl"
#include "lib/traversal.glsl"
// rays: vec4 (origin, tMin), vec4 (direction, tMax) per ray.
#include "shared/test_push.h"
layout(push_constant, scalar) uniform Push { TestSegmentsPush tp; };
layout(local_size_x = 32) in;

void main() {
    uint r = gl_GlobalInvocationID.x;
    if (r >= tp.count) return;
    gParams = ParamsRef(tp.params);
    vec4 o = Vec4Ref(tp.rays).v[2u * r], d = Vec4Ref(tp.rays).v[2u * r + 1u];
    StructureConfig cfg = StructureConfig(kSamplerExtBrick, tp.traversal, tp.backend);
    UintRW out_ = UintRW(tp.results);
    uint base = r * (2u + 4u * tp.maxSegments);
    uint n = 0u, steps = 0u;
    Traversal tr;
    if (traversalInit(cfg, o.xyz, d.xyz, o.w, d.w, tr)) {
        uint id;
        float maj, t0, t1;
        while (traversalNext(cfg, tr, steps, id, maj, t0, t1)) {
            if (n < tp.maxSegments) {
                uint k = base + 2u + 4u * n;
                out_.v[k] = id;
                out_.v[k + 1u] = floatBitsToUint(maj);
                out_.v[k + 2u] = floatBitsToUint(t0);
                out_.v[k + 3u] = floatBitsToUint(t1);
            }
            ++n;
        }
    }
    out_.v[base] = n;
    out_.v[base + 1u] = steps;
}
