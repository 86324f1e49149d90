// Robust 3-D DDA over the macrocell grid (local voxel space): yields contiguous segments
// [t0, t1] covering the ray's overlap with the grid, each with its macrocell index.
// Direction components may be +0 or -0 (that axis never steps); the start cell is clamped into
// the grid, so rays starting on faces, edges or corners, or inside the grid, work.
// The grid is clipped with the shared slab test (ray_box.glsl). CPU twin: accel/dda.h (the same
// steps, in float bit for bit or in double).
#ifndef AMRVK_MAJORANT_DDA_GLSL
#define AMRVK_MAJORANT_DDA_GLSL

#include "lib/ray_box.glsl"

struct DdaState {
    ivec3 cell;
    ivec3 stepDir;
    vec3 tNext;   // ray parameter of the next plane crossing per axis (kInf if never)
    vec3 tDelta;  // ray parameter per macrocell per axis
    float t;      // start of the current segment
    float tEnd;
};

// Starts in macrocell `cell` at ray parameter t, stepping until tEnd; no clip and no floor: for a
// caller that knows the cell the ray is in at t (grid-bvh, from a box query). ddaInit ends here.
void ddaStart(vec3 o, vec3 d, ivec3 cell, float t, float tEnd, out DdaState s) {
    vec3 lo = P.scene.gridOrigin;
    vec3 size = P.scene.gridCellSize;
    s.t = t;
    s.tEnd = tEnd;
    s.cell = cell;
    for (int a = 0; a < 3; ++a) {
        if (d[a] > 0.0) {
            s.stepDir[a] = 1;
            s.tDelta[a] = size[a] / d[a];
            s.tNext[a] = max(t, (lo[a] + float(cell[a] + 1) * size[a] - o[a]) / d[a]);
        } else if (d[a] < 0.0) {
            s.stepDir[a] = -1;
            s.tDelta[a] = -size[a] / d[a];
            s.tNext[a] = max(t, (lo[a] + float(cell[a]) * size[a] - o[a]) / d[a]);
        } else {
            s.stepDir[a] = 0;
            s.tDelta[a] = kInf;
            s.tNext[a] = kInf;
        }
    }
}

// The macrocell holding o + d t, clamped into the grid (a point on a face may round to either
// side: the DDA's first segment is then empty or a sliver).
ivec3 ddaCellAt(vec3 o, vec3 d, float t) {
    vec3 start = (o + d * t - P.scene.gridOrigin) / P.scene.gridCellSize;
    return clamp(ivec3(floor(start)), ivec3(0), P.scene.gridDims - 1);
}

// Macrocell coordinates of index x + dims.x * (y + dims.y * z).
ivec3 ddaCellOfIndex(uint index) {
    uvec3 dims = uvec3(P.scene.gridDims);
    return ivec3(index % dims.x, (index / dims.x) % dims.y, index / (dims.x * dims.y));
}

bool ddaInit(vec3 o, vec3 d, float tMin, float tMax, out DdaState s) {
    vec3 lo = P.scene.gridOrigin;
    vec3 hi = lo + P.scene.gridCellSize * vec3(P.scene.gridDims);
    float t = tMin, tEnd = tMax;
    if (!clipRay(lo, hi, o, d, t, tEnd)) return false;
    ddaStart(o, d, ddaCellAt(o, d, t), t, tEnd, s);
    return true;
}

// Next segment: macrocell index and [t0, t1]; false when the ray has left the grid.
bool ddaNext(inout DdaState s, out uint cellIndex, out float t0, out float t1) {
    ivec3 dims = P.scene.gridDims;
    if (s.t >= s.tEnd || any(lessThan(s.cell, ivec3(0))) || any(greaterThanEqual(s.cell, dims))) return false;
    float tExit = min(min(s.tNext.x, s.tNext.y), s.tNext.z);
    cellIndex = uint(s.cell.x + dims.x * (s.cell.y + dims.y * s.cell.z));
    t0 = s.t;
    t1 = min(tExit, s.tEnd);
    for (int a = 0; a < 3; ++a)
        if (s.tNext[a] == tExit) {
            s.cell[a] += s.stepDir[a];
            s.tNext[a] += s.tDelta[a];
        }
    s.t = t1;
    return true;
}

#endif
