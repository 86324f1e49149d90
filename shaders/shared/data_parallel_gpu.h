// Data-parallel path tracing over MPI ranks (passes/path_trace_dp.comp, mpi/data_parallel.cpp):
// every rank holds the same path state (replicated), tracks each path only through the box of
// space it owns, and the ranks agree on each result by reductions: the nearest local collision
// (MPI MINLOC over DataParallelHitGpu.t, the owner's TF colour), the product of the local shadow
// transmittances. Positions and directions are in the local voxel space every rank shares (the
// whole data set's lower corner as origin).
#ifndef AMRVK_DATA_PARALLEL_GPU_H
#define AMRVK_DATA_PARALLEL_GPU_H
#include "interop.h"
#include "path_state_gpu.h"

AMRVK_NAMESPACE_BEGIN

AMRVK_CONST uint kDpStageGenerate = 0u;    // camera rays of one sample per pixel
AMRVK_CONST uint kDpStageTrack = 1u;       // local first collision of each live path (hits)
AMRVK_CONST uint kDpStageShade = 2u;       // with the agreed hits: emission, NEE set-up, next direction
AMRVK_CONST uint kDpStageShadow = 3u;      // local transmittance of each shadow ray (shadow)
AMRVK_CONST uint kDpStageResolve = 4u;     // with the agreed transmittance: add the light
AMRVK_CONST uint kDpStageAccumulate = 5u;  // add each path's radiance to its pixel

// A local first collision (t = inf: none in this rank's box; t < 0: the path is not live) and
// the TF colour there; after the agreement, the nearest over ranks and its owner's colour.
struct DataParallelHitGpu {
    float t;
    vec3 color;
};
AMRVK_STATIC_ASSERT(sizeof(DataParallelHitGpu) == 16);

struct DataParallelPush {
    uint64_t params;    // RenderParams (this rank's structures, the shared view and shading)
    uint64_t paths;     // PathStateGpu[count]
    uint64_t hits;      // DataParallelHitGpu[count]
    uint64_t shadow;    // float[count]: local transmittance (< 0: no shadow ray), then the product
    uint64_t counters;  // uint[kCounterCount], then uint live paths (after a shade stage)
    vec3 ownedLo;       // this rank's box (local voxel)
    uint stage;         // kDpStage*
    vec3 ownedHi;
    uint count;         // paths (= pixels: one sample per pixel per batch)
    uint sampleIndex;   // the batch's sample number (seeds the shared random state)
    uint rankSeed;      // differs per rank: the random numbers of local tracking
    uint pad0, pad1;
};
AMRVK_STATIC_ASSERT(sizeof(DataParallelPush) == 88);

#ifdef __cplusplus
AMRVK_STATIC_ASSERT(offsetof(DataParallelHitGpu, color) == 4);
AMRVK_STATIC_ASSERT(offsetof(DataParallelPush, counters) == 32);
AMRVK_STATIC_ASSERT(offsetof(DataParallelPush, ownedLo) == 40);
AMRVK_STATIC_ASSERT(offsetof(DataParallelPush, stage) == 52);
AMRVK_STATIC_ASSERT(offsetof(DataParallelPush, ownedHi) == 56);
AMRVK_STATIC_ASSERT(offsetof(DataParallelPush, count) == 68);
AMRVK_STATIC_ASSERT(offsetof(DataParallelPush, sampleIndex) == 72);
AMRVK_STATIC_ASSERT(offsetof(DataParallelPush, rankSeed) == 76);
#endif

AMRVK_NAMESPACE_END

#endif
