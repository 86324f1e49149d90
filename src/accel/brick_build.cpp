#include "accel/brick_build.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <memory>
#include <mutex>
#include <vector>

#include "accel/brick_plan.h"
#include "accel/brick_split.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/stats.h"

namespace amrvk::accel {

namespace {

// The statistics of all cells from the model's summary (the pass over the cells it took), as
// BrickBuilder::info would gather them: the volume is the same sum of powers of 8.
CellStats rootStats(const amr::ModelSummary& s, size_t cells) {
    CellStats in;
    for (size_t l = 0; l < s.cellsPerLevel.size(); ++l)
        if (s.cellsPerLevel[l] > 0) in.levelMask |= 1u << l;
    AMRVK_CHECK(in.levelMask != 0 && cells < UINT32_MAX, "internal: a summary of ", cells, " cells");
    in.count = uint32_t(cells);
    in.volume = s.leafVolume;
    in.lo = glm::ivec3(s.bounds.lower);  // validated cells end at or below 2^31-1
    in.hi = glm::ivec3(s.bounds.upper);
    return in;
}

// The kd build over the model's own arrays: cells and every field are partitioned together, in
// place, so no per-cell copy exists; leaves are then put in x-fastest order inside their brick.
class BrickBuilder {
public:
    BrickBuilder(amr::Model& model, size_t planCells) : mModel(model), mCells(model.cells), mPlanCells(planCells) {
        for (amr::Field& f : model.fields) mFields.push_back(f.values.data());
    }

    // The bar of cells placed in bricks, drawn by whichever thread gets to it (at most every 0.1 s).
    void showProgress(uint64_t placed) {
        if (std::unique_lock lock(mBarMutex, std::try_to_lock); lock.owns_lock()) mBar.update(placed, mCells.size());
    }
    void finishProgress(bool complete) {
        if (complete) mBar.update(mCells.size(), mCells.size());
        mBar.finish();
    }

    // A node of the kd build: cells [b, e), their statistics, and an ancestor's cube grid.
    struct Node {
        size_t b, e;
        CellStats info;
        std::shared_ptr<const CubeGrid> cubes;
    };

    // Builds the subtree over cells [begin, end) (bounds `info`; `cubes`: an ancestor's cube grid)
    // and returns its bricks in left-to-right order. The two sides of a node of at least
    // kParallelCells cells (or the leaves of its plan) are built concurrently: they own disjoint
    // parts of the arrays, so the result does not depend on the schedule.
    std::vector<Brick> build(size_t begin, size_t end, const CellStats& info,
                             std::shared_ptr<const CubeGrid> cubes = nullptr) {
        std::vector<Brick> bricks;
        std::vector<Node> stack{{begin, end, info, std::move(cubes)}};
        while (!stack.empty()) {
            Node n = std::move(stack.back());
            stack.pop_back();
            if (tryLeaf(n.b, n.e, n.info, bricks)) continue;
            if (n.e - n.b >= mPlanCells) {
                std::vector<Node> parts = planned(n);
                if (parts.size() >= 2 && n.e - n.b >= kParallelCells) {
                    std::vector<std::vector<Brick>> built(parts.size());
                    parallelFor(0, parts.size(), [&](size_t k) {
                        built[k] = build(parts[k].b, parts[k].e, parts[k].info, parts[k].cubes);
                    });
                    for (const std::vector<Brick>& p : built) bricks.insert(bricks.end(), p.begin(), p.end());
                    continue;
                }
                if (parts.size() >= 2) {
                    for (size_t k = parts.size(); k-- > 0;) stack.push_back(std::move(parts[k]));
                    continue;
                }
            }
            CellStats left, right;
            const size_t mid = split(n.b, n.e, n.info, n.cubes, left, right);
            if (n.e - n.b >= kParallelCells) {
                std::vector<Brick> l, r;
                parallelInvoke([&] { l = build(n.b, mid, left, n.cubes); },
                               [&] { r = build(mid, n.e, right, n.cubes); });
                bricks.insert(bricks.end(), l.begin(), l.end());
                bricks.insert(bricks.end(), r.begin(), r.end());
                continue;
            }
            stack.push_back({mid, n.e, right, n.cubes});
            stack.push_back({n.b, mid, left, std::move(n.cubes)});
        }
        return bricks;
    }

