#include "accel/support_range.h"

#include <algorithm>
#include <cmath>

#include "accel/abrs.h"
#include "core/error.h"
#include "core/parallel.h"

namespace amrvk::accel {

namespace {

// Half-voxel coordinates beyond any int32 voxel corner (|corner| < 2^31, so |2 corner| < 2^33):
// clamping a query coordinate here changes no decision and keeps the integer arithmetic exact.
constexpr double kFar = 1099511627776.0;  // 2^40

int64_t toLattice(double halfUnits) { return int64_t(std::clamp(halfUnits, -kFar, kFar)); }

bool contains(const glm::i64vec3& qlo, const glm::i64vec3& qhi, const glm::i64vec3& lo,
              const glm::i64vec3& hi) {
    return lo.x >= qlo.x && lo.y >= qlo.y && lo.z >= qlo.z && hi.x <= qhi.x && hi.y <= qhi.y &&
           hi.z <= qhi.z;
}

bool disjoint(const glm::i64vec3& qlo, const glm::i64vec3& qhi, const glm::i64vec3& lo,
              const glm::i64vec3& hi) {
    return lo.x > qhi.x || lo.y > qhi.y || lo.z > qhi.z || hi.x < qlo.x || hi.y < qlo.y ||
           hi.z < qlo.z;
}

// True when extending r by `part` cannot change r (also for an empty `part`).
bool within(const ValueRange& part, const ValueRange& r) {
    return part.lo >= r.lo && part.hi <= r.hi;
}

}  // namespace

SupportRangeQuery::SupportRangeQuery(const BrickSet& bricks, std::span<const float> brickValues)
    : mBricks(&bricks), mValues(brickValues) {
    AMRVK_CHECK(brickValues.size() == bricks.slotCount(), "support ranges: ", brickValues.size(),
                " brick values for ", bricks.slotCount(), " brick slots");
    for (uint32_t bi = 0; bi < bricks.bricks.size(); ++bi) {
        const Brick& b = bricks.bricks[bi];
        const int64_t w = b.cellWidth();
        const glm::i64vec3 lower2 = glm::i64vec3(b.lower) * int64_t{2};
        for (int32_t z = 0; z < b.size.z; z += kSupportChunkCells)
            for (int32_t y = 0; y < b.size.y; y += kSupportChunkCells)
                for (int32_t x = 0; x < b.size.x; x += kSupportChunkCells) {
                    Chunk c;
                    c.k0 = {x, y, z};
                    const glm::ivec3 k1 = glm::min(c.k0 + kSupportChunkCells, b.size);
                    c.brick = bi;
                    // Cell k's support is [2L + 2kw - w, 2L + 2kw + 3w] in half units.
                    c.lo = lower2 + glm::i64vec3(c.k0) * (2 * w) - w;
                    c.hi = lower2 + glm::i64vec3(k1) * (2 * w) + w;
                    for (int32_t kz = c.k0.z; kz < k1.z; ++kz)
                        for (int32_t ky = c.k0.y; ky < k1.y; ++ky) {
                            const float* row =
                                brickValues.data() + b.begin +
                                (size_t(kz) * size_t(b.size.y) + size_t(ky)) * size_t(b.size.x);
                            for (int32_t kx = c.k0.x; kx < k1.x; ++kx)
                                if (!std::isnan(row[kx])) c.range.extend(row[kx]);
                        }
                    mChunks.push_back(c);
                }
    }
    if (mChunks.empty()) return;
    std::vector<BoxD> boxes(mChunks.size());
    for (size_t i = 0; i < mChunks.size(); ++i)
        boxes[i] = {glm::dvec3(mChunks[i].lo) * 0.5, glm::dvec3(mChunks[i].hi) * 0.5};
    mBvh = buildBvh(boxes);
    // Children are created after their parent, so a reverse sweep sees children first.
    mNodes.resize(mBvh.nodes.size());
    for (size_t n = mBvh.nodes.size(); n-- > 0;) {
        const BvhNode& node = mBvh.nodes[n];
        NodeBounds nb{glm::i64vec3(INT64_MAX), glm::i64vec3(INT64_MIN), {}};
        auto add = [&](const glm::i64vec3& lo, const glm::i64vec3& hi, const ValueRange& r) {
            nb.lo = glm::min(nb.lo, lo);
            nb.hi = glm::max(nb.hi, hi);
            nb.range.extend(r);
        };
        if (node.count > 0) {
            for (uint32_t i = 0; i < node.count; ++i) {
                const Chunk& c = mChunks[mBvh.primIds[node.first + i]];
                add(c.lo, c.hi, c.range);
            }
        } else {
            for (uint32_t child : {node.first, node.first + 1})
                add(mNodes[child].lo, mNodes[child].hi, mNodes[child].range);
        }
        mNodes[n] = nb;
    }
}

void SupportRangeQuery::scanChunk(const Chunk& c, glm::i64vec3 qlo, glm::i64vec3 qhi,
                                  ValueRange& r) const {
    const Brick& b = mBricks->bricks[c.brick];
    const int64_t w = b.cellWidth();
    glm::i64vec3 k0, k1;  // inclusive cell index range whose supports reach the box
    for (int a = 0; a < 3; ++a) {
        const int64_t lower2 = 2 * int64_t(b.lower[a]);
        k0[a] = std::max<int64_t>(c.k0[a], ceilDiv(qlo[a] - lower2 - 3 * w, 2 * w));
        const int64_t last = std::min(c.k0[a] + kSupportChunkCells, b.size[a]) - 1;
        k1[a] = std::min<int64_t>(last, floorDiv(qhi[a] - lower2 + w, 2 * w));
        if (k0[a] > k1[a]) return;
    }
    const float* values = mValues.data() + b.begin;
    for (int64_t z = k0.z; z <= k1.z; ++z)
        for (int64_t y = k0.y; y <= k1.y; ++y) {
            const float* row = values + (z * b.size.y + y) * b.size.x;
            for (int64_t x = k0.x; x <= k1.x; ++x)
                if (!std::isnan(row[x])) r.extend(row[x]);
        }
}

ValueRange SupportRangeQuery::query(const BoxD& box) const {
    ValueRange r;
    glm::i64vec3 qlo, qhi;  // the box in half units, shrunk onto the lattice (no decision changes)
    for (int a = 0; a < 3; ++a) {
        AMRVK_CHECK(!std::isnan(box.lo[a]) && !std::isnan(box.hi[a]),
                    "support range query: NaN box coordinate on axis ", a);
        if (box.lo[a] > box.hi[a]) return r;
        // A closed lattice interval [s, t] meets [lo, hi] iff s <= floor(2 hi) and t >= ceil(2 lo)
        // (in half units); this holds even when no lattice point lies inside [2 lo, 2 hi].
        qlo[a] = toLattice(std::ceil(2.0 * box.lo[a]));
        qhi[a] = toLattice(std::floor(2.0 * box.hi[a]));
    }
    if (mNodes.empty()) return r;
    uint32_t stack[shared::kBvhStackSize];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const uint32_t n = stack[--top];
        const NodeBounds& nb = mNodes[n];
        if (within(nb.range, r) || disjoint(qlo, qhi, nb.lo, nb.hi)) continue;
        if (contains(qlo, qhi, nb.lo, nb.hi)) {
            r.extend(nb.range);
            continue;
        }
        const BvhNode& node = mBvh.nodes[n];
        if (node.count == 0) {
            stack[top++] = node.first + 1;
            stack[top++] = node.first;
            continue;
        }
        for (uint32_t i = 0; i < node.count; ++i) {
            const Chunk& c = mChunks[mBvh.primIds[node.first + i]];
            if (within(c.range, r) || disjoint(qlo, qhi, c.lo, c.hi)) continue;
            if (contains(qlo, qhi, c.lo, c.hi))
                r.extend(c.range);
            else
                scanChunk(c, qlo, qhi, r);
        }
    }
    return r;
}

