#version 460
// Evaluates sampleField at given local-voxel points: out = (value, weightSum, inside) per point.
// Built twice: test_sample (sw) and test_sample_rq (-DAMRVK_RAY_QUERY, backend from the push).
#ifdef AMRVK_RAY_QUERY
#extension GL_EXT_ray_query : require
#endif
#include "lib/common.glsl"
#include "lib/amr_sample.glsl"
#include "shared/test_push.h"
layout(push_constant, scalar) uniform Push { TestSamplePush tp; };
layout(local_size_x = 32) in;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= tp.count) return;
    gParams = ParamsRef(tp.params);
    vec4 p = Vec4Ref(tp.points).v[i];
    FieldSample s = sampleField(tp.samplerKind, tp.backend, p.xyz);
    FloatRW o = FloatRW(tp.results);
    o.v[3u * i] = s.value;
    o.v[3u * i + 1u] = s.weightSum;
    o.v[3u * i + 2u] = s.inside ? 1.0 : 0.0;
}