    bool moved() const { return mMoved.load(); }

    CellStats info(size_t b, size_t e) const {
        return parallelReduce<CellStats>(
            b, e, 64,
            [&](size_t lo, size_t hi) {
                CellStats in;
                for (size_t i = lo; i < hi; ++i) in.add(mCells[i]);
                return in;
            },
            [](CellStats& a, CellStats&& o) { a.merge(o); });
    }

private:
    static constexpr size_t kParallelCells = size_t{1} << 15;
    // Nodes at least this large gather their slab statistics on every core.
    static constexpr size_t kParallelSlabCells = size_t{1} << 20;
    // A node with at least this many cells per coarse cube (cw^3) gathers a cube grid (one update
    // per cell) that its descendants read their slabs from, instead of gathering three slab arrays
    // from their cells at every split (which took 40% of the build at 10^8 cells with 16 here).
    static constexpr double kCellsPerCube = 4;
    // Its cubes are halved while they keep at least this many cells each (40 / 32 = 1.25 bytes per
    // cell), so that one grid serves the levels below the node's coarsest too (10^8-cell cloud:
    // 128^3 cubes of 32 voxels at the root serve cell widths 128, 64 and 32).
    static constexpr double kCellsPerFineCube = 32;
    // A plan stops at nodes of 1/kPlanLeaves of its root's cells (flagSort).
    static constexpr size_t kPlanLeaves = 256;
    // Nodes at least this large are partitioned on every core.
    static constexpr size_t kParallelPartitionCells = size_t{1} << 21;

    // The caller sets mMoved (once, not per swap: one shared flag written by every core).
    void swapCells(size_t i, size_t j) {
        mCells.swapCells(i, j);
        for (float* v : mFields) std::swap(v[i], v[j]);
    }

    // A node becomes a brick when it is one level, completely filled and at most kMaxBrickCells
    // wide; its cells are then put in brick order. Two cells on one slot overlap.
    bool tryLeaf(size_t b, size_t e, const CellStats& in, std::vector<Brick>& bricks) {
        glm::i64vec3 dims;
        if (!brickShaped(in, dims)) return false;
        const Brick brick{glm::ivec3(in.lo), glm::ivec3(dims), in.minLevel(), static_cast<uint32_t>(b)};
        orderBrick(brick, b, e);
        bricks.push_back(brick);
        showProgress(mPlaced.fetch_add(e - b, std::memory_order_relaxed) + (e - b));
        return true;
    }

    size_t slotOf(const Brick& br, const amr::Cell& c) const {
        const glm::i64vec3 local = (glm::i64vec3(c.lower) - glm::i64vec3(br.lower)) / br.cellWidth();
        return size_t((local.z * br.size.y + local.y) * br.size.x + local.x);
    }

    // Permutes cells [b, e) (exactly one per slot unless two overlap) into x-fastest order.
    void orderBrick(const Brick& br, size_t b, size_t e) {
        bool ordered = true;
        for (size_t i = b; i < e && ordered; ++i) ordered = slotOf(br, mCells[i]) == i - b;
        if (ordered) return;
        mMoved.store(true, std::memory_order_relaxed);
        const size_t n = e - b;
        std::vector<uint32_t> from(n, UINT32_MAX);  // slot -> position in [b, e)
        for (size_t i = b; i < e; ++i) {
            uint32_t& slot = from[slotOf(br, mCells[i])];
            if (slot != UINT32_MAX)
                AMRVK_CHECK(false, mModel.source, ": overlapping cells: ", amr::describeCell(mCells[i]), " duplicates ",
                            amr::describeCell(mCells[b + slot]));
            slot = static_cast<uint32_t>(i - b);
        }
        mCells.visitStorage([&](auto cells) {
            std::vector<typename decltype(cells)::value_type> moved(n);
            for (size_t k = 0; k < n; ++k) moved[k] = cells[b + from[k]];
            std::copy(moved.begin(), moved.end(), cells.begin() + std::ptrdiff_t(b));
        });
        std::vector<float> values(n);
        for (float* v : mFields) {
            for (size_t k = 0; k < n; ++k) values[k] = v[b + from[k]];
            std::copy(values.begin(), values.end(), v + b);
        }
    }

