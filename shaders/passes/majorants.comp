#version 460
// Majorant per macrocell or traversal box = exact maximum of the TF's alpha over its value range
// (tfMaxAlpha: the same piecewise-linear function the tracker evaluates). Run on every TF change,
// once per structure: ranges (ValueRangeGpu[count]) -> majorants (float[count]), and for the
// macrocells with --control-extinction minorant their minorants (tfMinAlpha) too.
#include "lib/common.glsl"
layout(push_constant, scalar) uniform Push { StructurePush pc; };
#include "lib/tf.glsl"

layout(local_size_x = 64) in;

void main() {
    gParams = ParamsRef(pc.params);
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    ValueRangeGpu range = ValueRangeRef(pc.source).v[i];
    float maxAlpha = tfMaxAlpha(range.lo, range.hi);
    FloatRW(pc.target).v[i] = maxAlpha;
    // The control extinction's minorant, below the exact minimum by more than evalTf's rounding;
    // an empty range (no medium) gets 0.
    if (pc.minorants != 0ul)
        FloatRW(pc.minorants).v[i] =
            range.lo > range.hi ? 0.0 : max(0.0, tfMinAlpha(range.lo, range.hi) - kMinorantMargin * maxAlpha);
}
