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

struct BvhNode {
    glm::vec3 lo;
    uint32_t first;  // inner: index of the left child (right = first + 1); leaf: first primitive slot
    glm::vec3 hi;
    uint32_t count;  // 0 for inner nodes, else primitives in this leaf
};
static_assert(sizeof(BvhNode) == 32);

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
