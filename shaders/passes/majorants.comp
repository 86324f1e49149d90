#version 460
// Majorant per macrocell or traversal box = exact maximum of the TF's alpha over its value range
// (tfMaxAlpha: the same piecewise-linear function the tracker evaluates). Run on every TF change,
// once per structure: ranges (ValueRangeGpu[count]) -> majorants (float[count]).
#include "lib/common.glsl"
layout(push_constant, scalar) uniform Push { StructurePush pc; };
#include "lib/tf.glsl"

layout(local_size_x = 64) in;

void main() {
    gParams = ParamsRef(pc.params);
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    ValueRangeGpu range = ValueRangeRef(pc.source).v[i];
    FloatRW(pc.target).v[i] = tfMaxAlpha(range.lo, range.hi);
}
