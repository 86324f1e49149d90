// Push-constant blocks of the test kernels in tests/shaders (used by tests only): one definition
// for the kernels and the C++ tests that dispatch them.
#ifndef AMRVK_TEST_PUSH_H
#define AMRVK_TEST_PUSH_H
#include "interop.h"

AMRVK_NAMESPACE_BEGIN

// test_layout: copies fields read through the GLSL declarations into results (uint words).
struct TestLayoutPush {
    uint64_t params;  // RenderParams
    uint64_t results; // uint[]
    uint64_t structs; // BrickGpu, BvhNodeGpu, AbrGpu, AabbGpu, ValueRangeGpu, AccumPixelGpu, one each, packed
    uint64_t pad;
};
AMRVK_STATIC_ASSERT(sizeof(TestLayoutPush) == 32);

// test_dda: per ray (vec4 origin + tMin, vec4 direction + tMax) the DDA segments.
struct TestDdaPush {
    uint64_t params;
    uint64_t rays;
    uint64_t results;
    uint rayCount;
    uint startCells;  // 0: ddaInit; 1: ddaStart in a given macrocell (a third vec4 per ray: x, y, z);
                      // 2: ddaInit, then ddaNextSkipping over the params' blocks
};
AMRVK_STATIC_ASSERT(sizeof(TestDdaPush) == 32);

// test_sample: per point (vec4) the reconstruction (value, weightSum, inside).
struct TestSamplePush {
    uint64_t params;
    uint64_t points;
    uint64_t results;
    uint count;
    uint samplerKind;  // SamplerKind
    uint backend;  // Backend
    uint pad;
};
AMRVK_STATIC_ASSERT(sizeof(TestSamplePush) == 40);

// test_segments: per ray (vec4 origin + tMin, vec4 direction + tMax) the majorant segments.
struct TestSegmentsPush {
    uint64_t params;
    uint64_t rays;
    uint64_t results;
    uint count;
    uint traversal;    // TraversalKind
    uint backend;      // Backend
    uint maxSegments;  // records per ray
};
AMRVK_STATIC_ASSERT(sizeof(TestSegmentsPush) == 40);

// test_tracking: count estimates of delta and ratio tracking along one ray.
struct TestTrackingPush {
    uint64_t params;
    uint64_t results;
    vec4 origin;  // xyz: local voxel; w unused
    vec4 dir;     // xyz: unit direction; w: tMax
    uint count;
    uint samplerKind;  // SamplerKind
    uint traversal;  // TraversalKind
    uint withUbrm;   // 1: also the unbiased ray-marching estimate (else 0 in its slot)
};
AMRVK_STATIC_ASSERT(sizeof(TestTrackingPush) == 64);

// test_ray_query: rays against a TLAS, candidates filtered by boxes (see the kernel).
struct TestRayQueryPush {
    uint64_t tlas;
    uint64_t boxes;
    uint64_t rays;
    uint64_t results;
    uint rayCount;
    uint mode;
    uint maxOut;
    uint pad;
};
AMRVK_STATIC_ASSERT(sizeof(TestRayQueryPush) == 48);

AMRVK_NAMESPACE_END
#endif
