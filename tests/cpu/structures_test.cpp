// Bricks, ABRs and macrocell value ranges: structural invariants checked independently
// (rasterised volumes, brute-force reconstruction), and the .bricks file reader.
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <cstring>
#include <set>
#include <tuple>

#include "accel/abrs.h"
#include "accel/brick_build.h"
#include "accel/brick_sampler.h"
#include "accel/bricks.h"
#include "accel/bricks_file.h"
#include "accel/majorant_bounds.h"
#include "accel/range_grid.h"
#include "accel/support_range.h"
#include "amr/sampler.h"
#include "amr/synthetic.h"
#include "core/error.h"
#include "model_fixtures.h"
#include "test_data.h"

using namespace amrvk;
using namespace amrvk::accel;

namespace {
amr::Model fixture(uint32_t seed) {
    amr::Model m = test::makeRefinedModel(seed, {5, 4, 3}, 3, 0.4, {-2, 0, 1});
    test::addRandomField(m, "r", seed + 100);
    amr::validate(m);
    return m;
}
// Range membership up to float rounding of the double-precision reconstruction (1e-6 relative).
bool rangeHolds(const ValueRange& r, double v) {
    double tol = 1e-6 * std::max({1.0, std::abs(double(r.lo)), std::abs(double(r.hi))});
    return v >= double(r.lo) - tol && v <= double(r.hi) + tol;
}
// `m` with its cells (and every field's values with them) in a random order of `seed`.
amr::Model shuffledCopy(const amr::Model& m, uint32_t seed) {
    amr::Model shuffled = m;
    std::mt19937 rng(seed);
    for (size_t i = shuffled.cells.size(); i-- > 1;) {
        const size_t j = std::uniform_int_distribution<size_t>(0, i)(rng);
        shuffled.cells.swapCells(i, j);
        for (amr::Field& f : shuffled.fields) std::swap(f.values[i], f.values[j]);
    }
    return shuffled;
}
}  // namespace

TEST(Bricks, EveryCellInExactlyOneBrickAtItsPositionAndTheModelInBrickOrder) {
    const amr::Model original = fixture(1);
    amr::Model m = original;
    const amr::ReferenceSampler stale(m, m.fields[0]);
    BrickSet bs = buildBricks(m);
    // What indexed the cells by position before the build says so instead of reading wrong cells.
    EXPECT_THROW(stale.sample(glm::dvec3(m.cells[0].lower) + 0.5), Error);
    EXPECT_TRUE(bs.cellIds.empty()) << "the model itself is in brick order";
    ASSERT_EQ(bs.slotCount(), m.cells.size());
    // The model is a permutation of the original: every (cell, value) pair once.
    auto key = [](const amr::Model& x, size_t i) {
        const amr::Cell& c = x.cells[i];
        return std::make_tuple(c.lower.x, c.lower.y, c.lower.z, c.level, x.fields[0].values[i], x.fields.back().values[i]);
    };
    std::multiset<decltype(key(m, 0))> before, after;
    for (size_t i = 0; i < m.cells.size(); ++i) {
        before.insert(key(original, i));
        after.insert(key(m, i));
    }
    EXPECT_EQ(before, after);
    uint64_t total = 0;
    for (const Brick& b : bs.bricks) {
        EXPECT_EQ(b.begin, total);
        total += b.cellCount();
        for (int a = 0; a < 3; ++a) {
            EXPECT_GE(b.size[a], 1);
            EXPECT_LE(b.size[a], kMaxBrickCells);
        }
        for (uint64_t k = 0; k < b.cellCount(); ++k) {
            const uint32_t id = bs.cellId(b.begin + k);
            EXPECT_EQ(id, b.begin + k);
            glm::ivec3 local(int(k % uint64_t(b.size.x)), int(k / uint64_t(b.size.x) % uint64_t(b.size.y)),
                             int(k / uint64_t(b.size.x * b.size.y)));
            EXPECT_EQ(m.cells[id].lower, b.lower + local * int(b.cellWidth()));
            EXPECT_EQ(m.cells[id].level, b.level);
        }
    }
    EXPECT_EQ(total, m.cells.size());

    // The order is a function of the cells alone: building again, or from a shuffled file order,
    // gives the same bricks and the same model.
    const amr::Model ordered = m;
    const amr::ReferenceSampler fresh(m, m.fields[0]);
    const BrickSet again = buildBricks(m);
    EXPECT_NO_THROW(fresh.sample(glm::dvec3(m.cells[0].lower) + 0.5)) << "nothing moved";
    EXPECT_TRUE(m.cells == ordered.cells);
    EXPECT_EQ(m.fields[0].values, ordered.fields[0].values);
    amr::Model shuffled = shuffledCopy(original, 7);
    const BrickSet fromShuffled = buildBricks(shuffled);
    ASSERT_EQ(fromShuffled.bricks.size(), bs.bricks.size());
    EXPECT_TRUE(shuffled.cells == ordered.cells);
    EXPECT_EQ(shuffled.fields.back().values, ordered.fields.back().values);
}

