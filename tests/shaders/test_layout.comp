#version 460
// Layout conformance: copies RenderParams fields, read through the GLSL declaration, into a flat
// uint array that the C++ test compares with what it wrote (tests/gpu/layout_test.cpp).
#include "lib/common.glsl"
layout(push_constant, scalar) uniform TestPush { uint64_t params; uint64_t outAddr; } tp;
layout(local_size_x = 1) in;

void main() {
    gParams = ParamsRef(tp.params);
    UintRW o = UintRW(tp.outAddr);
    uint k = 0u;
    o.v[k++] = floatBitsToUint(P.eye.x);
    o.v[k++] = floatBitsToUint(P.dv.w);
    o.v[k++] = P.image.x;
    o.v[k++] = P.image.w;
    o.v[k++] = floatBitsToUint(P.boundsLo.w);
    o.v[k++] = floatBitsToUint(P.boundsHi.w);
    o.v[k++] = uint(P.gridDims.z);
    o.v[k++] = floatBitsToUint(P.gridCellSize.y);
    o.v[k++] = floatBitsToUint(P.tfInfo.x);
    o.v[k++] = floatBitsToUint(P.background.z);
    o.v[k++] = floatBitsToUint(P.shading.x);
    o.v[k++] = floatBitsToUint(P.lights[3].posOrDir.w);
    o.v[k++] = floatBitsToUint(P.lights[7].radiance.y);
    o.v[k++] = uint(P.bricks);
    o.v[k++] = uint(P.bricks >> 32);
    o.v[k++] = uint(P.gridMajorants);
    o.v[k++] = uint(P.counters >> 32);
    // Struct arrays read through buffer references (BrickGpu, BvhNodeGpu, AbrGpu).
    BrickGpu b = BrickRef(P.brickValues).v[1];
    o.v[k++] = uint(b.lowerLevel.w);
    o.v[k++] = uint(b.sizeBegin.w);
    BvhNodeGpu n = BvhRef(P.samplerNodes).v[1];
    o.v[k++] = n.first;
    o.v[k++] = n.count;
    o.v[k++] = floatBitsToUint(n.hi.z);
    AbrGpu a = AbrRef(P.abrs).v[1];
    o.v[k++] = a.brickBegin;
    o.v[k++] = a.brickCount;
    o.v[k++] = floatBitsToUint(a.hi.x);
    // Structure-matrix fields and the AABB layout (VkAabbPositionsKHR).
    o.v[k++] = uint(P.samplerAccel);
    o.v[k++] = uint(P.domainAccel >> 32);
    o.v[k++] = P.domainInfo.x;
    o.v[k++] = P.domainInfo.y;
    AabbGpu box = AabbRef(P.domainBoxes).v[1];
    o.v[k++] = floatBitsToUint(box.lo.z);
    o.v[k++] = floatBitsToUint(box.hi.y);
    // dvr and dense-sampler fields.
    o.v[k++] = floatBitsToUint(P.dvr.x);
    o.v[k++] = floatBitsToUint(P.dvrLight.z);
    o.v[k++] = uint(P.denseDims.w);
    o.v[k++] = floatBitsToUint(P.denseOrigin.w);
    o.v[k++] = uint(P.denseValues >> 32);
    o.v[k++] = uint(P.accum);
}
