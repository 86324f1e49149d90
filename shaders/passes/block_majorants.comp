#version 460
// grid-dda's blocks (P.scene.gridBlockShift > 0): per block of 2^shift macrocells per axis (fewer
// at the grid's far faces), the max of its macrocells' majorants, so a block is 0 exactly when
// every majorant in it is 0 (majorant_dda.glsl crosses it in one step). Run after majorants.comp
// on every TF change: macrocell majorants (float[cells]) -> block majorants (float[count]).
#include "lib/common.glsl"
layout(push_constant, scalar) uniform Push { StructurePush pc; };

layout(local_size_x = 64) in;

void main() {
    gParams = ParamsRef(pc.params);
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    ivec3 dims = P.scene.gridDims;
    int shift = int(P.scene.gridBlockShift);
    uvec3 blocks = uvec3((dims + (1 << shift) - 1) >> shift);
    ivec3 lo = ivec3(i % blocks.x, (i / blocks.x) % blocks.y, i / (blocks.x * blocks.y)) << shift;
    ivec3 hi = min(lo + (1 << shift), dims);
    FloatRef cells = FloatRef(pc.source);
    float m = 0.0;
    for (int z = lo.z; z < hi.z; ++z)
        for (int y = lo.y; y < hi.y; ++y)
            for (int x = lo.x; x < hi.x; ++x) {
                float c = cells.v[uint(x + dims.x * (y + dims.y * z))];
                if (!(c <= m)) m = isnan(c) ? kInf : c;  // a NaN majorant keeps its block walked
            }
    FloatRW(pc.target).v[i] = m;
}
