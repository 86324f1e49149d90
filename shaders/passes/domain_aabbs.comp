#version 460
// Ray-query culling: writes the BLAS input for the traversal boxes, box i as is when its majorant
// is > 0, else collapsed to the point lo (primitive index = box id either way). Vulkan's own rule
// for inactive AABBs (lo.x = NaN) loses active boxes on lavapipe 25.0 (a NaN propagates into its
// node bounds: tests/gpu/acceleration_structure_test.cpp), so a culled box stays in the BLAS as a
// point, is rarely reported, and foldCandidate skips it by its zero majorant.
// Run after majorants.comp on every TF change, followed by a BLAS rebuild.
#include "lib/common.glsl"
layout(push_constant, scalar) uniform Push { StructurePush pc; };
#include "lib/domain_traversal.glsl"

layout(local_size_x = 64) in;

void main() {
    gParams = ParamsRef(pc.params);
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    AabbGpu box;
    domainBox(pc.traversal, i, box.lo, box.hi);
    if (!(FloatRef(pc.source).v[i] > 0.0)) box.hi = box.lo;
    AabbRW(pc.target).v[i] = box;
}