// Near the root, nodes of at least 2^21 cells are partitioned on every core (chunks partitioned
// in parallel, then the misplaced cells swapped across the split): the bricks and the model's
// order are still those of the cells alone, from the generator's order and from a shuffled one.
TEST(Bricks, ParallelPartitionsNearTheRootGiveTheSameBricks) {
    amr::SyntheticParams p;
    p.cells = 3000000;
    p.seed = 3;
    const amr::Model original = amr::makeSyntheticModel(p);
    ASSERT_GT(original.cells.size(), size_t{1} << 21);
    amr::Model m = original;
    const BrickSet bs = buildBricks(m);
    uint64_t total = 0;
    for (const Brick& b : bs.bricks) {
        ASSERT_EQ(b.begin, total);
        total += b.cellCount();
        const amr::Cell& first = m.cells[b.begin];
        const amr::Cell& last = m.cells[b.begin + b.cellCount() - 1];
        EXPECT_EQ(first.lower, b.lower);
        EXPECT_EQ(last.lower, b.lower + (b.size - 1) * int(b.cellWidth()));
        EXPECT_EQ(first.level, b.level);
    }
    EXPECT_EQ(total, m.cells.size());
    amr::Model shuffled = shuffledCopy(original, 11);
    const BrickSet fromShuffled = buildBricks(shuffled);
    ASSERT_EQ(fromShuffled.bricks.size(), bs.bricks.size());
    EXPECT_TRUE(shuffled.cells == m.cells);
    EXPECT_EQ(shuffled.fields[0].values, m.fields[0].values);
}

// The top levels planned on a cube grid, their cells moved once (BrickBuildTuning::planCells), give
// the bricks and the model order of the level-by-level splits exactly: on block-structured clouds
// and a cell octree, from a shuffled order, planned at the default size and at every node, and with
// the root's statistics taken from the model's summary instead of a pass over the cells.
TEST(Bricks, PlannedTopLevelsGiveTheBricksOfLevelByLevelSplits) {
    for (const auto& [kind, cells, block] : {std::tuple{amr::SyntheticKind::Cloud, 300000, 8},
                                             std::tuple{amr::SyntheticKind::Cloud, 60000, 1},
                                             std::tuple{amr::SyntheticKind::Shells, 100000, 4}}) {
        amr::SyntheticParams p;
        p.kind = kind;
        p.cells = uint64_t(cells);
        p.blockCells = block;
        p.seed = 5;
        const amr::Model original = shuffledCopy(amr::makeSyntheticModel(p), 13);
        amr::Model levelByLevel = original;
        const BrickSet want = buildBricks(levelByLevel, {.planCells = SIZE_MAX});
        const amr::ModelSummary summary = amr::summarize(original);
        for (const auto& [planCells, known] : {std::pair{size_t{1} << 16, false}, std::pair{size_t{2}, false},
                                               std::pair{size_t{1} << 16, true}}) {
            SCOPED_TRACE(strCat("cells ", cells, " block ", block, " planCells ", planCells, " summary given ", known));
            amr::Model m = original;
            const BrickSet got = buildBricks(m, {.planCells = planCells}, known ? &summary : nullptr);
            ASSERT_EQ(got.bricks.size(), want.bricks.size());
            for (size_t k = 0; k < got.bricks.size(); ++k) {
                const Brick &g = got.bricks[k], &w = want.bricks[k];
                ASSERT_TRUE(g.lower == w.lower && g.size == w.size && g.level == w.level && g.begin == w.begin)
                    << "brick " << k;
            }
            EXPECT_TRUE(m.cells == levelByLevel.cells);
            EXPECT_EQ(m.fields[0].values, levelByLevel.fields[0].values);
        }
    }
}

