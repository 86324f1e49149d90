#pragma once
// CPU twin of shaders/lib/majorant_dda.glsl: the 3-D DDA over a uniform macrocell grid, written
// with the same operations in the same order (templated on the scalar type: float reproduces the
// shader, double is the precise reference). Segments are contiguous and cover the ray's overlap
// with the grid within [tMin, tMax]; the grid is clipped by the shared slab test (ray_box.h).
#include <glm/glm.hpp>

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

template <typename T>
std::vector<DdaSegment<T>> ddaSegments(const DdaGrid& grid, glm::vec<3, T> o, glm::vec<3, T> d, T tMin,
                                       T tMax) {
    using V = glm::vec<3, T>;
    const T inf = std::numeric_limits<T>::infinity();
    const V lo(grid.origin), size(grid.cellSize);
    const glm::ivec3 dims = grid.dims;
    const V hi = lo + size * V(dims);
    std::vector<DdaSegment<T>> out;
    T t = tMin, tEnd = tMax;
    if (!clipRay(lo, hi, o, d, t, tEnd)) return out;
    V start = (o + d * t - lo) / size;
    glm::ivec3 cell = glm::clamp(glm::ivec3(glm::floor(start)), glm::ivec3(0), dims - 1);
    glm::ivec3 step(0);
    V tNext(inf), tDelta(inf);
    for (int a = 0; a < 3; ++a) {
        if (d[a] > T(0)) {
            step[a] = 1;
            tDelta[a] = size[a] / d[a];
            tNext[a] = std::max(t, (lo[a] + T(cell[a] + 1) * size[a] - o[a]) / d[a]);
        } else if (d[a] < T(0)) {
            step[a] = -1;
            tDelta[a] = -size[a] / d[a];
            tNext[a] = std::max(t, (lo[a] + T(cell[a]) * size[a] - o[a]) / d[a]);
        }
    }
    while (!(t >= tEnd) && glm::all(glm::greaterThanEqual(cell, glm::ivec3(0))) &&
           glm::all(glm::lessThan(cell, dims))) {
        T tExit = std::min(std::min(tNext.x, tNext.y), tNext.z);
        DdaSegment<T> seg{uint32_t(cell.x + dims.x * (cell.y + dims.y * cell.z)), t, std::min(tExit, tEnd)};
        for (int a = 0; a < 3; ++a)
            if (tNext[a] == tExit) {
                cell[a] += step[a];
                tNext[a] += tDelta[a];
            }
        t = seg.t1;
        out.push_back(seg);
    }
    return out;
}

}  // namespace amrvk::accel
