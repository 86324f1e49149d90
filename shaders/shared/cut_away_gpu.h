// The cut-away as the shaders see it (scene/cut_away.h makes it): a crop box and up to
// kMaxClipPlanes half-spaces, all in local voxel space. The medium is kept where the point lies in
// the crop box (when flags has kCutCrop) and on the kept side of every plane; elsewhere it is empty.
// The kept region is convex, so a ray meets it in one interval (lib/cut_away.glsl).
#ifndef AMRVK_CUT_AWAY_GPU_H
#define AMRVK_CUT_AWAY_GPU_H
#include "interop.h"

AMRVK_NAMESPACE_BEGIN

AMRVK_CONST uint kMaxClipPlanes = 4u;
AMRVK_CONST uint kCutCrop = 1u;  // flags: the crop box is in use

struct CutAwayGpu {
    vec3 cropLo;      // local voxel; kept: cropLo <= p <= cropHi
    uint flags;       // kCutCrop
    vec3 cropHi;      // local voxel
    uint planeCount;  // planes[0, planeCount) are in use
    vec4 planes[kMaxClipPlanes];  // xyz = unit normal n, w = offset c: kept where dot(n, p) <= c
};
AMRVK_STATIC_ASSERT(sizeof(CutAwayGpu) == 32 + 16 * kMaxClipPlanes);

#ifdef __cplusplus
AMRVK_STATIC_ASSERT(offsetof(CutAwayGpu, cropLo) == 0);
AMRVK_STATIC_ASSERT(offsetof(CutAwayGpu, flags) == 12);
AMRVK_STATIC_ASSERT(offsetof(CutAwayGpu, cropHi) == 16);
AMRVK_STATIC_ASSERT(offsetof(CutAwayGpu, planeCount) == 28);
AMRVK_STATIC_ASSERT(offsetof(CutAwayGpu, planes) == 32);
#endif

AMRVK_NAMESPACE_END
#endif
