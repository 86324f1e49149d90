// One interface over every majorant traversal (kTraversal*): segments [t0, t1] front to back,
// each with the id of its macrocell or box and its majorant (max TF alpha; multiply by
// densityScale / finestCellWidth for extinction per voxel unit); a gap between segments holds
// nothing of alpha > 0. grid-dda steps the macrocell grid (majorant_dda.glsl), crossing blocks of
// macrocells whose majorants are all 0 in one step; grid-bvh steps it too and queries its active
// macrocells only to skip culled ones; every other traversal queries its boxes
// (domain_traversal.glsl).
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
    DdaState dda;  // grid-dda; grid-bvh while stepping
    vec3 o, d;
    float t, tEnd;
    bool stepping;  // grid-bvh: dda holds the walk; else the next segment starts with a box query at t
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
    tr.stepping = false;
    if (!clipToCutAway(o, d, tMin, tMax)) {
        tr.t = tMin;
        tr.tEnd = tMin;
        return false;
    }
    tr.t = tMin;
    tr.tEnd = tMax;
    if (cfg.traversal == kTraversalGridDda) return ddaInit(o, d, tMin, tMax, tr.dda);
    // The medium lies inside the union of leaf cells: boxes beyond it carry no extinction.
    if (!clipRay(vec3(0.0), P.scene.boundsHi, o, d, tr.t, tr.tEnd)) return false;
    if (cfg.traversal == kTraversalGridBvh) tr.stepping = ddaInit(o, d, tr.t, tr.tEnd, tr.dda);
    return true;
}

// grid-bvh: steps the grid with the DDA while its macrocells are active (majorant > 0), exactly as
// grid-dda does, and through runs of culled ones shorter than P.scene.gridBvhQueryAfter (K); the
// K-th culled macrocell of a run starts ONE box query at its entry t over the active macrocells,
// which jumps to the nearest active entry ahead (or ends the ray), where the DDA resumes in the
// macrocell the ray enters. A run of L culled macrocells thus costs L steps when L < K and K steps
// plus a query otherwise (K = 1: a query at every culled run). The DDA's plane crossings and the
// query's slab test round apart at a face, so a query may find an active macrocell covering t:
// its segment (exact ends) is yielded and the DDA resumes in that macrocell at the segment's end.
// Every query moves t strictly forward and the DDA leaves the grid, so the walk ends. Empty DDA
// segments (a start on a face, an edge crossing) are skipped. Segments stay contiguous within runs
// of active macrocells and never skip an active macrocell; sw and rq make the same decisions from
// the same (bit-identical) query answers, so their segments stay bit-identical.
bool gridBvhNext(StructureConfig cfg, inout Traversal tr, inout uint steps, out uint id, out float majAlpha,
                 out float t0, out float t1) {
    uint culled = 0u;  // culled macrocells stepped in a row
    for (;;) {
        if (tr.stepping) {
            if (!ddaNext(tr.dda, id, t0, t1)) return false;
            steps++;
            majAlpha = domainMajorant(id);
            if (majAlpha > 0.0) {
                if (t1 > t0) return true;
                culled = 0u;
                continue;
            }
            if (++culled < P.scene.gridBvhQueryAfter) continue;
            culled = 0u;
            tr.t = t0;
            tr.stepping = false;
        }
        if (!(tr.t < tr.tEnd)) return false;
        steps++;
        SegmentQuery q = querySegment(cfg.traversal, cfg.backend, tr.o, tr.d, tr.t, tr.tEnd);
        if (!q.covered) {
            if (!(q.end < tr.tEnd)) return false;  // no active macrocell ahead
            tr.t = q.end;
            ddaStart(tr.o, tr.d, ddaCellEntered(tr.o, tr.d, tr.t), tr.t, tr.tEnd, tr.dda);
            tr.stepping = true;
            continue;
        }
        id = q.prim;
        majAlpha = q.maj;
        t0 = tr.t;
        t1 = q.end;
        tr.t = q.end;
        ddaStart(tr.o, tr.d, ddaCellOfIndex(q.prim), q.end, tr.tEnd, tr.dda);
        tr.stepping = true;
        return true;
    }
}

// Next segment with a box or macrocell; gaps between boxes are skipped (nothing there).
// `steps` counts DDA steps plus box queries, one each (grid-bvh does both).
bool traversalNext(StructureConfig cfg, inout Traversal tr, inout uint steps, out uint id, out float majAlpha,
                   out float t0, out float t1) {
    if (cfg.traversal == kTraversalGridDda) {
        bool empty = false;
        if (tr.dda.blockShift > 0) {
            if (!ddaNextSkipping(tr.o, tr.d, tr.dda, id, t0, t1, empty)) return false;
        } else {
            if (!ddaNext(tr.dda, id, t0, t1)) return false;
        }
        steps++;
        majAlpha = empty ? 0.0 : FloatRef(P.majorants.gridMajorants).v[id];
        return true;
    }
    if (cfg.traversal == kTraversalGridBvh) return gridBvhNext(cfg, tr, steps, id, majAlpha, t0, t1);
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