    // Gives the node a cube grid where its ancestor's does not serve it (cubes wider than its
    // coarsest cell width cw) and it holds at least kCellsPerCube cells per cw^3: its cells are
    // merged per cube once (one update per cell), in cubes of cw or finer (kCellsPerFineCube). A
    // descendant whose coarsest width is a multiple of the cube width holds exactly the cells of the
    // cubes in its box (every plane between them is a multiple of its cw), so it reads its slabs
    // from the grid; cubes stays null where the node is too sparse for one.
    void ensureCubes(size_t b, size_t e, const SplitFrame& f, std::shared_ptr<const CubeGrid>& cubes) const {
        if (cubes && cubes->cw <= f.cw) return;
        cubes.reset();
        const double n = double(e - b);
        auto cubesOf = [&](int64_t c) {
            const double r = double(f.cw / c);
            return double(f.slabs.x) * r * double(f.slabs.y) * r * double(f.slabs.z) * r;
        };
        if (cubesOf(f.cw) * kCellsPerCube > n) return;
        int64_t c = f.cw;
        while (c > 1 && cubesOf(c / 2) * kCellsPerFineCube <= n) c /= 2;
        cubes = gatherCubes(b, e, f.lo, c, f.slabs * (f.cw / c), size_t(cubesOf(c)));
    }

    // Slab statistics of cells [b, e) along every axis of the frame (slab k of axis a covers
    // [lo[a] + k cw, lo[a] + (k + 1) cw)); an axis with `used[a] == 0` is skipped. From the node's
    // cube grid where it has one (ensureCubes), else from its cells.
    Slabs slabStats(size_t b, size_t e, const SplitFrame& f, std::shared_ptr<const CubeGrid>& cubes) const {
        const size_t n = e - b;
        const int shift = std::countr_zero(uint64_t(f.cw));
        ensureCubes(b, e, f, cubes);
        // From the cubes unless the node is sparse in them (few cells in a wide box of fine cubes).
        if (cubes) {
            const double r = double(f.cw / cubes->cw);
            if (double(f.slabs.x) * double(f.slabs.y) * double(f.slabs.z) * r * r * r <= 16.0 * double(n) + 4096)
                return slabsFromCubes(*cubes, f);
        }
        auto gather = [&](size_t from, size_t to) {
            Slabs s;
            for (int a = 0; a < 3; ++a) s[size_t(a)].assign(size_t(f.used[a]), CellStats{});
            for (size_t i = from; i < to; ++i) {
                const amr::Cell& c = mCells[i];
                for (int a = 0; a < 3; ++a)
                    if (f.used[a] > 0) s[size_t(a)][size_t((int64_t(c.lower[a]) - f.lo[a]) >> shift)].add(c);
            }
            return s;
        };
        const uint64_t slabTotal = uint64_t(f.used.x + f.used.y + f.used.z);
        if (n < kParallelSlabCells || slabTotal * 64 > n) return gather(b, e);
        return parallelReduce<Slabs>(b, e, 16, gather, mergeSlabs);
    }

    static void mergeSlabs(Slabs& acc, Slabs&& part) {
        for (size_t a = 0; a < 3; ++a)
            for (size_t k = 0; k < acc[a].size(); ++k) acc[a][k].merge(part[a][k]);
    }

    std::shared_ptr<const CubeGrid> gatherCubes(size_t b, size_t e, glm::i64vec3 lo, int64_t cw, glm::i64vec3 dims,
                                                size_t count) const {
        const int64_t shift = std::countr_zero(uint64_t(cw));
        auto gather = [&](size_t from, size_t to) {
            Slabs s;
            s[0].assign(count, CellStats{});
            for (size_t i = from; i < to; ++i) {
                const amr::Cell& c = mCells[i];
                const glm::i64vec3 q = (glm::i64vec3(c.lower) - lo) >> shift;
                s[0][size_t((q.z * dims.y + q.y) * dims.x + q.x)].add(c);
            }
            return s;
        };
        // Every core gathers its own copy of the cubes, as many copies as keep them at most 2.5 bytes
        // per cell of the node (merging is exact in any order: the grid is the same for any count).
        const size_t n = e - b;
        const size_t copies = std::min<size_t>(size_t(threadCount()), n / (count * 16));
        Slabs s = n >= kParallelSlabCells && copies >= 2 ? parallelReduce<Slabs>(b, e, copies, gather, mergeSlabs)
                                                         : gather(b, e);
        return std::make_shared<const CubeGrid>(CubeGrid{lo, dims, cw, std::move(s[0])});
    }

