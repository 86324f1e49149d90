#include "accel/bricks.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>

#include "core/checked_size.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/stats.h"

namespace amrvk::accel {

amr::Box3l Brick::bounds() const {
    glm::i64vec3 lo(lower);
    return {lo, lo + glm::i64vec3(size) * cellWidth()};
}

namespace {

double halfArea(glm::dvec3 s) { return s.x * s.y + s.y * s.z + s.z * s.x; }

// Level set, used volume and bounds of a set of cells (voxel space): a node of the kd build, or one
// slab or coarse cube of it. Bounds are int32: validated cells end at or below 2^31-1.
struct CellStats {
    uint32_t levelMask = 0;
    uint32_t count = 0;  // cells (a model has fewer than 2^32)
    double volume = 0;
    glm::ivec3 lo{std::numeric_limits<int32_t>::max()}, hi{std::numeric_limits<int32_t>::min()};
    void add(const amr::Cell& c) {
        levelMask |= 1u << c.level;
        ++count;
        volume += amr::cellVolume(c.level);
        lo = glm::min(lo, c.lower);
        hi = glm::max(hi, c.lower + (int32_t{1} << c.level));
    }
    void merge(const CellStats& o) {
        levelMask |= o.levelMask;
        count += o.count;
        volume += o.volume;
        lo = glm::min(lo, o.lo);
        hi = glm::max(hi, o.hi);
    }
    int32_t minLevel() const { return std::countr_zero(levelMask); }
    int32_t maxLevel() const { return 31 - std::countl_zero(levelMask); }
};
double sahCost(const CellStats& s) {
    if (s.levelMask == 0) return 0;
    const glm::dvec3 size = glm::dvec3(s.hi) - glm::dvec3(s.lo);
    return halfArea(size) * (size.x * size.y * size.z) * std::popcount(s.levelMask);
}

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

// Cell statistics per cube (cw^3) of a box [lo, lo + dims cw), x fastest; a cell counts in the
// cube of its lower corner. It serves every node inside the box whose coarsest cell width is a
// multiple of cw (a power of two at least cw): such a node's slabs and planes are unions of cubes.
struct CubeGrid {
    glm::i64vec3 lo{0}, dims{0};
    int64_t cw = 1;  // cube width, voxel space
    std::vector<CellStats> cubes;
};

using Slabs = std::array<std::vector<CellStats>, 3>;

// A node's candidate planes: multiples of its coarsest cell width cw inside its bounds rounded out
// to cw (voxel space); `slabs` coarse slabs per axis, `used[a]` = slabs[a] where axis a gets slab
// statistics, else 0 (fewer than 2 slabs, or more than 4 per cell).
struct SplitFrame {
    int64_t cw = 1;
    glm::i64vec3 lo{0}, hi{0}, slabs{0}, used{0};
};
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

// A node's split plane; axis -1 when no plane exists (the node lies in one coarse cell).
struct SplitChoice {
    int axis = -1;
    int64_t plane = 0;
    bool sidesFromSlabs = false;  // then left and right hold the two sides' statistics
    CellStats left, right;
};

// exaBuilder's SAH-alike cost over the boundary planes between coarse slabs (where the level set or
// fullness changes), else the spatial median of the longest axis. A function of the statistics
// alone, so a plan on a cube grid chooses what a split over the cells chooses.
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

// A frame's slabs from the cubes of a grid that serves it (g.cw divides f.cw): slab k of axis a
// merges the cubes whose coordinate along a, counted from the frame's lower corner, is k f.cw/g.cw
// up to (k + 1) f.cw/g.cw.
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

// A node that becomes a brick: one level, completely filled, at most kMaxBrickCells per axis;
// `dims` its cells per axis.
bool brickShaped(const CellStats& in, glm::i64vec3& dims) {
    const int32_t level = in.minLevel();
    if (in.levelMask == 0 || level != in.maxLevel()) return false;
    const int64_t w = amr::cellWidth(level);
    dims = (glm::i64vec3(in.hi) - glm::i64vec3(in.lo)) / w;
    if (dims.x > kMaxBrickCells || dims.y > kMaxBrickCells || dims.z > kMaxBrickCells) return false;
    return uint64_t(dims.x * dims.y * dims.z) == in.count;  // else not completely filled
}

// The top of a kd subtree decided on a cube grid alone. While a node keeps the grid's coarsest
// width or a coarser one its slabs come from the cubes, so its split (chooseSplit, as split() would
// choose it) and its sides' statistics need no pass over its cells. Leaves of the plan: nodes of
// fewer than `minCells` cells, whose coarsest width is below the cubes', brick-shaped, or split on an
// axis without slabs.
// Every leaf is a box of whole cubes; the leaves tile the root's box, in left-to-right order.
struct Plan {
    struct Node {
        CellStats info;
        glm::i64vec3 qlo{0}, qhi{0};  // the node's region, in the grid's cubes [qlo, qhi)
        int axis = -1;                // split axis; -1 for a leaf
        int32_t plane = 0;            // voxel space
        uint32_t left = 0;            // children: nodes[left], nodes[left + 1]
        uint32_t leafBegin = 0, leafEnd = 0;  // its leaves: leaves[leafBegin, leafEnd)
    };
    const CubeGrid& grid;
    size_t minCells;
    std::vector<Node> nodes;
    std::vector<uint32_t> leaves;  // node indices, left to right

