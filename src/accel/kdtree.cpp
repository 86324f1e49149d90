#include "accel/kdtree.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <utility>

#include "core/error.h"
#include "core/stats.h"

namespace amrvk::accel {

// Ranges are majorant ranges (SupportRangeQuery::majorantRange): a slab's range covers the slab
// grown by the position margin and padded for the GPU, and so does a union of slab ranges.
// Cost and pruning. Every split of a leaf evaluates the distinct integer planes among the 7
// binned candidates per axis (8 bins), i.e. at most 8 slabs per axis. The closed range of a box
// is the union of the closed ranges of slabs that cover it (a support meets the union iff it
// meets one slab), so one SupportRangeQuery per slab plus prefix/suffix unions give the exact
// ranges of all left/right candidates: <= 24 queries per split instead of 42, each over a
// thinner box. The winning split's children ranges come from the same unions (no extra query).
// A leaf's split is evaluated only when it is popped as the costliest leaf, so a tree of K leaves
// costs K - 1 evaluations: O(K (log K + 24 Q)), Q being one range query (BVH descent over the
// chunks that straddle the slab's faces; ranges that cannot widen the result are skipped).
// Leaves with mu = 0 (cost 0) or one voxel wide on every axis never enter the queue.

namespace {

struct Leaf {
    glm::i64vec3 lo, hi;  // voxel space, closed for ranges, half-open for tiling
    ValueRange range;
    float mu = 0;
    double cost = 0;
};

double boxCost(const glm::i64vec3& lo, const glm::i64vec3& hi, float mu) {
    if (mu <= 0) return 0;
    const glm::dvec3 s(hi - lo);
    const double area = 2.0 * (s.x * s.y + s.y * s.z + s.z * s.x);
    return area * std::sqrt(s.x * s.x + s.y * s.y + s.z * s.z) * double(mu);
}

bool splittable(const Leaf& l) {
    const glm::i64vec3 s = l.hi - l.lo;
    return s.x >= 2 || s.y >= 2 || s.z >= 2;
}

class KdBuilder {
public:
    KdBuilder(const SupportRangeQuery& ranges, const std::function<float(float, float)>& maxAlpha, double margin)
        : mRanges(ranges), mMaxAlpha(maxAlpha), mMargin(margin) {}

    Leaf makeLeaf(const glm::i64vec3& lo, const glm::i64vec3& hi, const ValueRange& range) const {
        Leaf l{lo, hi, range, 0.0f, 0.0};
        if (!range.empty()) {
            l.mu = mMaxAlpha(range.lo, range.hi);
            AMRVK_CHECK(std::isfinite(l.mu) && l.mu >= 0, "kd-tree: transfer function majorant ",
                        l.mu, " over [", range.lo, ", ", range.hi, "] is not a finite value >= 0");
        }
        l.cost = boxCost(lo, hi, l.mu);
        return l;
    }

    ValueRange rangeOf(const glm::i64vec3& lo, const glm::i64vec3& hi) const {
        return mRanges.majorantRange({glm::dvec3(lo), glm::dvec3(hi)}, mMargin);
    }

    // The cheapest binned split of `l` (children in left/right); false when no plane exists.
    bool split(const Leaf& l, Leaf& left, Leaf& right) const {
        constexpr int kBins = 8;
        bool found = false;
        double best = 0;
        for (int axis = 0; axis < 3; ++axis) {
            const int64_t lo = l.lo[axis], ext = l.hi[axis] - lo;
            if (ext < 2) continue;
            // Bin boundaries rounded to the nearest integer, kept strictly inside, deduplicated.
            int64_t planes[kBins + 1];
            int count = 0;
            planes[count++] = lo;
            for (int i = 1; i < kBins; ++i) {
                int64_t p = std::clamp(lo + (ext * i + kBins / 2) / kBins, lo + 1, lo + ext - 1);
                if (p > planes[count - 1]) planes[count++] = p;
            }
            planes[count++] = lo + ext;
            // Slab j = [planes[j], planes[j + 1]] (closed); prefix/suffix unions give L/R ranges.
            ValueRange slab[kBins], suffix[kBins + 1];
            for (int j = 0; j + 1 < count; ++j) {
                glm::i64vec3 slo = l.lo, shi = l.hi;
                slo[axis] = planes[j];
                shi[axis] = planes[j + 1];
                slab[j] = rangeOf(slo, shi);
            }
            for (int j = count - 2; j >= 0; --j) {
                suffix[j] = suffix[j + 1];
                suffix[j].extend(slab[j]);
            }
            ValueRange prefix = slab[0];
            for (int k = 1; k + 1 < count; ++k) {
                glm::i64vec3 lhi = l.hi, rlo = l.lo;
                lhi[axis] = planes[k];
                rlo[axis] = planes[k];
                Leaf a = makeLeaf(l.lo, lhi, prefix), b = makeLeaf(rlo, l.hi, suffix[k]);
                const double c = a.cost + b.cost;
                if (!found || c < best) {
                    found = true;
                    best = c;
                    left = a;
                    right = b;
                }
                prefix.extend(slab[k]);
            }
        }
        return found;
    }

private:
    const SupportRangeQuery& mRanges;
    const std::function<float(float, float)>& mMaxAlpha;
    double mMargin;  // positionMargin of the root box
};

}  // namespace

KdTree buildKdTree(const SupportRangeQuery& ranges, const amr::Box3l& bounds,
                   const std::function<float(float, float)>& maxAlpha, const KdTreeParams& params) {
    AMRVK_CHECK(params.maxLeaves >= 1, "--kd-leaves ", params.maxLeaves, ": must be at least 1");
    AMRVK_CHECK(!bounds.empty(), "kd-tree: empty root box [", bounds.lower.x, ",", bounds.lower.y,
                ",", bounds.lower.z, "]-[", bounds.upper.x, ",", bounds.upper.y, ",",
                bounds.upper.z, "]: pass the union of the leaf cells");
    Timer timer;
    KdBuilder builder(ranges, maxAlpha, positionMargin(bounds));
    std::vector<Leaf> leaves;
    leaves.reserve(std::min<uint32_t>(params.maxLeaves, 1u << 16));  // grows past that as it splits
    leaves.push_back(
        builder.makeLeaf(bounds.lower, bounds.upper, builder.rangeOf(bounds.lower, bounds.upper)));
    // Costliest first; equal costs pop the newer leaf first (deterministic either way).
    std::priority_queue<std::pair<double, uint32_t>> queue;
    auto enqueue = [&](uint32_t i) {
        if (leaves[i].cost > 0 && splittable(leaves[i])) queue.push({leaves[i].cost, i});
    };
    enqueue(0);
    while (leaves.size() < params.maxLeaves && !queue.empty()) {
        const uint32_t i = queue.top().second;
        queue.pop();
        Leaf left, right;
        if (!builder.split(leaves[i], left, right)) continue;
        leaves[i] = left;
        leaves.push_back(right);
        enqueue(i);
        enqueue(uint32_t(leaves.size() - 1));
    }
    KdTree tree;
    tree.bounds = bounds;
    tree.leaves.reserve(leaves.size());
    tree.leafRanges.reserve(leaves.size());
    tree.leafMajorants.reserve(leaves.size());
    for (const Leaf& l : leaves) {
        tree.leaves.push_back({glm::dvec3(l.lo), glm::dvec3(l.hi)});
        tree.leafRanges.push_back(l.range);
        tree.leafMajorants.push_back(l.mu);
    }
    tree.buildSeconds = timer.seconds();
    return tree;
}

}  // namespace amrvk::accel