// Overlaps are found by the build itself (no hash): a cell inside a coarser one, and a duplicate,
// each wherever it sits in the file; the message names both cells by position and level.
TEST(Bricks, OverlappingCellsAreFoundByTheBuild) {
    for (size_t at : {size_t(0), size_t(17), SIZE_MAX}) {
        for (bool duplicate : {false, true}) {
            amr::Model m = fixture(4);
            const size_t pos = std::min(at, m.cells.size());
            amr::Cell extra = m.cells[m.cells.size() / 2];
            if (!duplicate) {  // a finest cell inside the coarsest cell of the model
                const amr::Cell coarse = *std::max_element(
                    m.cells.begin(), m.cells.end(), [](const amr::Cell& a, const amr::Cell& b) { return a.level < b.level; });
                ASSERT_GT(coarse.level, 0);
                extra = {coarse.lower + glm::ivec3(1, 0, 1), 0};
            }
            amr::CellArray cells;
            for (size_t i = 0; i <= m.cells.size(); ++i) {
                if (i == pos) cells.push_back(extra);
                if (i < m.cells.size()) cells.push_back(m.cells[i]);
            }
            m.cells.swap(cells);
            for (amr::Field& f : m.fields) f.values.insert(f.values.begin() + std::ptrdiff_t(pos), 1.0f);
            amr::validateCells(m);
            EXPECT_THROW(amr::validate(m), Error);  // the hash check agrees
            const std::string where = strCat("(lower ", extra.lower.x, ",", extra.lower.y, ",", extra.lower.z,
                                             " level ", extra.level, ")");
            try {
                buildBricks(m);
                ADD_FAILURE() << "no error, duplicate " << duplicate << " at " << pos;
            } catch (const Error& e) {
                const std::string msg = e.what();
                EXPECT_NE(msg.find("overlapping cells"), std::string::npos) << msg;
                EXPECT_NE(msg.find(where), std::string::npos) << msg;
                EXPECT_NE(msg.find(duplicate ? "duplicates" : "inside"), std::string::npos) << msg;
            }
        }
    }
}

TEST(Bricks, LargeUniformBlockIsSplitAtTheBrickLimit) {
    amr::Model m = test::makeRefinedModel(0, {130, 3, 2}, 0, 0.0);
    test::addField(m, "c", [](glm::dvec3) { return 1.0; });
    BrickSet bs = buildBricks(m);
    EXPECT_EQ(bs.bricks.size(), 2u);  // 130 cells need two bricks along x
    for (const Brick& b : bs.bricks) EXPECT_LE(b.size.x, kMaxBrickCells);
}

TEST(Bricks, BricksFileRoundTripAndErrors) {
    amr::Model m = fixture(2);
    BrickSet bs = buildBricks(m);
    auto dir = test::scratchDir();
    writeBricksFile(dir / "m.bricks", bs);
    BrickSet back = readBricksFile(dir / "m.bricks", m);
    ASSERT_EQ(back.bricks.size(), bs.bricks.size());
    ASSERT_EQ(back.slotCount(), bs.slotCount());
    for (uint64_t k = 0; k < bs.slotCount(); ++k) ASSERT_EQ(back.cellId(k), bs.cellId(k)) << k;

    // Truncated: the error names the file and the byte count.
    auto bytes = std::filesystem::file_size(dir / "m.bricks");
    std::filesystem::copy_file(dir / "m.bricks", dir / "t.bricks");
    std::filesystem::resize_file(dir / "t.bricks", bytes - 6);
    try {
        readBricksFile(dir / "t.bricks", m);
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("t.bricks: truncated"), std::string::npos) << e.what();
    }
    // A cell id listed twice is rejected.
    BrickSet dup = back;
    dup.cellIds[1] = dup.cellIds[0];
    writeBricksFile(dir / "d.bricks", dup);
    EXPECT_THROW(readBricksFile(dir / "d.bricks", m), Error);
    // Missing file.
    EXPECT_THROW(readBricksFile(dir / "none.bricks", m), Error);
}