    Plan(const CubeGrid& g, size_t min, const CellStats& root, const SplitFrame& f) : grid(g), minCells(min) {
        nodes.push_back({root, (f.lo - g.lo) / g.cw, (f.hi - g.lo) / g.cw});
        grow(0);
    }
    void grow(uint32_t i) {
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
    std::vector<uint32_t> leafOfCube() const {
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
};

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
        const Plan plan(*n.cubes, std::max(mPlanCells, (n.e - n.b) / kPlanLeaves), n.info, f);
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
    void applyPlan(const Plan& p, const std::vector<uint32_t>& leafOfCube, uint32_t i, size_t b, size_t e) {
        const Plan::Node& n = p.nodes[i];
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
    void flagSort(const Plan& p, const std::vector<uint32_t>& leafOfCube, uint32_t lb, uint32_t le, size_t b) {
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
        mCells.visitStorage([&](auto cells) {  // cells move as stored: no repacking
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
                run = size_t(std::upper_bound(r.begin(), r.end(), m, [](size_t x, const Run& q) { return x < q.before; }) -
                             r.begin()) - 1;
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
    size_t mPlanCells;  // nodes at least this large are planned on a cube grid (BrickBuildTuning)
    std::atomic<bool> mMoved{false};  // some cell changed place
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
        AMRVK_CHECK(f.values.size() == n, model.source, ": field '", f.name, "' has ", f.values.size(),
                    " values for ", n, " cells");
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

BrickSet readBricksFile(const std::filesystem::path& path, const amr::Model& model) {
    Timer timer;
    BrickSet out;
    BinaryReader in(path);
    AMRVK_CHECK(in.size() > 0, path.string(), ": empty file (no bricks)");
    const uint64_t n = model.cells.size();
    std::vector<uint8_t> used(n, 0);
    uint64_t usedCount = 0;
    while (!in.atEnd()) {
        const uint64_t recordOffset = in.offset();
        int32_t header[7];
        in.read(header, sizeof header);
        Brick br{{header[3], header[4], header[5]}, {header[0], header[1], header[2]}, header[6],
                 0};
        AMRVK_CHECK(br.size.x > 0 && br.size.y > 0 && br.size.z > 0 && br.level >= 0 &&
                        br.level <= amr::kMaxLevel,
                    path.string(), ": brick at byte ", recordOffset, " has size ", br.size.x, "x",
                    br.size.y, "x", br.size.z, " level ", br.level, " (invalid)");
        const std::string where = strCat(path.string(), ": brick at byte ", recordOffset);
        const uint64_t cells = checkedProduct({uint64_t(br.size.x), uint64_t(br.size.y), uint64_t(br.size.z)}, where);
        AMRVK_CHECK(checkedSum(out.cellIds.size(), cells, where) < BrickSet::kEmptySlot, where, ": ",
                    out.cellIds.size() + cells, " brick cells in all, the limit is ", BrickSet::kEmptySlot - 1);
        AMRVK_CHECK(glm::all(glm::lessThanEqual(glm::i64vec3(br.lower) + glm::i64vec3(br.size) * br.cellWidth(),
                                                glm::i64vec3(INT32_MAX))),
                    where, ": brick reaches past the 32-bit voxel range");
        br.begin = static_cast<uint32_t>(out.cellIds.size());
        std::vector<int32_t> ids;
        in.readArray(ids, br.cellCount());
        const int64_t w = br.cellWidth();
        for (size_t k = 0; k < ids.size(); ++k) {
            int32_t id = ids[k];
            if (id == -1) {
                out.cellIds.push_back(BrickSet::kEmptySlot);
                continue;
            }
            AMRVK_CHECK(id >= 0 && uint64_t(id) < n, path.string(), ": brick at byte ",
                        recordOffset, " names cell ", id, " but the model has ", n, " cells");
            AMRVK_CHECK(!used[size_t(id)], path.string(), ": cell ", id,
                        " is in more than one brick (second at byte ", recordOffset, ")");
            used[size_t(id)] = 1;
            ++usedCount;
            glm::i64vec3 local(int64_t(k % size_t(br.size.x)),
                               int64_t(k / size_t(br.size.x) % size_t(br.size.y)),
                               int64_t(k / (size_t(br.size.x) * size_t(br.size.y))));
            glm::i64vec3 expect = glm::i64vec3(br.lower) + local * w;
            const amr::Cell& c = model.cells[size_t(id)];
            AMRVK_CHECK(glm::i64vec3(c.lower) == expect && c.level == br.level, path.string(),
                        ": brick at byte ", recordOffset, " slot ", k, " names cell ", id,
                        " which is not at that position and level");
            out.cellIds.push_back(static_cast<uint32_t>(id));
        }
        out.bricks.push_back(br);
    }
    AMRVK_CHECK(usedCount == n, path.string(), ": ", n - usedCount,
                " cells of the model are in no brick");
    out.buildSeconds = timer.seconds();
    return out;
}

void writeBricksFile(const std::filesystem::path& path, const BrickSet& bricks) {
    AtomicFileWriter out(path);
    std::vector<int32_t> ids;
    for (const Brick& b : bricks.bricks) {
        int32_t header[7] = {b.size.x, b.size.y, b.size.z, b.lower.x, b.lower.y, b.lower.z, b.level};
        out.write(header, sizeof header);
        ids.clear();
        for (uint64_t k = 0; k < b.cellCount(); ++k) {
            uint32_t id = bricks.cellId(b.begin + k);
            ids.push_back(id == BrickSet::kEmptySlot ? -1 : static_cast<int32_t>(id));
        }
        out.write(ids.data(), ids.size() * sizeof(int32_t));
    }
    out.commit();
}

std::vector<float> brickOrderValues(const BrickSet& bricks, const amr::Field& field) {
    if (bricks.cellIds.empty()) return field.values;
    std::vector<float> out(bricks.slotCount());
    for (size_t i = 0; i < out.size(); ++i) {
        uint32_t id = bricks.cellIds[i];
        out[i] = id == BrickSet::kEmptySlot ? std::numeric_limits<float>::quiet_NaN()
                                            : field.values[id];
    }
    return out;
}

BrickStats computeBrickStats(const BrickSet& bricks) {
    BrickStats s;
    s.brickCount = bricks.bricks.size();
    for (const Brick& b : bricks.bricks) {
        s.singleCellBricks += b.cellCount() == 1;
        s.largestBrickCells = std::max(s.largestBrickCells, b.cellCount());
    }
    s.averageCellsPerBrick = s.brickCount ? double(bricks.slotCount()) / double(s.brickCount) : 0;
    return s;
}

}  // namespace amrvk::accel
