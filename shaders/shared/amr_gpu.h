// GPU layouts of the AMR structures (scalar block layout). Coordinates are in local voxel space:
// voxel space minus the scene's local origin (VolumeScene::toLocal), so float positions stay small.
#ifndef AMRVK_AMR_GPU_H
#define AMRVK_AMR_GPU_H
#include "interop.h"

AMRVK_NAMESPACE_BEGIN

// One brick: full single-level box of cells; values at brickValues[begin + x + sx*(y + sy*z)].
struct BrickGpu {
    ivec3 lower;  // lower corner, local voxel units
    int level;    // cell width 1 << level
    ivec3 size;   // cells per axis
    uint begin;   // first value index (brick order)
};
AMRVK_STATIC_ASSERT(sizeof(BrickGpu) == 32);
#ifdef __cplusplus
AMRVK_STATIC_ASSERT(offsetof(BrickGpu, lower) == 0);
AMRVK_STATIC_ASSERT(offsetof(BrickGpu, level) == 12);
AMRVK_STATIC_ASSERT(offsetof(BrickGpu, size) == 16);
AMRVK_STATIC_ASSERT(offsetof(BrickGpu, begin) == 28);
#endif

// Depth limit of the software BVHs (root = depth 0). Median splits reach it only beyond 2^24
// leaves; deeper nodes become (larger) leaves. Point queries need a stack of kBvhMaxDepth + 2.
AMRVK_CONST uint kBvhMaxDepth = 24u;
AMRVK_CONST uint kBvhStackSize = kBvhMaxDepth + 2u;

// Node of a software BVH (accel/bvh.h builds them): inner nodes have count 0 and children first,
// first + 1.
struct BvhNodeGpu {
    vec3 lo;     // local voxel units, rounded outward
    uint first;  // inner: left child; leaf: first slot in the primitive-id array
    vec3 hi;
    uint count;  // 0 = inner node, else primitives in the leaf
};
AMRVK_STATIC_ASSERT(sizeof(BvhNodeGpu) == 32);
#ifdef __cplusplus
AMRVK_STATIC_ASSERT(offsetof(BvhNodeGpu, lo) == 0);
AMRVK_STATIC_ASSERT(offsetof(BvhNodeGpu, first) == 12);
AMRVK_STATIC_ASSERT(offsetof(BvhNodeGpu, hi) == 16);
AMRVK_STATIC_ASSERT(offsetof(BvhNodeGpu, count) == 28);
#endif

// One active brick region: a box whose overlapping bricks are abrBrickList[brickBegin ...].
struct AbrGpu {
    vec3 lo;          // local voxel units (exact: half-integers)
    uint brickBegin;
    vec3 hi;
    uint brickCount;
};
AMRVK_STATIC_ASSERT(sizeof(AbrGpu) == 32);
#ifdef __cplusplus
AMRVK_STATIC_ASSERT(offsetof(AbrGpu, lo) == 0);
AMRVK_STATIC_ASSERT(offsetof(AbrGpu, brickBegin) == 12);
AMRVK_STATIC_ASSERT(offsetof(AbrGpu, hi) == 16);
AMRVK_STATIC_ASSERT(offsetof(AbrGpu, brickCount) == 28);
#endif

// An axis-aligned box with the layout of VkAabbPositionsKHR (ray-query BLAS input); local voxel
// units.
struct AabbGpu {
    vec3 lo;
    vec3 hi;
};
AMRVK_STATIC_ASSERT(sizeof(AabbGpu) == 24);
#ifdef __cplusplus
AMRVK_STATIC_ASSERT(offsetof(AabbGpu, lo) == 0);
AMRVK_STATIC_ASSERT(offsetof(AabbGpu, hi) == 12);
#endif

// A closed interval of field values (macrocell, traversal box); empty when lo > hi.
// accel::ValueRange adds the host operations.
struct ValueRangeGpu {
    float lo;
    float hi;
};
AMRVK_STATIC_ASSERT(sizeof(ValueRangeGpu) == 8);
#ifdef __cplusplus
AMRVK_STATIC_ASSERT(offsetof(ValueRangeGpu, lo) == 0);
AMRVK_STATIC_ASSERT(offsetof(ValueRangeGpu, hi) == 4);
#endif

AMRVK_NAMESPACE_END
#endif
