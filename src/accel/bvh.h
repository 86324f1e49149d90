#pragma once
// Binary bounding-volume hierarchy over axis-aligned boxes, for point queries ("every primitive
// whose box contains P"). Node boxes are float, rounded outward from the double input, so they
// are conservative; callers test containment exactly against their own primitive boxes.
#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

#include "shared/amr_gpu.h"

namespace amrvk::accel {

// The node layout is the GPU's (shaders/shared/amr_gpu.h): inner nodes have count 0 and children
// first, first + 1; leaves list primIds[first, first + count).
using BvhNode = shared::BvhNodeGpu;

struct Bvh {
    std::vector<BvhNode> nodes;      // nodes[0] is the root
    std::vector<uint32_t> primIds;   // leaf slots -> primitive index
    uint64_t memoryBytes() const {
        return nodes.size() * sizeof(BvhNode) + primIds.size() * sizeof(uint32_t);
    }
    // Calls visit(primId) for every primitive whose (conservative) box contains p.
    template <typename Visit>
    void forEachContaining(glm::dvec3 p, Visit&& visit) const;
};

struct BoxD {
    glm::dvec3 lo, hi;
};

// v rounded to float outwards: the largest float <= v / the smallest float >= v.
float roundDown(double v);
float roundUp(double v);

// Median split on the longest centroid axis, leaves of at most maxLeafSize primitives.
Bvh buildBvh(std::span<const BoxD> boxes, uint32_t maxLeafSize = 4);

template <typename Visit>
void Bvh::forEachContaining(glm::dvec3 p, Visit&& visit) const {
    if (nodes.empty()) return;
    uint32_t stack[shared::kBvhStackSize];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const BvhNode& n = nodes[stack[--top]];
        if (p.x < n.lo.x || p.y < n.lo.y || p.z < n.lo.z || p.x > n.hi.x || p.y > n.hi.y ||
            p.z > n.hi.z)
            continue;
        if (n.count > 0) {
            for (uint32_t i = 0; i < n.count; ++i) visit(primIds[n.first + i]);
        } else {
            stack[top++] = n.first + 1;
            stack[top++] = n.first;
        }
    }
}

}  // namespace amrvk::accel
