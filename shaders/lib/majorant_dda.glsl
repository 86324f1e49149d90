// Robust 3-D DDA over the macrocell grid (local voxel space): yields contiguous segments
// [t0, t1] covering the ray's overlap with the grid, each with its macrocell index.
// Direction components may be +0 or -0 (that axis never steps); the start cell is clamped into
// the grid, so rays starting on faces, edges or corners, or inside the grid, work.
// The grid is clipped with the shared slab test (ray_box.glsl). grid-dda crosses blocks of
// macrocells whose majorants are all 0 in one step (ddaNextSkipping). CPU twin: accel/dda.h (the
// same steps, in float bit for bit or in double).
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
    ivec3 block;  // ddaNextSkipping: the block it last found active (-1 after ddaStart)
    int blockShift;  // P.scene.gridBlockShift where P.majorants.gridBlocks says the blocks pay, else 0
};

// Starts in macrocell `cell` at ray parameter t, stepping until tEnd; no clip and no floor: for a
// caller that knows the cell the ray is in at t (grid-bvh, from a box query). ddaInit ends here.
void ddaStart(vec3 o, vec3 d, ivec3 cell, float t, float tEnd, out DdaState s) {
    vec3 lo = P.scene.gridOrigin;
    vec3 size = P.scene.gridCellSize;
    s.t = t;
    s.tEnd = tEnd;
    s.cell = cell;
    s.block = ivec3(-1);
    s.blockShift = P.majorants.gridBlocks != 0u ? int(P.scene.gridBlockShift) : 0;
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

// o + d t in macrocell units from the grid's origin (unclamped).
vec3 ddaGridPoint(vec3 o, vec3 d, float t) { return (o + d * t - P.scene.gridOrigin) / P.scene.gridCellSize; }

// The macrocell holding o + d t, clamped into the grid (a point on a face may round to either
// side: the DDA's first segment is then empty or a sliver).
ivec3 ddaCellAt(vec3 o, vec3 d, float t) {
    return clamp(ivec3(floor(ddaGridPoint(o, d, t))), ivec3(0), P.scene.gridDims - 1);
}

// The macrocell the ray enters at o + d t: ddaCellAt's, except that a point exactly on a face the
// ray crosses in a negative direction belongs to the cell below the face, the one it enters
// (grid-bvh resumes there after a box query: no empty first segment in the cell behind).
ivec3 ddaCellEntered(vec3 o, vec3 d, float t) {
    vec3 start = ddaGridPoint(o, d, t);
    ivec3 cell = ivec3(floor(start));
    for (int a = 0; a < 3; ++a)
        if (d[a] < 0.0 && start[a] == float(cell[a])) cell[a] -= 1;
    return clamp(cell, ivec3(0), P.scene.gridDims - 1);
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

// Whether the walk is over: tEnd reached, or the ray has left the grid.
bool ddaEnded(DdaState s) {
    return s.t >= s.tEnd || any(lessThan(s.cell, ivec3(0))) || any(greaterThanEqual(s.cell, P.scene.gridDims));
}

// Next segment: macrocell index and [t0, t1]; false when the ray has left the grid.
bool ddaNext(inout DdaState s, out uint cellIndex, out float t0, out float t1) {
    ivec3 dims = P.scene.gridDims;
    if (ddaEnded(s)) return false;
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

// grid-dda's block majorant (P.scene.gridBlockShift > 0): the max of the majorants of the block's
// macrocells, stored after theirs (block_majorants.comp); blocks are numbered x fastest.
float ddaBlockMajorant(ivec3 block) {
    ivec3 dims = P.scene.gridDims;
    ivec3 blocks = (dims + (1 << P.scene.gridBlockShift) - 1) >> P.scene.gridBlockShift;
    uint cells = uint(dims.x) * uint(dims.y) * uint(dims.z);
    return FloatRef(P.majorants.gridMajorants).v[cells + uint(block.x + blocks.x * (block.y + blocks.y * block.z))];
}

// ddaNext over blocks of 2^gridBlockShift macrocells per axis: a block whose majorant is 0 holds
// only macrocells of majorant 0, whose segments the tracker skips anyway, so it is crossed in one
// step, yielded as one segment with `empty` set (majorant 0) and no macrocell. The walk restarts
// at the block's exit parameter in the first macrocell past the face it leaves by (the neighbour
// along every axis whose exit plane comes first; inside the block on the others). The block index
// only moves forward along each axis, so the walk ends. A sliver that rounding puts across the
// exit face lies within the majorant margin of the block's own macrocells, whose majorants are 0
// there too. So the segments that are not empty are those of ddaNext in blocks of majorant > 0; a
// segment after a skip starts at the block's exit parameter (the plane through the same float
// expression as ddaStart's). One step per call and no inner loop: lanes that skip and lanes that
// step stay in step with each other.
bool ddaNextSkipping(vec3 o, vec3 d, inout DdaState s, out uint cellIndex, out float t0, out float t1,
                     out bool empty) {
    empty = false;
    ivec3 block = s.cell >> s.blockShift;
    if (block == s.block) return ddaNext(s, cellIndex, t0, t1);  // inside the grid: s.block is a block
    if (ddaEnded(s)) return false;
    if (ddaBlockMajorant(block) > 0.0) {  // read once per block entered
        s.block = block;
        return ddaNext(s, cellIndex, t0, t1);
    }
    ivec3 first = block << s.blockShift;
    ivec3 last = min(first + (1 << s.blockShift), P.scene.gridDims) - 1;
    vec3 lo = P.scene.gridOrigin;
    vec3 size = P.scene.gridCellSize;
    vec3 tExit = vec3(kInf);
    for (int a = 0; a < 3; ++a) {
        if (s.stepDir[a] > 0) tExit[a] = max(s.t, (lo[a] + float(last[a] + 1) * size[a] - o[a]) / d[a]);
        else if (s.stepDir[a] < 0) tExit[a] = max(s.t, (lo[a] + float(first[a]) * size[a] - o[a]) / d[a]);
    }
    float tx = min(min(tExit.x, tExit.y), tExit.z);
    if (!(tx < s.tEnd)) return false;  // the ray ends inside the empty block
    vec3 p = (o + d * tx - lo) / size;
    ivec3 cell;
    for (int a = 0; a < 3; ++a)
        cell[a] = tExit[a] == tx ? (s.stepDir[a] > 0 ? last[a] + 1 : first[a] - 1)
                                 : int(floor(clamp(p[a], float(first[a]), float(last[a]))));
    empty = true;
    cellIndex = 0u;
    t0 = s.t;
    t1 = tx;
    ddaStart(o, d, cell, tx, s.tEnd, s);
    return true;
}

#endif
