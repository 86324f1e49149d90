#include "accel/abrs.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "accel/support_range.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/stats.h"

namespace amrvk::accel {

HalfBox brickDomain(const Brick& brick) {
    const int64_t w = brick.cellWidth();
    glm::i64vec3 lo = glm::i64vec3(brick.lower) * int64_t{2} - w;
    glm::i64vec3 hi = (glm::i64vec3(brick.lower) + glm::i64vec3(brick.size) * w) * int64_t{2} + w;
    return {lo, hi};
}

namespace {

bool overlapsWithVolume(const HalfBox& a, const HalfBox& b) {
    return a.lo.x < b.hi.x && b.lo.x < a.hi.x && a.lo.y < b.hi.y && b.lo.y < a.hi.y &&
           a.lo.z < b.hi.z && b.lo.z < a.hi.z;
}

class AbrBuilder {
public:
    AbrBuilder(const BrickSet& bricks, AbrSet& out) : mBricks(bricks), mOut(out) {
        mDomains.reserve(bricks.bricks.size());
        for (const Brick& b : bricks.bricks) mDomains.push_back(brickDomain(b));
    }

    void run() {
        HalfBox all{glm::i64vec3(std::numeric_limits<int64_t>::max()),
                    glm::i64vec3(std::numeric_limits<int64_t>::min())};
        std::vector<uint32_t> prims(mDomains.size());
        for (uint32_t i = 0; i < prims.size(); ++i) {
            prims[i] = i;
            all.lo = glm::min(all.lo, mDomains[i].lo);
            all.hi = glm::max(all.hi, mDomains[i].hi);
        }
        struct Task {
            HalfBox box;
            std::vector<uint32_t> prims;
        };
        std::vector<Task> stack;
        stack.push_back({all, std::move(prims)});
        while (!stack.empty()) {
            Task t = std::move(stack.back());
            stack.pop_back();
            if (t.prims.empty()) continue;
            int axis = -1;
            int64_t plane = 0;
            findSplit(t.box, t.prims, axis, plane);
            if (axis < 0) {
                emitLeaf(t.box, t.prims);
                continue;
            }
            HalfBox left = t.box, right = t.box;
            left.hi[axis] = plane;
            right.lo[axis] = plane;
            std::vector<uint32_t> l, r;
            for (uint32_t p : t.prims) {
                if (overlapsWithVolume(mDomains[p], left)) l.push_back(p);
                if (overlapsWithVolume(mDomains[p], right)) r.push_back(p);
            }
            stack.push_back({right, std::move(r)});
            stack.push_back({left, std::move(l)});
        }
    }

private:
    // A domain face strictly inside the box, closest to its centre, on the widest axis that has one.
    void findSplit(const HalfBox& box, const std::vector<uint32_t>& prims, int& axis,
                   int64_t& plane) const {
        int order[3] = {0, 1, 2};
        glm::i64vec3 ext = box.hi - box.lo;
        std::stable_sort(order, order + 3, [&](int a, int b) { return ext[a] > ext[b]; });
        for (int a : order) {
            const int64_t c2 = box.lo[a] + box.hi[a];  // twice the centre
            int64_t best = 0, bestDist = std::numeric_limits<int64_t>::max();
            for (uint32_t p : prims) {
                for (int64_t f : {mDomains[p].lo[a], mDomains[p].hi[a]}) {
                    if (f <= box.lo[a] || f >= box.hi[a]) continue;
                    int64_t d = std::abs(2 * f - c2);
                    if (d < bestDist || (d == bestDist && f < best)) {
                        bestDist = d;
                        best = f;
                    }
                }
            }
            if (bestDist != std::numeric_limits<int64_t>::max()) {
                axis = a;
                plane = best;
                return;
            }
        }
        axis = -1;
    }

    void emitLeaf(const HalfBox& box, std::vector<uint32_t>& prims) {
        std::sort(prims.begin(), prims.end());
        Abr abr;
        abr.box = box;
        abr.brickBegin = static_cast<uint32_t>(mOut.brickList.size());
        abr.brickCount = static_cast<uint32_t>(prims.size());
        abr.finestLevel = amr::kMaxLevel;
        for (uint32_t p : prims) abr.finestLevel = std::min(abr.finestLevel, mBricks.bricks[p].level);
        mOut.brickList.insert(mOut.brickList.end(), prims.begin(), prims.end());
        mOut.abrs.push_back(abr);
    }

    const BrickSet& mBricks;
    AbrSet& mOut;
    std::vector<HalfBox> mDomains;
};

}  // namespace

AbrSet buildAbrs(const BrickSet& bricks) {
    Timer timer;
    AbrSet out;
    AMRVK_CHECK(!bricks.bricks.empty(), "cannot build ABRs without bricks");
    AbrBuilder(bricks, out).run();
    out.buildSeconds = timer.seconds();
    return out;
}

std::vector<ValueRange> computeAbrValueRanges(const AbrSet& abrs, const SupportRangeQuery& query, double margin) {
    std::vector<ValueRange> ranges(abrs.abrs.size());
    parallelFor(0, ranges.size(), [&](size_t ai) {
        const HalfBox& box = abrs.abrs[ai].box;
        ranges[ai] = query.majorantRange({box.lower(), box.upper()}, margin);
    });
    return ranges;
}

}  // namespace amrvk::accel