    // Chooses a plane (chooseSplit) and partitions; returns the split index and the sides' bounds.
    // Planes lie on multiples of the node's coarsest cell width, so no cell straddles one: the
    // subtrees' regions are disjoint and cells in different bricks never overlap.
    size_t split(size_t b, size_t e, const CellStats& in, std::shared_ptr<const CubeGrid>& cubes, CellStats& left,
                 CellStats& right) {
        const SplitFrame f = frameOf(in);
        SplitChoice c = chooseSplit(f, slabStats(b, e, f, cubes));
        if (c.axis < 0) reportOverlap(b, e, in);
        if (c.sidesFromSlabs) {
            left = c.left;
            right = c.right;
        }
        const int32_t plane = int32_t(c.plane);  // inside the node's int32 bounds
        const size_t i = e - b >= kParallelPartitionCells
                             ? parallelPartition(b, e, c.axis, plane, !c.sidesFromSlabs, left, right)
                             : partition(b, e, c.axis, plane, !c.sidesFromSlabs, left, right);
        AMRVK_CHECK(i > b && i < e, "brick builder: empty side at plane ", c.plane, " axis ", c.axis);
        return i;
    }

    // The node's plan on its cube grid, carried out: its cells moved once into the plan's leaves
    // (applyPlan), which are returned in left-to-right order. Fewer than two leaves: nothing moved.
    std::vector<Node> planned(Node& n) {
        const SplitFrame f = frameOf(n.info);
        ensureCubes(n.b, n.e, f, n.cubes);
        if (!n.cubes) return {};
        // At most about kPlanLeaves leaves: a multi-way pass stays fast while its destinations are
        // few (a cache line and a page each); the leaves are planned again in their turn.
        const BrickPlan plan(*n.cubes, std::max(mPlanCells, (n.e - n.b) / kPlanLeaves), n.info, f);
        if (plan.leaves.size() < 2) return {};
        applyPlan(plan, plan.leafOfCube(), 0, n.b, n.e);
        std::vector<Node> parts;
        size_t at = n.b;
        for (uint32_t leaf : plan.leaves) {
            const CellStats& s = plan.nodes[leaf].info;
            parts.push_back({at, at + s.count, s, n.cubes});
            at += s.count;
        }
        return parts;
    }

    // Moves cells [b, e) of plan node i into its leaves' ranges. Nodes that hold more than a core's
    // share of all the cells are split in two on every core (parallelPartition) and their sides
    // done concurrently; below that, one multi-way pass per node (flagSort), while other cores
    // work on other nodes.
    void applyPlan(const BrickPlan& p, const std::vector<uint32_t>& leafOfCube, uint32_t i, size_t b, size_t e) {
        const BrickPlan::Node& n = p.nodes[i];
        if (n.axis >= 0 && threadCount() > 1 && (e - b) * size_t(threadCount()) > mCells.size()) {
            CellStats unused;
            const size_t mid = parallelPartition(b, e, n.axis, n.plane, false, unused, unused);
            AMRVK_CHECK(mid == b + p.nodes[n.left].info.count, "internal: the brick plan's counts do not match");
            parallelInvoke([&] { applyPlan(p, leafOfCube, n.left, b, mid); },
                           [&] { applyPlan(p, leafOfCube, n.left + 1, mid, e); });
            return;
        }
        flagSort(p, leafOfCube, n.leafBegin, n.leafEnd, b);
    }

