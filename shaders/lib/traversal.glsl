// One interface over every majorant traversal (kTraversal*): segments [t0, t1] front to back,
// contiguous, each with the id of its macrocell or box and its majorant (max TF alpha; multiply
// by densityScale / finestCellWidth for extinction per voxel unit). grid-dda steps the macrocell
// grid (majorant_dda.glsl); every other traversal queries its boxes (domain_traversal.glsl).
#ifndef AMRVK_TRAVERSAL_GLSL
#define AMRVK_TRAVERSAL_GLSL
#include "lib/cut_away.glsl"

// The structure combination a pass was specialised for.
struct StructureConfig {
    uint samplerKind;  // kSampler*
    uint traversal;  // kTraversal*
    uint backend;    // kBackend*
};

struct Traversal {
    DdaState dda;  // grid-dda only
    vec3 o, d;
    float t, tEnd;
};

// Moves the origin of o + t d, t in [0, tMax], to where the ray enters the data bounds (local
// voxel space [0, boundsHi]) and shortens tMax to match; tBase is the parameter of the new origin
// on the old ray (0 for a ray that starts inside). False when the ray misses the data. Positions
// o + d t are then rounded like coordinates of the data, not like a far camera's: tracking and
// ray marching call it before traversalInit (the medium lies inside the bounds).
bool rebaseRay(inout vec3 o, vec3 d, inout float tMax, out float tBase) {
    float tIn = 0.0, tOut = tMax;
    tBase = 0.0;
    if (!clipRay(vec3(0.0), P.scene.boundsHi, o, d, tIn, tOut) || !(tIn < tOut)) return false;
    if (tIn > 0.0) {
        o += d * tIn;
        tBase = tIn;
    }
    tMax = tOut - tIn;
    return true;
}

// False when the ray misses the structure within [tMin, tMax]. The interval is first narrowed to
// the cut-away's kept region (lib/cut_away.glsl), so every estimator and dvr see an empty medium
// beyond the cut.
bool traversalInit(StructureConfig cfg, vec3 o, vec3 d, float tMin, float tMax, out Traversal tr) {
    tr.o = o;
    tr.d = d;
    if (!clipToCutAway(o, d, tMin, tMax)) {
        tr.t = tMin;
        tr.tEnd = tMin;
        return false;
    }
    tr.t = tMin;
    tr.tEnd = tMax;
    if (cfg.traversal == kTraversalGridDda) return ddaInit(o, d, tMin, tMax, tr.dda);
    // The medium lies inside the union of leaf cells: boxes beyond it carry no extinction.
    return clipRay(vec3(0.0), P.scene.boundsHi, o, d, tr.t, tr.tEnd);
}

// Next segment with a box or macrocell; gaps between boxes are skipped (nothing there).
// `steps` counts DDA steps or segment queries.
bool traversalNext(StructureConfig cfg, inout Traversal tr, inout uint steps, out uint id, out float majAlpha,
                   out float t0, out float t1) {
    if (cfg.traversal == kTraversalGridDda) {
        if (!ddaNext(tr.dda, id, t0, t1)) return false;
        steps++;
        majAlpha = FloatRef(P.majorants.gridMajorants).v[id];
        return true;
    }
    while (tr.t < tr.tEnd) {
        steps++;
        SegmentQuery q = querySegment(cfg.traversal, cfg.backend, tr.o, tr.d, tr.t, tr.tEnd);
        if (!q.covered) {
            if (!(q.end < tr.tEnd)) return false;
            tr.t = q.end;
            continue;
        }
        id = q.prim;
        majAlpha = q.maj;
        t0 = tr.t;
        t1 = q.end;
        tr.t = q.end;
        return true;
    }
    return false;
}

#endif