ValueRange SupportRangeQuery::majorantRange(const BoxD& box, double margin) const {
    const double grow = 0.5 * double(marginHalfUnits(margin));
    return padForGpu(query({box.lo - grow, box.hi + grow}));
}

uint64_t SupportRangeQuery::memoryBytes() const {
    return mChunks.size() * sizeof(Chunk) + mBvh.memoryBytes() + mNodes.size() * sizeof(NodeBounds);
}

std::vector<ValueRange> brickBoundsRanges(const SupportRangeQuery& query, const BrickSet& bricks, double margin) {
    std::vector<ValueRange> out(bricks.bricks.size());
    parallelFor(0, out.size(), [&](size_t i) {
        const amr::Box3l b = bricks.bricks[i].bounds();
        out[i] = query.majorantRange({glm::dvec3(b.lower), glm::dvec3(b.upper)}, margin);
    });
    return out;
}

std::vector<ValueRange> brickDomainRanges(const SupportRangeQuery& query, const BrickSet& bricks, double margin) {
    std::vector<ValueRange> out(bricks.bricks.size());
    parallelFor(0, out.size(), [&](size_t i) {
        const HalfBox d = brickDomain(bricks.bricks[i]);
        out[i] = query.majorantRange({d.lower(), d.upper()}, margin);
    });
    return out;
}

}  // namespace amrvk::accel
