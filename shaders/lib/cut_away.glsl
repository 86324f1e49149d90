// The cut-away (shared/cut_away_gpu.h): narrows a ray's interval to the kept region, the crop box
// intersected with every clip plane's kept half-space. That region is convex, so the kept part of
// a ray is one interval and every traversal simply starts and ends there: boxes and macrocells
// beyond the cut are never visited, and the majorants inside stay valid bounds. The field inside
// is reconstructed as before (cells beyond the cut still weigh in near it). CPU twin:
// scene/cut_away.cpp (keptInterval).
#ifndef AMRVK_CUT_AWAY_GLSL
#define AMRVK_CUT_AWAY_GLSL
#include "lib/ray_box.glsl"

// Narrows [tMin, tMax] of o + t d to the kept region; false when nothing of it is kept.
bool clipToCutAway(vec3 o, vec3 d, inout float tMin, inout float tMax) {
    if ((P.cut.flags & kCutCrop) != 0u && !clipRay(P.cut.cropLo, P.cut.cropHi, o, d, tMin, tMax)) return false;
    for (uint i = 0u; i < P.cut.planeCount; ++i) {
        vec4 pl = P.cut.planes[i];
        precise float s = pl.w - dot(pl.xyz, o);  // kept at t where dot(n, d) t <= s
        precise float dn = dot(pl.xyz, d);
        if (dn == 0.0) {
            if (s < 0.0) return false;  // parallel and on the removed side
        } else if (dn > 0.0) {
            tMax = min(tMax, s / dn);
        } else {
            tMin = max(tMin, s / dn);
        }
    }
    return tMin < tMax;
}

#endif
