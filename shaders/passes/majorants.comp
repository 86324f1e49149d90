#version 460
// Majorant per macrocell = exact maximum of the TF's alpha over the macrocell's value range
// (tfMaxAlpha: the same piecewise-linear function the tracker evaluates). Run on every TF change.
#include "lib/common.glsl"
layout(push_constant, scalar) uniform Push { PushConstants pc; };
#include "lib/tf.glsl"

layout(local_size_x = 64) in;

void main() {
    gParams = ParamsRef(pc.params);
    uint i = gl_GlobalInvocationID.x;
    uint count = uint(P.gridDims.x * P.gridDims.y * P.gridDims.z);
    if (i >= count) return;
    vec2 range = Vec2Ref(P.gridRanges).v[i];
    FloatRW(P.gridMajorants).v[i] = tfMaxAlpha(range.x, range.y);
}
