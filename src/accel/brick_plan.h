#pragma once
// The top of a kd subtree of the brick build decided on a cube grid alone (accel/brick_build.h:
// "planned top levels"). While a node keeps the grid's coarsest width or a coarser one its slabs
// come from the cubes (slabsFromCubes), so its split (chooseSplit, as the build's split over the
// cells would choose it) and its sides' statistics need no pass over its cells. Leaves of the plan:
// nodes of fewer than `minCells` cells, whose coarsest width is below the cubes', brick-shaped, or
// split on an axis without slabs.
// Every leaf is a box of whole cubes; the leaves tile the root's box, in left-to-right order.
#include <glm/glm.hpp>

#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "accel/brick_split.h"
#include "amr/model.h"

namespace amrvk::accel {

struct BrickPlan {
    struct Node {
        CellStats info;
        glm::i64vec3 qlo{0}, qhi{0};          // the node's region, in the grid's cubes [qlo, qhi)
        int axis = -1;                        // split axis; -1 for a leaf
        int32_t plane = 0;                    // voxel space
        uint32_t left = 0;                    // children: nodes[left], nodes[left + 1]
        uint32_t leafBegin = 0, leafEnd = 0;  // its leaves: leaves[leafBegin, leafEnd)
    };
    const CubeGrid& grid;  // kept by reference: it must outlive the plan
    size_t minCells;
    std::vector<Node> nodes;       // nodes[0] is the root
    std::vector<uint32_t> leaves;  // node indices, left to right

    // Plans the node of statistics `root` and frame `f` (frameOf(root)) on `g`, which serves it
    // (g.cw divides f.cw, the frame's box lies inside the grid's).
    BrickPlan(const CubeGrid& g, size_t min, const CellStats& root, const SplitFrame& f);

    // The plan root's box of cubes, x fastest: each plan allocates and fills a table of its own
    // cubes only, not of the whole (ancestor's) grid, which the ~256 plans below the root shared.
    glm::i64vec3 boxDims() const { return nodes[0].qhi - nodes[0].qlo; }
    // The index in the root's box of a cell inside it (its lower corner's cube).
    size_t boxCubeOf(const amr::Cell& c) const {
        const int64_t shift = std::countr_zero(uint64_t(grid.cw));
        const glm::i64vec3 q = ((glm::i64vec3(c.lower) - grid.lo) >> shift) - nodes[0].qlo, d = boxDims();
        return size_t((q.z * d.y + q.y) * d.x + q.x);
    }
    // Cube of the root's box -> index in `leaves`; the leaves tile the box.
    std::vector<uint32_t> leafOfCube() const;

private:
    void grow(uint32_t i);
};

}  // namespace amrvk::accel
