#include "accel/brick_plan.h"

#include <algorithm>
#include <cstddef>

namespace amrvk::accel {

BrickPlan::BrickPlan(const CubeGrid& g, size_t min, const CellStats& root, const SplitFrame& f)
    : grid(g), minCells(min) {
    nodes.push_back({root, (f.lo - g.lo) / g.cw, (f.hi - g.lo) / g.cw});
    grow(0);
}

void BrickPlan::grow(uint32_t i) {
    nodes[i].leafBegin = uint32_t(leaves.size());
    const CellStats in = nodes[i].info;
    SplitChoice c;
    glm::i64vec3 dims;
    if (in.count >= minCells && !brickShaped(in, dims)) {
        const SplitFrame f = frameOf(in);
        if (f.cw >= grid.cw) c = chooseSplit(f, slabsFromCubes(grid, f));
    }
    if (c.axis < 0 || !c.sidesFromSlabs) {
        leaves.push_back(i);
        nodes[i].leafEnd = uint32_t(leaves.size());
        return;
    }
    const uint32_t l = uint32_t(nodes.size());
    Node left{c.left, nodes[i].qlo, nodes[i].qhi}, right{c.right, nodes[i].qlo, nodes[i].qhi};
    left.qhi[c.axis] = right.qlo[c.axis] = (c.plane - grid.lo[c.axis]) / grid.cw;
    nodes[i].axis = c.axis;
    nodes[i].plane = int32_t(c.plane);  // inside the node's int32 bounds
    nodes[i].left = l;
    nodes.push_back(left);
    nodes.push_back(right);
    grow(l);
    grow(l + 1);
    nodes[i].leafEnd = uint32_t(leaves.size());
}

std::vector<uint32_t> BrickPlan::leafOfCube() const {
    const glm::i64vec3 d = boxDims(), o = nodes[0].qlo;
    std::vector<uint32_t> out(size_t(d.x * d.y * d.z), UINT32_MAX);
    for (uint32_t k = 0; k < leaves.size(); ++k) {
        const Node& n = nodes[leaves[k]];
        for (int64_t z = n.qlo.z - o.z; z < n.qhi.z - o.z; ++z)
            for (int64_t y = n.qlo.y - o.y; y < n.qhi.y - o.y; ++y)
                std::fill_n(out.begin() + std::ptrdiff_t((z * d.y + y) * d.x + n.qlo.x - o.x), n.qhi.x - n.qlo.x, k);
    }
    return out;
}

}  // namespace amrvk::accel
