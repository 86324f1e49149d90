#include "accel/bvh.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace amrvk::accel {

float roundDown(double v) {
    float f = static_cast<float>(v);
    return double(f) > v ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}
float roundUp(double v) {
    float f = static_cast<float>(v);
    return double(f) < v ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

Bvh buildBvh(std::span<const BoxD> boxes, uint32_t maxLeafSize) {
    Bvh bvh;
    AMRVK_CHECK(!boxes.empty(), "cannot build a BVH over no boxes");
    // The boxes are partitioned as they are, not through their ids: a split's nth_element then
    // reads contiguous memory (2M macrocells of grid-bvh: the partitions were most of a TF edit).
    // The comparisons and their order are those on the ids, so the tree is the same.
    struct Item {
        BoxD box;
        uint32_t id;
    };
    std::vector<Item> items(boxes.size());
    for (uint32_t i = 0; i < boxes.size(); ++i) items[i] = {boxes[i], i};
    struct Task {
        uint32_t node, begin, end, depth;
    };
    bvh.nodes.push_back({});
    std::vector<Task> stack{{0, 0, uint32_t(boxes.size()), 0}};
    while (!stack.empty()) {
        Task t = stack.back();
        stack.pop_back();
        glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
        glm::dvec3 clo = lo, chi = hi;
        for (uint32_t i = t.begin; i < t.end; ++i) {
            const BoxD& b = items[i].box;
            lo = glm::min(lo, b.lo);
            hi = glm::max(hi, b.hi);
            glm::dvec3 c = 0.5 * (b.lo + b.hi);
            clo = glm::min(clo, c);
            chi = glm::max(chi, c);
        }
        BvhNode& node = bvh.nodes[t.node];
        node.lo = {roundDown(lo.x), roundDown(lo.y), roundDown(lo.z)};
        node.hi = {roundUp(hi.x), roundUp(hi.y), roundUp(hi.z)};
        const uint32_t n = t.end - t.begin;
        glm::dvec3 ext = chi - clo;
        int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
        // Traversal stacks hold kBvhStackSize entries: depth stays within kBvhMaxDepth.
        if (n <= maxLeafSize || ext[axis] <= 0 || t.depth >= shared::kBvhMaxDepth) {
            node.first = t.begin;
            node.count = n;
            continue;
        }
        uint32_t mid = t.begin + n / 2;
        std::nth_element(items.begin() + t.begin, items.begin() + mid, items.begin() + t.end,
                         [axis](const Item& a, const Item& b) {
                             return a.box.lo[axis] + a.box.hi[axis] < b.box.lo[axis] + b.box.hi[axis];
                         });
        uint32_t left = uint32_t(bvh.nodes.size());
        bvh.nodes[t.node].first = left;
        bvh.nodes[t.node].count = 0;
        bvh.nodes.push_back({});
        bvh.nodes.push_back({});
        stack.push_back({left + 1, mid, t.end, t.depth + 1});
        stack.push_back({left, t.begin, mid, t.depth + 1});
    }
    bvh.primIds.resize(items.size());
    for (size_t i = 0; i < items.size(); ++i) bvh.primIds[i] = items[i].id;
    return bvh;
}

}  // namespace amrvk::accel
