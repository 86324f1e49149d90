#pragma once
// CPU twin of shaders/lib/majorant_dda.glsl: the 3-D DDA over a uniform macrocell grid, written
// with the same operations in the same order (templated on the scalar type: float reproduces the
// shader, double is the precise reference). Segments are contiguous and cover the ray's overlap
// with the grid within [tMin, tMax]; the grid is clipped by the shared slab test (ray_box.h).
// ddaStart begins the walk in a given macrocell (grid-bvh resumes there after a box query);
// ddaNextSkipping crosses blocks of inactive macrocells in one step (grid-dda).
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "accel/ray_box.h"

namespace amrvk::accel {

struct DdaGrid {
    glm::dvec3 origin{0.0};    // lower corner
    glm::dvec3 cellSize{1.0};  // per axis
    glm::ivec3 dims{1};
};

template <typename T>
struct DdaSegment {
    uint32_t cell;  // x + dims.x * (y + dims.y * z)
    T t0, t1;
};

// The walk's state: the macrocell the ray is in and the next plane crossing per axis.
template <typename T>
struct DdaState {
    glm::ivec3 cell{0};
    glm::ivec3 step{0};
    glm::vec<3, T> tNext{std::numeric_limits<T>::infinity()};   // per axis (inf: never)
    glm::vec<3, T> tDelta{std::numeric_limits<T>::infinity()};  // ray parameter per macrocell per axis
    T t{}, tEnd{};                                                // start of the current segment; end
    glm::ivec3 block{-1};  // ddaNextSkipping: the block it last found active (-1 after ddaStart)
};

// The macrocell holding o + d t, clamped into the grid.
template <typename T>
glm::ivec3 ddaCellAt(const DdaGrid& grid, glm::vec<3, T> o, glm::vec<3, T> d, T t) {
    using V = glm::vec<3, T>;
    const V lo(grid.origin), size(grid.cellSize);
    V start = (o + d * t - lo) / size;
    return glm::clamp(glm::ivec3(glm::floor(start)), glm::ivec3(0), grid.dims - 1);
}

// Starts in macrocell `cell` at ray parameter t (no clip, no floor), as the shader's ddaStart.
template <typename T>
DdaState<T> ddaStart(const DdaGrid& grid, glm::vec<3, T> o, glm::vec<3, T> d, glm::ivec3 cell, T t, T tEnd) {
    using V = glm::vec<3, T>;
    const V lo(grid.origin), size(grid.cellSize);
    DdaState<T> s;
    s.t = t;
    s.tEnd = tEnd;
    s.cell = cell;
    for (int a = 0; a < 3; ++a) {
        if (d[a] > T(0)) {
            s.step[a] = 1;
            s.tDelta[a] = size[a] / d[a];
            s.tNext[a] = std::max(t, (lo[a] + T(cell[a] + 1) * size[a] - o[a]) / d[a]);
        } else if (d[a] < T(0)) {
            s.step[a] = -1;
            s.tDelta[a] = -size[a] / d[a];
            s.tNext[a] = std::max(t, (lo[a] + T(cell[a]) * size[a] - o[a]) / d[a]);
        }
    }
    return s;
}

// Whether the walk is over: tEnd reached, or the ray has left the grid.
template <typename T>
bool ddaEnded(const DdaGrid& grid, const DdaState<T>& s) {
    return s.t >= s.tEnd || !glm::all(glm::greaterThanEqual(s.cell, glm::ivec3(0))) ||
           !glm::all(glm::lessThan(s.cell, grid.dims));
}

// Next segment; false when the ray has left the grid or reached tEnd.
template <typename T>
bool ddaNext(const DdaGrid& grid, DdaState<T>& s, DdaSegment<T>& seg) {
    const glm::ivec3 dims = grid.dims;
    if (ddaEnded(grid, s)) return false;
    T tExit = std::min(std::min(s.tNext.x, s.tNext.y), s.tNext.z);
    seg = {uint32_t(s.cell.x + dims.x * (s.cell.y + dims.y * s.cell.z)), s.t, std::min(tExit, s.tEnd)};
    for (int a = 0; a < 3; ++a)
        if (s.tNext[a] == tExit) {
            s.cell[a] += s.step[a];
            s.tNext[a] += s.tDelta[a];
        }
    s.t = seg.t1;
    return true;
}

// grid-dda's block size, 2^shift macrocells per axis (0: no blocks): blocks of 8^3 from 64
// macrocells on the longest axis, 4^3 from 16; a smaller grid is crossed in a few steps anyway.
inline int ddaBlockShift(glm::ivec3 dims) {
    const int longest = std::max({dims.x, dims.y, dims.z});
    return longest >= 64 ? 3 : longest >= 16 ? 2 : 0;
}

// grid-dda crosses empty blocks under a TF only where at least this fraction of the blocks is
// empty: a lane that crosses or enters a block makes the others of its SIMD group wait, which
// costs more than the steps saved where few blocks are empty (lavapipe, benchmarks section 23:
// the synthetic clouds, 91-96% empty, 1.09-1.19x the paths/s at grid 128 and 1.8-2.5x at 256;
// Enzo, PeleLM and RAMSES, 22-63% empty, 0.86-1.09x with blocks forced on).
inline constexpr double kMinEmptyBlockFraction = 0.75;

// grid-bvh steps this many culled macrocells in a row with the DDA before one box query skips the
// rest of the run (1: a query at every culled run). Stepping a run until it has cost about one
// query, then querying, costs at most about twice the cheaper of the two ways for every run. On
// lavapipe a software BVH query costs as much as 30-60 DDA steps: swept over 1-64 on five data
// sets under foggy, 32 took grid-bvh from 4.4x (Enzo), 2.7-2.9x (RAMSES) and 2.1-2.5x (the
// clouds) of grid-dda's time to 1.36-1.53x, 1.19-1.42x and 1.08-1.35x (benchmarks section 26).
inline constexpr uint32_t kGridBvhQueryAfter = 32;

// Blocks of 2^shift macrocells per axis over the grid (the last ones cut at its far faces).
inline glm::ivec3 ddaBlockDims(const DdaGrid& grid, int shift) { return (grid.dims + (1 << shift) - 1) >> shift; }

// The cell of a segment that crosses an empty block (majorant 0, no macrocell).
inline constexpr uint32_t kDdaEmptyBlock = 0xffffffffu;

// ddaNext over blocks of 2^shift macrocells per axis, as the shader's ddaNextSkipping: a block for
// which blockActive(x + bx * (y + by * z)) is false (all its majorants are 0) is crossed in one
// step, yielded as one segment with cell kDdaEmptyBlock; the walk restarts at its exit parameter
// in the first macrocell past the face it leaves by (inside the block on the other axes). The
// other segments are those of ddaNext inside active blocks.
template <typename T, typename BlockActive>
bool ddaNextSkipping(const DdaGrid& grid, int shift, glm::vec<3, T> o, glm::vec<3, T> d, DdaState<T>& s,
                     const BlockActive& blockActive, DdaSegment<T>& seg) {
    using V = glm::vec<3, T>;
    const glm::ivec3 dims = grid.dims, blocks = ddaBlockDims(grid, shift);
    const glm::ivec3 block = s.cell >> shift;
    if (block == s.block) return ddaNext(grid, s, seg);  // inside the grid: s.block is a block
    if (ddaEnded(grid, s)) return false;
    if (blockActive(uint32_t(block.x + blocks.x * (block.y + blocks.y * block.z)))) {
        s.block = block;  // read once per block entered
        return ddaNext(grid, s, seg);
    }
    const V lo(grid.origin), size(grid.cellSize);
    const glm::ivec3 first = block << shift, last = glm::min(first + (1 << shift), dims) - 1;
    V tExit(std::numeric_limits<T>::infinity());
    for (int a = 0; a < 3; ++a) {
        if (s.step[a] > 0) tExit[a] = std::max(s.t, (lo[a] + T(last[a] + 1) * size[a] - o[a]) / d[a]);
        else if (s.step[a] < 0) tExit[a] = std::max(s.t, (lo[a] + T(first[a]) * size[a] - o[a]) / d[a]);
    }
    const T tx = std::min(std::min(tExit.x, tExit.y), tExit.z);
    if (!(tx < s.tEnd)) return false;  // the ray ends inside the empty block
    const V p = (o + d * tx - lo) / size;
    glm::ivec3 cell;
    for (int a = 0; a < 3; ++a)
        cell[a] = tExit[a] == tx ? (s.step[a] > 0 ? last[a] + 1 : first[a] - 1)
                                 : int(std::floor(std::clamp(p[a], T(first[a]), T(last[a]))));
    seg = {kDdaEmptyBlock, s.t, tx};
    s = ddaStart(grid, o, d, cell, tx, s.tEnd);
    return true;
}

// Every segment of a walk started with ddaStart.
template <typename T>
std::vector<DdaSegment<T>> ddaSegmentsFrom(const DdaGrid& grid, glm::vec<3, T> o, glm::vec<3, T> d, glm::ivec3 cell,
                                           T t, T tEnd) {
    std::vector<DdaSegment<T>> out;
    DdaState<T> s = ddaStart(grid, o, d, cell, t, tEnd);
    DdaSegment<T> seg;
    while (ddaNext(grid, s, seg)) out.push_back(seg);
    return out;
}

// Every segment of the ray's overlap with the grid within [tMin, tMax].
template <typename T>
std::vector<DdaSegment<T>> ddaSegments(const DdaGrid& grid, glm::vec<3, T> o, glm::vec<3, T> d, T tMin,
                                       T tMax) {
    using V = glm::vec<3, T>;
    const V lo(grid.origin), size(grid.cellSize);
    const V hi = lo + size * V(grid.dims);
    T t = tMin, tEnd = tMax;
    if (!clipRay(lo, hi, o, d, t, tEnd)) return {};
    return ddaSegmentsFrom(grid, o, d, ddaCellAt(grid, o, d, t), t, tEnd);
}

// Every segment ddaNextSkipping yields over the ray's overlap with the grid within [tMin, tMax]
// (one a step, empty blocks included).
template <typename T, typename BlockActive>
std::vector<DdaSegment<T>> ddaSegmentsSkipping(const DdaGrid& grid, int shift, glm::vec<3, T> o, glm::vec<3, T> d,
                                               T tMin, T tMax, const BlockActive& blockActive) {
    using V = glm::vec<3, T>;
    const V lo(grid.origin), size(grid.cellSize);
    const V hi = lo + size * V(grid.dims);
    T t = tMin, tEnd = tMax;
    std::vector<DdaSegment<T>> out;
    if (!clipRay(lo, hi, o, d, t, tEnd)) return out;
    DdaState<T> s = ddaStart(grid, o, d, ddaCellAt(grid, o, d, t), t, tEnd);
    DdaSegment<T> seg;
    while (ddaNextSkipping(grid, shift, o, d, s, blockActive, seg)) out.push_back(seg);
    return out;
}

}  // namespace amrvk::accel