TEST(Bricks, EmptySlotsFromABricksFileAreSkippedInReconstruction) {
    // One 2x1x1 brick whose second slot is empty (-1): the value is the first cell's everywhere.
    amr::Model m;
    m.source = "one-cell";
    m.cells.push_back({{0, 0, 0}, 0});
    m.fields.push_back({"v", {4.0f}});
    auto dir = test::scratchDir();
    {
        std::ofstream out(dir / "h.bricks", std::ios::binary);
        int32_t rec[9] = {2, 1, 1, 0, 0, 0, 0, 0, -1};
        out.write(reinterpret_cast<const char*>(rec), sizeof rec);
    }
    BrickSet bs = readBricksFile(dir / "h.bricks", m);
    auto values = brickOrderValues(bs, m.fields[0]);
    ASSERT_EQ(values.size(), 2u);
    EXPECT_TRUE(std::isnan(values[1]));
    ExtBrickSampler s(bs, values);
    EXPECT_DOUBLE_EQ(s.sample({1.2, 0.5, 0.5}).value, 4.0);
}

TEST(Abrs, DisjointAndTileTheUnionOfBrickDomains) {
    amr::Model m = fixture(3);
    BrickSet bs = buildBricks(m);
    AbrSet abrs = buildAbrs(bs);
    ASSERT_FALSE(abrs.abrs.empty());
    // Rasterise in half-voxel units: every unit voxel of the domain union is in exactly one ABR.
    HalfBox all{glm::i64vec3(INT64_MAX), glm::i64vec3(INT64_MIN)};
    for (const Brick& b : bs.bricks) {
        HalfBox d = brickDomain(b);
        all.lo = glm::min(all.lo, d.lo);
        all.hi = glm::max(all.hi, d.hi);
    }
    glm::i64vec3 ext = all.hi - all.lo;
    ASSERT_LT(ext.x * ext.y * ext.z, 20'000'000);
    auto idx = [&](glm::i64vec3 p) { return size_t(((p.z - all.lo.z) * ext.y + (p.y - all.lo.y)) * ext.x + (p.x - all.lo.x)); };
    std::vector<uint8_t> inDomain(size_t(ext.x * ext.y * ext.z), 0), inAbr(inDomain.size(), 0);
    auto fill = [&](const HalfBox& b, std::vector<uint8_t>& grid, bool count) {
        for (int64_t z = b.lo.z; z < b.hi.z; ++z)
            for (int64_t y = b.lo.y; y < b.hi.y; ++y)
                for (int64_t x = b.lo.x; x < b.hi.x; ++x) {
                    uint8_t& g = grid[idx({x, y, z})];
                    g = count ? uint8_t(g + 1) : uint8_t(1);
                }
    };
    for (const Brick& b : bs.bricks) fill(brickDomain(b), inDomain, false);
    double abrVolume = 0;
    for (const Abr& a : abrs.abrs) {
        fill(a.box, inAbr, true);
        abrVolume += a.box.volume();
    }
    double unionVolume = 0;
    for (size_t i = 0; i < inDomain.size(); ++i) {
        ASSERT_LE(inAbr[i], 1) << "ABRs overlap";
        ASSERT_EQ(inAbr[i], inDomain[i]) << "ABRs do not tile the domain union";
        unionVolume += inDomain[i] * 0.125;  // one half-unit voxel = 1/8 voxel^3
    }
    EXPECT_DOUBLE_EQ(abrVolume, unionVolume);
    // The brick list of an ABR is exactly the bricks whose domain overlaps it, sorted.
    for (const Abr& a : abrs.abrs) {
        std::vector<uint32_t> expect;
        for (uint32_t i = 0; i < bs.bricks.size(); ++i) {
            HalfBox d = brickDomain(bs.bricks[i]);
            bool overlap = true;
            for (int k = 0; k < 3; ++k) overlap = overlap && d.lo[k] < a.box.hi[k] && a.box.lo[k] < d.hi[k];
            if (overlap) expect.push_back(i);
        }
        auto got = abrs.bricksOf(a);
        EXPECT_EQ(std::vector<uint32_t>(got.begin(), got.end()), expect);
    }
}