    // American flag sort of the cells from b on into the plan's leaves [lb, le), whose counts are
    // known: each leaf's next free place takes the cells of that leaf. A misplaced cell is carried
    // along its cycle (to its leaf's next place, whose cell is carried on) until the cycle returns,
    // so every cell is read once and written at most once.
    void flagSort(const BrickPlan& p, const std::vector<uint32_t>& leafOfCube, uint32_t lb, uint32_t le, size_t b) {
        const size_t k = le - lb;
        if (k < 2) return;
        std::vector<size_t> head(k), end(k);
        for (size_t m = 0, at = b; m < k; ++m) {
            head[m] = at;
            at += p.nodes[p.leaves[lb + m]].info.count;
            end[m] = at;
        }
        auto leafOf = [&](const amr::Cell& c) { return size_t(leafOfCube[p.boxCubeOf(c)] - lb); };
        std::vector<float> values(mFields.size());
        bool moved = false;
        mCells.visitStorage([&](auto cells) {   // cells move as stored: no repacking
            for (size_t m = 0; m + 1 < k; ++m)  // the last leaf then holds what is left
                for (; head[m] < end[m]; ++head[m]) {
                    const size_t at = head[m];
                    auto cell = cells[at];
                    size_t d = leafOf(amr::CellArray::decode(cell));
                    if (d == m) continue;
                    for (size_t f = 0; f < mFields.size(); ++f) values[f] = mFields[f][at];
                    do {
                        AMRVK_CHECK(d < k && head[d] < end[d], "internal: a cell outside the brick plan's leaves");
                        const size_t to = head[d]++;
                        std::swap(cell, cells[to]);
                        for (size_t f = 0; f < mFields.size(); ++f) std::swap(values[f], mFields[f][to]);
                        d = leafOf(amr::CellArray::decode(cell));
                    } while (d != m);
                    cells[at] = cell;
                    for (size_t f = 0; f < mFields.size(); ++f) mFields[f][at] = values[f];
                    moved = true;
                }
        });
        if (moved) mMoved.store(true, std::memory_order_relaxed);
    }

    // Hoare partition of cells [b, e) and their values: those with lower[axis] < plane first.
    // Returns the first of the others; with `stats`, adds each side's cells to left and right.
    size_t partition(size_t b, size_t e, int axis, int32_t plane, bool stats, CellStats& left, CellStats& right) {
        size_t i = b, j = e;
        for (bool swapped = false;; swapped = true) {
            if (!stats) {
                while (i < j && mCells[i].lower[axis] < plane) ++i;
                while (i < j && mCells[j - 1].lower[axis] >= plane) --j;
            } else {
                while (i < j && mCells[i].lower[axis] < plane) left.add(mCells[i++]);
                while (i < j && mCells[j - 1].lower[axis] >= plane) right.add(mCells[--j]);
            }
            if (i >= j) {
                if (swapped) mMoved.store(true, std::memory_order_relaxed);
                return i;
            }
            swapCells(i, j - 1);
        }
    }

