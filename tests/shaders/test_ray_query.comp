#version 460
// Ray-query probe for tests/gpu/acceleration_structure_test.cpp. One ray per invocation, stored as
// (origin, tMin), (direction, tMax). Every AABB candidate's box is read from `boxes` (6 floats per
// primitive: min xyz, max xyz; not necessarily the data the structure was built from) and kept by `mode`:
//   0 point:   the closed box contains the origin
//   1 segment: the closed slab interval of the box overlaps [tMin, tMax]
//   2 nearest: rayQueryGenerateIntersectionEXT(entry) for each box overlapping [tMin, tMax] over a
//              positive length whose entry is nearer than the last generated one
// mode | 4: also skip boxes whose minX < maxX fails (NaN minX or zero width: culled markers).
// Output per ray, 2 + maxOut uints: modes 0/1 [kept, candidates, kept prims (first maxOut)];
// mode 2 [committed generated ? 1 : 0, candidates, committed prim, floatBits(committed t)].
#extension GL_EXT_ray_query : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

layout(buffer_reference, scalar) readonly buffer BoxesRef { float v[]; };
layout(buffer_reference, scalar) readonly buffer RaysRef { vec4 v[]; };
layout(buffer_reference, scalar) buffer OutRef { uint v[]; };
#include "shared/test_push.h"
layout(push_constant, scalar) uniform Push { TestRayQueryPush tp; };
layout(local_size_x = 32) in;

// Closed slab interval (x, y) of box b along o + t d; empty when x > y. A zero direction
// component keeps every t if the origin lies in the closed slab, none otherwise.
vec2 slab(BoxesRef boxes, uint b, vec3 o, vec3 d) {
    const float inf = uintBitsToFloat(0x7f800000u);
    vec2 s = vec2(-inf, inf);
    for (int a = 0; a < 3; ++a) {
        float lo = boxes.v[6u * b + uint(a)], hi = boxes.v[6u * b + 3u + uint(a)];
        if (d[a] == 0.0) {
            if (o[a] < lo || o[a] > hi) return vec2(1.0, 0.0);
        } else {
            float t0 = (lo - o[a]) / d[a], t1 = (hi - o[a]) / d[a];
            s = vec2(max(s.x, min(t0, t1)), min(s.y, max(t0, t1)));
        }
    }
    return s;
}

bool containsPoint(BoxesRef boxes, uint b, vec3 p) {
    vec3 lo = vec3(boxes.v[6u * b], boxes.v[6u * b + 1u], boxes.v[6u * b + 2u]);
    vec3 hi = vec3(boxes.v[6u * b + 3u], boxes.v[6u * b + 4u], boxes.v[6u * b + 5u]);
    return all(greaterThanEqual(p, lo)) && all(lessThanEqual(p, hi));
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= tp.rayCount) return;
    RaysRef rays = RaysRef(tp.rays);
    BoxesRef boxes = BoxesRef(tp.boxes);
    OutRef outs = OutRef(tp.results);
    vec4 o = rays.v[2u * i], d = rays.v[2u * i + 1u];
    uint base = i * (2u + tp.maxOut);

    rayQueryEXT q;
    rayQueryInitializeEXT(q, accelerationStructureEXT(tp.tlas), gl_RayFlagsNoneEXT, 0xFF, o.xyz, o.w, d.xyz, d.w);
    const uint mode = tp.mode & 3u;
    const bool skipFlat = (tp.mode & 4u) != 0u;
    uint kept = 0u, candidates = 0u;
    float nearest = d.w;
    while (rayQueryProceedEXT(q)) {
        if (rayQueryGetIntersectionTypeEXT(q, false) != gl_RayQueryCandidateIntersectionAABBEXT) continue;
        ++candidates;
        uint b = uint(rayQueryGetIntersectionPrimitiveIndexEXT(q, false));
        if (skipFlat && !(boxes.v[6u * b] < boxes.v[6u * b + 3u])) continue;
        bool keep;
        if (mode == 0u) {
            keep = containsPoint(boxes, b, o.xyz);
        } else {
            vec2 s = slab(boxes, b, o.xyz, d.xyz);
            float lo = max(s.x, o.w), hi = min(s.y, d.w);
            keep = lo <= hi;
            if (mode == 2u && lo < hi && lo < nearest) {
                rayQueryGenerateIntersectionEXT(q, lo);  // tMin <= lo < committed t: shrinks the query
                nearest = lo;
            }
        }
        if (keep && mode != 2u) {
            if (kept < tp.maxOut) outs.v[base + 2u + kept] = b;
            ++kept;
        }
    }
    if (mode == 2u) {
        bool hit = rayQueryGetIntersectionTypeEXT(q, true) == gl_RayQueryCommittedIntersectionGeneratedEXT;
        outs.v[base] = hit ? 1u : 0u;
        outs.v[base + 2u] = hit ? uint(rayQueryGetIntersectionPrimitiveIndexEXT(q, true)) : 0xFFFFFFFFu;
        outs.v[base + 3u] = floatBitsToUint(hit ? rayQueryGetIntersectionTEXT(q, true) : 0.0);
    } else {
        outs.v[base] = kept;
    }
    outs.v[base + 1u] = candidates;
}