TEST(Abrs, ValueRangesContainReconstructedValues) {
    amr::Model m = fixture(4);
    BrickSet bs = buildBricks(m);
    AbrSet abrs = buildAbrs(bs);
    auto values = brickOrderValues(bs, m.fields[0]);
    auto ranges = computeAbrValueRanges(abrs, SupportRangeQuery(bs, values), positionMargin(amr::summarize(m).bounds));
    amr::ReferenceSampler ref(m, m.fields[0]);
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    size_t checked = 0;
    for (size_t i = 0; i < abrs.abrs.size(); ++i) {
        const HalfBox& b = abrs.abrs[i].box;
        for (int k = 0; k < 40; ++k) {
            // Interior points and the 8 corners.
            glm::dvec3 t = k < 8 ? glm::dvec3(k & 1, (k >> 1) & 1, (k >> 2) & 1)
                                 : glm::dvec3(u(rng), u(rng), u(rng));
            glm::dvec3 p = b.lower() + (b.upper() - b.lower()) * t;
            amr::Sample s = ref.sample(p);
            if (!s.valid()) continue;
            ++checked;
            EXPECT_TRUE(rangeHolds(ranges[i], s.value))
                << "ABR " << i << " range [" << ranges[i].lo << ", " << ranges[i].hi << "] value " << s.value;
        }
    }
    EXPECT_GT(checked, abrs.abrs.size() * 20);
}

TEST(RangeGrid, ParsesGridOptions) {
    amr::Box3l b{{0, 0, 0}, {256, 128, 64}};
    EXPECT_EQ(parseGridDims("auto", b), glm::ivec3(128, 64, 32));
    EXPECT_EQ(parseGridDims("32", b), glm::ivec3(32, 16, 8));
    EXPECT_EQ(parseGridDims("4x5x6", b), glm::ivec3(4, 5, 6));
    EXPECT_THROW(parseGridDims("0", b), Error);
    EXPECT_THROW(parseGridDims("4x5", b), Error);
    EXPECT_THROW(parseGridDims("big", b), Error);
}

// "auto" never gives a small data set more than kAutoMacrocellsPerCell macrocells per leaf cell:
// the largest near-cubical grid under the cap (shrinking the longest axis keeps the aspect), and
// the full 128 once the cells can pay for it; N and NxMxK are taken as given.
TEST(RangeGrid, AutoGridFollowsTheCellCount) {
    amr::Box3l b{{0, 0, 0}, {256, 128, 64}};  // 128x64x32 = 262,144 macrocells uncapped
    EXPECT_EQ(parseGridDims("auto", b, 131072), glm::ivec3(128, 64, 32));  // 2 x 131,072 = the full grid
    const glm::ivec3 capped = parseGridDims("auto", b, 131071);
    EXPECT_EQ(capped, glm::ivec3(127, 64, 32));  // one step below: 260,096 <= 262,142
    const glm::ivec3 small = parseGridDims("auto", b, 1000);  // <= 2,000 macrocells
    EXPECT_LE(uint64_t(small.x) * small.y * small.z, 2000u);
    EXPECT_GT(uint64_t(small.x + 1) * ((small.x + 1 + 1) / 2) * ((small.x + 1 + 3) / 4), 2000u);  // the next is over
    EXPECT_EQ(small, autoGridDims(b, small.x));  // the same shape as the uncapped grid of that size
    EXPECT_EQ(parseGridDims("auto", b, 1), glm::ivec3(2, 1, 1));  // two macrocells for one cell
    EXPECT_EQ(autoGridDims(b, 128, 1), glm::ivec3(1));            // and never below one macrocell
    EXPECT_EQ(parseGridDims("64", b, 10), glm::ivec3(64, 32, 16));  // given sizes are not capped
    EXPECT_EQ(parseGridDims("4x5x6", b, 10), glm::ivec3(4, 5, 6));
}
