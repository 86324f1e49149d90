#include "accel/bricks.h"

#include <algorithm>
#include <bit>
#include <limits>

#include "core/checked_size.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/parallel.h"
#include "core/stats.h"

namespace amrvk::accel {

amr::Box3l Brick::bounds() const {
    glm::i64vec3 lo(lower);
    return {lo, lo + glm::i64vec3(size) * cellWidth()};
}

namespace {

struct WorkCell {
    glm::ivec3 lower;
    int32_t level;
    uint32_t id;  // index into model.cells
};

struct Leaf {
    size_t begin, end;  // range in the work array
    Brick brick;
};

int64_t floorTo(int64_t v, int64_t w) { return v >= 0 ? v / w * w : -((-v + w - 1) / w) * w; }
int64_t ceilTo(int64_t v, int64_t w) { return -floorTo(-v, w); }

double halfArea(glm::dvec3 s) { return s.x * s.y + s.y * s.z + s.z * s.x; }

// Per-slab statistics along one axis: cells' level set, used volume and bounds.
struct Slab {
    uint32_t levelMask = 0;
    double volume = 0;
    glm::i64vec3 lo{std::numeric_limits<int64_t>::max()}, hi{std::numeric_limits<int64_t>::min()};
};

class BrickBuilder {
public:
    explicit BrickBuilder(std::vector<WorkCell>& work) : mWork(work) {}

    // Builds the subtree over work[begin, end) and returns its leaves in left-to-right order.
    // The two sides of a node of at least kParallelCells cells are built concurrently: they
    // partition disjoint parts of the work array, so the leaves do not depend on the schedule.
    std::vector<Leaf> build(size_t begin, size_t end) {
        std::vector<Leaf> leaves;
        struct Node { size_t b, e; };
        std::vector<Node> stack{{begin, end}};
        while (!stack.empty()) {
            Node n = stack.back();
            stack.pop_back();
            if (tryLeaf(n.b, n.e, leaves)) continue;
            const size_t mid = split(n.b, n.e);
            if (n.e - n.b >= kParallelCells) {
                std::vector<Leaf> left, right;
                parallelInvoke([&] { left = build(n.b, mid); }, [&] { right = build(mid, n.e); });
                leaves.insert(leaves.end(), left.begin(), left.end());
                leaves.insert(leaves.end(), right.begin(), right.end());
                continue;
            }
            stack.push_back({mid, n.e});
            stack.push_back({n.b, mid});
        }
        return leaves;
    }

private:
    static constexpr size_t kParallelCells = size_t{1} << 15;

    struct NodeInfo {
        glm::i64vec3 lo, hi;
        uint32_t levelMask;
        int32_t minLevel, maxLevel;
    };

    NodeInfo info(size_t b, size_t e) const {
        NodeInfo in{glm::i64vec3(std::numeric_limits<int64_t>::max()),
                    glm::i64vec3(std::numeric_limits<int64_t>::min()), 0, 64, -1};
        for (size_t i = b; i < e; ++i) {
            const WorkCell& c = mWork[i];
            glm::i64vec3 l(c.lower);
            in.lo = glm::min(in.lo, l);
            in.hi = glm::max(in.hi, l + amr::cellWidth(c.level));
            in.levelMask |= 1u << c.level;
        }
        in.minLevel = std::countr_zero(in.levelMask);
        in.maxLevel = 31 - std::countl_zero(in.levelMask);
        return in;
    }

    bool tryLeaf(size_t b, size_t e, std::vector<Leaf>& leaves) {
        NodeInfo in = info(b, e);
        if (in.minLevel != in.maxLevel) return false;
        const int64_t w = amr::cellWidth(in.minLevel);
        glm::i64vec3 dims = (in.hi - in.lo) / w;
        if (dims.x > kMaxBrickCells || dims.y > kMaxBrickCells || dims.z > kMaxBrickCells)
            return false;
        if (uint64_t(dims.x * dims.y * dims.z) != e - b) return false;  // not completely filled
        Brick brick{glm::ivec3(in.lo), glm::ivec3(dims), in.minLevel, static_cast<uint32_t>(b)};
        leaves.push_back({b, e, brick});
        return true;
    }

