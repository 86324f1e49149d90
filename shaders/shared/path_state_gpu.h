// A path's state between its events (shaders/lib/estimator.glsl): kept in registers by
// passes/path_trace.comp, which runs a path's events in one loop, and in a buffer between the
// stages of passes/path_trace_dp.comp. Positions and directions are in local voxel space.
#ifndef AMRVK_PATH_STATE_GPU_H
#define AMRVK_PATH_STATE_GPU_H
#include "interop.h"

AMRVK_NAMESPACE_BEGIN

AMRVK_CONST uint kPathLive = 1u;     // the path goes on: its ray o + t d waits for tracking
AMRVK_CONST uint kPathShadow = 2u;   // a shadow ray waits for its transmittance

struct PathStateGpu {
    vec3 o;            // ray origin (local voxel)
    uint rng;          // the path's own decisions (light, phase, roulette); identical on every rank
    vec3 d;            // ray direction (unit)
    uint bounce;       // collisions so far
    vec3 throughput;
    uint flags;        // kPath*
    vec3 radiance;     // gathered so far
    uint pixel;        // the pixel it samples
    vec3 pending;      // light contribution waiting for its shadow transmittance
    float shadowDist;  // shadow ray length (voxel units; inf: directional light or ambient)
    vec3 shadowDir;
    uint pad;
};
AMRVK_STATIC_ASSERT(sizeof(PathStateGpu) == 96);

#ifdef __cplusplus
AMRVK_STATIC_ASSERT(offsetof(PathStateGpu, d) == 16);
AMRVK_STATIC_ASSERT(offsetof(PathStateGpu, throughput) == 32);
AMRVK_STATIC_ASSERT(offsetof(PathStateGpu, radiance) == 48);
AMRVK_STATIC_ASSERT(offsetof(PathStateGpu, pending) == 64);
AMRVK_STATIC_ASSERT(offsetof(PathStateGpu, shadowDist) == 76);
AMRVK_STATIC_ASSERT(offsetof(PathStateGpu, shadowDir) == 80);
#endif

AMRVK_NAMESPACE_END
#endif
