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

bool ddaInit(vec3 o, vec3 d, float tMin, float tMax, out DdaState s) {
    vec3 lo = P.scene.gridOrigin;
    vec3 size = P.scene.gridCellSize;
    ivec3 dims = P.scene.gridDims;
    vec3 hi = lo + size * vec3(dims);
    s.t = tMin;
    s.tEnd = tMax;
    if (!clipRay(lo, hi, o, d, s.t, s.tEnd)) return false;
    vec3 start = (o + d * s.t - lo) / size;
    s.cell = clamp(ivec3(floor(start)), ivec3(0), dims - 1);
    for (int a = 0; a < 3; ++a) {
        if (d[a] > 0.0) {
            s.stepDir[a] = 1;
            s.tDelta[a] = size[a] / d[a];
            s.tNext[a] = max(s.t, (lo[a] + float(s.cell[a] + 1) * size[a] - o[a]) / d[a]);
        } else if (d[a] < 0.0) {
            s.stepDir[a] = -1;
            s.tDelta[a] = -size[a] / d[a];
            s.tNext[a] = max(s.t, (lo[a] + float(s.cell[a]) * size[a] - o[a]) / d[a]);
        } else {
            s.stepDir[a] = 0;
            s.tDelta[a] = kInf;
            s.tNext[a] = kInf;
        }
    }
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