    // Chooses a plane (exaBuilder's SAH-alike cost over boundary planes between coarse-cell slabs,
    // else the spatial median of the longest axis) and partitions; returns the split index.
    size_t split(size_t b, size_t e) {
        NodeInfo in = info(b, e);
        const int64_t cw = amr::cellWidth(in.maxLevel);
        glm::i64vec3 lo, hi, slabs;
        for (int a = 0; a < 3; ++a) {
            lo[a] = floorTo(in.lo[a], cw);
            hi[a] = ceilTo(in.hi[a], cw);
            slabs[a] = (hi[a] - lo[a]) / cw;
        }
        const uint64_t slabLimit = 4 * (e - b) + 1024;
        double bestCost = std::numeric_limits<double>::infinity();
        int bestAxis = -1;
        int64_t bestPlane = 0;
        std::vector<Slab> slab;
        std::vector<Slab> suffix;
        for (int a = 0; a < 3; ++a) {
            if (slabs[a] < 2 || uint64_t(slabs[a]) > slabLimit) continue;
            slab.assign(size_t(slabs[a]), Slab{});
            for (size_t i = b; i < e; ++i) {
                const WorkCell& c = mWork[i];
                Slab& s = slab[size_t((c.lower[a] - lo[a]) / cw)];
                const int64_t w = amr::cellWidth(c.level);
                glm::i64vec3 l(c.lower);
                s.levelMask |= 1u << c.level;
                s.volume += double(w) * double(w) * double(w);
                s.lo = glm::min(s.lo, l);
                s.hi = glm::max(s.hi, l + w);
            }
            const int b1 = (a + 1) % 3, b2 = (a + 2) % 3;
            const double fullVolume = double(cw) * double(hi[b1] - lo[b1]) * double(hi[b2] - lo[b2]);
            suffix.assign(slab.size() + 1, Slab{});
            for (size_t k = slab.size(); k-- > 0;) suffix[k] = merge(suffix[k + 1], slab[k]);
            Slab prefix;
            for (size_t k = 1; k < slab.size(); ++k) {
                prefix = merge(prefix, slab[k - 1]);
                const Slab& l = slab[k - 1];
                const Slab& r = slab[k];
                bool boundary = l.levelMask != r.levelMask || l.volume < fullVolume ||
                                r.volume < fullVolume;
                if (!boundary) continue;
                double cost = sahCost(prefix) + sahCost(suffix[k]);
                if (cost < bestCost) {
                    bestCost = cost;
                    bestAxis = a;
                    bestPlane = lo[a] + int64_t(k) * cw;
                }
            }
        }
        if (bestAxis < 0) {  // spatial median of the longest axis, in coarse cells
            int a = 0;
            for (int k = 1; k < 3; ++k)
                if (slabs[k] > slabs[a]) a = k;
            AMRVK_CHECK(slabs[a] >= 2, "brick builder: cannot split a node of ", e - b, " cells");
            bestAxis = a;
            bestPlane = lo[a] + slabs[a] / 2 * cw;
        }
        auto midIt = std::partition(mWork.begin() + std::ptrdiff_t(b), mWork.begin() + std::ptrdiff_t(e),
                                    [&](const WorkCell& c) { return c.lower[bestAxis] < bestPlane; });
        size_t mid = size_t(midIt - mWork.begin());
        AMRVK_CHECK(mid > b && mid < e, "brick builder: empty side at plane ", bestPlane,
                    " axis ", bestAxis);
        return mid;
    }

    static Slab merge(const Slab& a, const Slab& s) {
        Slab m;
        m.levelMask = a.levelMask | s.levelMask;
        m.volume = a.volume + s.volume;
        m.lo = glm::min(a.lo, s.lo);
        m.hi = glm::max(a.hi, s.hi);
        return m;
    }
    static double sahCost(const Slab& s) {
        if (s.levelMask == 0) return 0;
        glm::dvec3 size(s.hi - s.lo);
        return halfArea(size) * (size.x * size.y * size.z) * std::popcount(s.levelMask);
    }

    std::vector<WorkCell>& mWork;
};

}  // namespace

BrickSet buildBricks(const amr::Model& model) {
    Timer timer;
    BrickSet out;
    const size_t n = model.cells.size();
    AMRVK_CHECK(n > 0 && n < BrickSet::kEmptySlot, model.source, ": cannot brick ", n, " cells");
    std::vector<Leaf> leaves;
    {
        std::vector<WorkCell> work(n);
        for (size_t i = 0; i < n; ++i)
            work[i] = {model.cells[i].lower, model.cells[i].level, static_cast<uint32_t>(i)};
        BrickBuilder builder(work);
        leaves = builder.build(0, n);
        std::sort(leaves.begin(), leaves.end(),
                  [](const Leaf& a, const Leaf& b) { return a.begin < b.begin; });
        out.cellIds.resize(n);
        for (const Leaf& leaf : leaves) {
            const Brick& br = leaf.brick;
            const int64_t w = br.cellWidth();
            for (size_t i = leaf.begin; i < leaf.end; ++i) {
                glm::i64vec3 local = (glm::i64vec3(work[i].lower) - glm::i64vec3(br.lower)) / w;
                size_t idx = size_t((local.z * br.size.y + local.y) * br.size.x + local.x);
                out.cellIds[br.begin + idx] = work[i].id;
            }
        }
    }
    out.bricks.reserve(leaves.size());
    for (const Leaf& leaf : leaves) out.bricks.push_back(leaf.brick);
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
            uint32_t id = bricks.cellIds[b.begin + k];
            ids.push_back(id == BrickSet::kEmptySlot ? -1 : static_cast<int32_t>(id));
        }
        out.write(ids.data(), ids.size() * sizeof(int32_t));
    }
    out.commit();
}

std::vector<float> brickOrderValues(const BrickSet& bricks, const amr::Field& field) {
    std::vector<float> out(bricks.cellIds.size());
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
    s.averageCellsPerBrick = s.brickCount ? double(bricks.cellIds.size()) / double(s.brickCount) : 0;
    return s;
}

}  // namespace amrvk::accel
