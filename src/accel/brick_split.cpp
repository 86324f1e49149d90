#include "accel/brick_split.h"

#include "accel/bricks.h"

namespace amrvk::accel {

namespace {

double halfArea(glm::dvec3 s) { return s.x * s.y + s.y * s.z + s.z * s.x; }

double sahCost(const CellStats& s) {
    if (s.levelMask == 0) return 0;
    const glm::dvec3 size = glm::dvec3(s.hi) - glm::dvec3(s.lo);
    return halfArea(size) * (size.x * size.y * size.z) * std::popcount(s.levelMask);
}

}  // namespace

SplitFrame frameOf(const CellStats& in) {
    SplitFrame f;
    f.cw = amr::cellWidth(in.maxLevel());
    const uint64_t slabLimit = 4 * uint64_t(in.count) + 1024;
    for (int a = 0; a < 3; ++a) {
        f.lo[a] = floorDiv(in.lo[a], f.cw) * f.cw;
        f.hi[a] = ceilDiv(in.hi[a], f.cw) * f.cw;
        f.slabs[a] = (f.hi[a] - f.lo[a]) / f.cw;
        f.used[a] = f.slabs[a] < 2 || uint64_t(f.slabs[a]) > slabLimit ? 0 : f.slabs[a];
    }
    return f;
}

SplitChoice chooseSplit(const SplitFrame& f, const Slabs& stats) {
    SplitChoice c;
    double bestCost = std::numeric_limits<double>::infinity();
    std::vector<CellStats> suffix;
    for (int a = 0; a < 3; ++a) {
        const std::vector<CellStats>& slab = stats[size_t(a)];
        if (slab.empty()) continue;
        const int b1 = (a + 1) % 3, b2 = (a + 2) % 3;
        const double fullVolume = double(f.cw) * double(f.hi[b1] - f.lo[b1]) * double(f.hi[b2] - f.lo[b2]);
        suffix.assign(slab.size() + 1, CellStats{});
        for (size_t k = slab.size(); k-- > 0;) {
            suffix[k] = suffix[k + 1];
            suffix[k].merge(slab[k]);
        }
        CellStats prefix;
        for (size_t k = 1; k < slab.size(); ++k) {
            prefix.merge(slab[k - 1]);
            const CellStats& l = slab[k - 1];
            const CellStats& r = slab[k];
            bool boundary = l.levelMask != r.levelMask || l.volume < fullVolume || r.volume < fullVolume;
            if (!boundary) continue;
            double cost = sahCost(prefix) + sahCost(suffix[k]);
            if (cost < bestCost) {
                bestCost = cost;
                c.axis = a;
                c.plane = f.lo[a] + int64_t(k) * f.cw;
            }
        }
    }
    if (c.axis < 0) {  // spatial median of the longest axis, in coarse cells
        int a = 0;
        for (int k = 1; k < 3; ++k)
            if (f.slabs[k] > f.slabs[a]) a = k;
        if (f.slabs[a] < 2) return c;
        c.axis = a;
        c.plane = f.lo[a] + f.slabs[a] / 2 * f.cw;
    }
    // The sides' bounds come from the slabs when the split axis has them, else from the cells.
    const std::vector<CellStats>& slab = stats[size_t(c.axis)];
    c.sidesFromSlabs = !slab.empty();
    const size_t k = size_t((c.plane - f.lo[c.axis]) / f.cw);
    for (size_t m = 0; m < slab.size(); ++m) (m < k ? c.left : c.right).merge(slab[m]);
    return c;
}

Slabs slabsFromCubes(const CubeGrid& g, const SplitFrame& f) {
    Slabs s;
    for (int a = 0; a < 3; ++a) s[size_t(a)].assign(size_t(f.used[a]), CellStats{});
    const int64_t shift = std::countr_zero(uint64_t(f.cw / g.cw));
    const glm::i64vec3 q0 = (f.lo - g.lo) / g.cw, span = f.slabs << shift;
    for (int64_t z = 0; z < span.z; ++z)
        for (int64_t y = 0; y < span.y; ++y) {
            const size_t row = size_t(((q0.z + z) * g.dims.y + q0.y + y) * g.dims.x + q0.x);
            for (int64_t x = 0; x < span.x; ++x) {
                const CellStats& c = g.cubes[row + size_t(x)];
                if (c.levelMask == 0) continue;
                const int64_t q[3] = {x >> shift, y >> shift, z >> shift};
                for (int a = 0; a < 3; ++a)
                    if (f.used[a] > 0) s[size_t(a)][size_t(q[a])].merge(c);
            }
        }
    return s;
}

bool brickShaped(const CellStats& in, glm::i64vec3& dims) {
    const int32_t level = in.minLevel();
    if (in.levelMask == 0 || level != in.maxLevel()) return false;
    const int64_t w = amr::cellWidth(level);
    dims = (glm::i64vec3(in.hi) - glm::i64vec3(in.lo)) / w;
    if (dims.x > kMaxBrickCells || dims.y > kMaxBrickCells || dims.z > kMaxBrickCells) return false;
    return uint64_t(dims.x * dims.y * dims.z) == in.count;  // else not completely filled
}

}  // namespace amrvk::accel