    // The same on every core, for the nodes near the root whose partitions would otherwise run on
    // one: a fixed number of chunks is partitioned in parallel, then the cells left of the final
    // split that belong right are swapped, in parallel, with those right of it that belong left.
    // The chunk count is fixed, so the order is the same whatever the thread count.
    size_t parallelPartition(size_t b, size_t e, int axis, int32_t plane, bool stats, CellStats& left,
                             CellStats& right) {
        constexpr size_t kChunks = 64;
        struct Part {
            size_t mid = 0;
            CellStats left, right;
        };
        std::vector<Part> parts(kChunks);
        auto bound = [&](size_t k) { return b + k * (e - b) / kChunks; };
        parallelFor(0, kChunks, [&](size_t k) {
            parts[k].mid = partition(bound(k), bound(k + 1), axis, plane, stats, parts[k].left, parts[k].right);
        });
        size_t leftCount = 0;
        for (size_t k = 0; k < kChunks; ++k) {
            leftCount += parts[k].mid - bound(k);
            left.merge(parts[k].left);
            right.merge(parts[k].right);
        }
        const size_t split = b + leftCount;
        // Misplaced: right cells before `split` (runs [mid, end of chunk)) and left cells after it
        // (runs [start of chunk, mid)); there are as many of each. Swap the m-th of one with the m-th
        // of the other.
        struct Run {
            size_t begin, end, before;  // positions, and how many misplaced cells earlier runs hold
        };
        std::vector<Run> wrongRight, wrongLeft;
        size_t nr = 0, nl = 0;
        for (size_t k = 0; k < kChunks; ++k) {
            const size_t r0 = parts[k].mid, r1 = std::min(bound(k + 1), split);
            if (r0 < r1) {
                wrongRight.push_back({r0, r1, nr});
                nr += r1 - r0;
            }
            const size_t l0 = std::max(bound(k), split), l1 = parts[k].mid;
            if (l0 < l1) {
                wrongLeft.push_back({l0, l1, nl});
                nl += l1 - l0;
            }
        }
        AMRVK_CHECK(nr == nl, "internal: parallel partition lost cells");
        // A cursor over the runs: the position of the m-th misplaced cell, advanced one at a time.
        struct Cursor {
            const std::vector<Run>* runs;
            size_t run, pos;
            Cursor(const std::vector<Run>& r, size_t m) : runs(&r) {
                run = size_t(
                          std::upper_bound(r.begin(), r.end(), m, [](size_t x, const Run& q) { return x < q.before; }) -
                          r.begin()) -
                      1;
                pos = r[run].begin + (m - r[run].before);
            }
            void next() {
                if (++pos == (*runs)[run].end && run + 1 < runs->size()) pos = (*runs)[++run].begin;
            }
        };
        const size_t blocks = std::min<size_t>(kChunks, nr);
        parallelFor(0, blocks, [&](size_t k) {
            const size_t first = k * nr / blocks, end = (k + 1) * nr / blocks;
            if (first == end) return;
            Cursor r(wrongRight, first), l(wrongLeft, first);
            for (size_t m = first; m < end; ++m, r.next(), l.next()) swapCells(r.pos, l.pos);
        });
        if (nr > 0) mMoved.store(true, std::memory_order_relaxed);
        return split;
    }

    // A node of several cells inside one cell of its coarsest level: that cell overlaps the others.
    [[noreturn]] void reportOverlap(size_t b, size_t e, const CellStats& in) const {
        size_t big = b;
        while (mCells[big].level != in.maxLevel()) ++big;
        const size_t other = big == b ? b + 1 : b;
        const bool same = mCells[other].level == mCells[big].level;
        throw Error(strCat(mModel.source, ": overlapping cells: ", amr::describeCell(mCells[other]),
                           same ? " duplicates " : " lies inside ", amr::describeCell(mCells[big]), " (", e - b,
                           " cells share that cell's box)"));
    }

    amr::Model& mModel;
    amr::CellArray& mCells;
    std::vector<float*> mFields;
    size_t mPlanCells;                 // nodes at least this large are planned on a cube grid (BrickBuildTuning)
    std::atomic<bool> mMoved{false};   // some cell changed place
    std::atomic<uint64_t> mPlaced{0};  // cells in bricks so far
    std::mutex mBarMutex;
    ProgressBar mBar{"bricks", "cells"};
};

}  // namespace

BrickSet buildBricks(amr::Model& model, const BrickBuildTuning& tuning, const amr::ModelSummary* known) {
    Timer timer;
    BrickSet out;
    const size_t n = model.cells.size();
    AMRVK_CHECK(n > 0 && n < BrickSet::kEmptySlot, model.source, ": cannot brick ", n, " cells");
    for (const amr::Field& f : model.fields)
        AMRVK_CHECK(f.values.size() == n, model.source, ": field '", f.name, "' has ", f.values.size(), " values for ",
                    n, " cells");
    BrickBuilder builder(model, std::max<size_t>(tuning.planCells, 2));
    try {
        out.bricks = builder.build(0, n, known ? rootStats(*known, n) : builder.info(0, n));
    } catch (...) {
        builder.finishProgress(false);
        model.cellOrder += builder.moved();
        throw;
    }
    builder.finishProgress(true);
    model.cellOrder += builder.moved();
    out.buildSeconds = timer.seconds();
    return out;
}

}  // namespace amrvk::accel
