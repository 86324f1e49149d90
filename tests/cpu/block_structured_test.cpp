// appendLeafCells on hand-made block-structured levels: next-finer-level coverage (Enzo and
// Chombo-like nestings), 2-D planar slabs, and the one-line errors.
#include "amr/block_structured.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "amr/model.h"
#include "core/error.h"
#include "test_data.h"

using namespace amrvk;
using namespace amrvk::amr;

using namespace amrvk::test;

namespace {

// One field "v"; every cell of the block holds `value`.
Block makeBlock(glm::ivec3 lo, glm::ivec3 hi, float value) {
    Block b;
    b.lo = lo;
    b.hi = hi;
    const glm::ivec3 d = b.dims();
    b.values.push_back(std::vector<float>(size_t(d.x) * size_t(d.y) * size_t(d.z), value));
    return b;
}

// A cube block [lo, hi]^3 in level indices.
Block cubeBlock(int lo, int hi, float value) {
    return makeBlock(glm::ivec3(lo), glm::ivec3(hi), value);
}

BlockLevel makeLevel(int64_t cellWidth, std::vector<Block> blocks) {
    BlockLevel level;
    level.cellWidth = cellWidth;
    level.blocks = std::move(blocks);
    return level;
}

Model emptyModel() {
    Model m;
    m.source = "test";
    m.fields.push_back({"v", {}});
    m.availableFields = {"v"};
    return m;
}

Model leavesOf(const std::vector<BlockLevel>& levels, bool planar = false) {
    Model m = emptyModel();
    appendLeafCells(m, levels, planar);
    return m;
}

// The message appendLeafCells throws for `levels` (a test failure if it throws none).
std::string leafErrorOf(const std::vector<BlockLevel>& levels, bool planar = false) {
    return errorOf([&] { leavesOf(levels, planar); });
}

// The value of the leaf containing finest-unit point p (NaN if none).
float valueAt(const Model& m, glm::ivec3 p) {
    for (size_t i = 0; i < m.cells.size(); ++i) {
        const int w = 1 << m.cells[i].level;
        const glm::ivec3 lo = m.cells[i].lower;
        if (glm::all(glm::greaterThanEqual(p, lo)) && glm::all(glm::lessThan(p, lo + w)))
            return m.fields[0].values[i];
    }
    return NAN;
}

// Widths 4, 2, 1 (Enzo, RefineBy 2). The level-1 block is finest [4, 12)^3 (on level-0 cell
// boundaries); the level-2 block is finest [6, 10)^3: on level-1 boundaries, not on level-0 ones.
std::vector<BlockLevel> enzoLikeLevels() {
    return {makeLevel(4, {cubeBlock(0, 3, 0.0f)}), makeLevel(2, {cubeBlock(2, 5, 1.0f)}),
            makeLevel(1, {cubeBlock(6, 9, 2.0f)})};
}

}  // namespace

TEST(BlockStructured, DeepLevelOnlyAlignedToNextCoarserLevel) {
    const Model m = leavesOf(enzoLikeLevels());
    ASSERT_EQ(m.fields[0].values.size(), m.cells.size());
    const ModelSummary s = summarize(m);
    // Per ExaBrick level (0 = width 1): level 2 all 64; width 2: 64 less the 2^3 under level 2;
    // width 4: 64 less the 2^3 under level 1.
    EXPECT_EQ(s.cellsPerLevel, (std::vector<uint64_t>{64, 56, 56}));
    EXPECT_DOUBLE_EQ(s.leafVolume, 16.0 * 16.0 * 16.0);
    EXPECT_EQ(s.bounds.lower, glm::i64vec3(0));
    EXPECT_EQ(s.bounds.upper, glm::i64vec3(16));
    EXPECT_NO_THROW(validate(m));
    EXPECT_EQ(valueAt(m, {1, 1, 1}), 0.0f);
    EXPECT_EQ(valueAt(m, {4, 4, 4}), 1.0f);
    EXPECT_EQ(valueAt(m, {11, 5, 5}), 1.0f);
    EXPECT_EQ(valueAt(m, {6, 6, 6}), 2.0f);
    EXPECT_EQ(valueAt(m, {9, 9, 9}), 2.0f);
    // Cells come level by level in input order.
    EXPECT_EQ(m.cells.front().level, 2);
    EXPECT_EQ(m.cells.back().level, 0);
}

TEST(BlockStructured, LevelOrderDoesNotMatter) {
    std::vector<BlockLevel> levels = enzoLikeLevels();
    std::swap(levels[0], levels[2]);
    const Model m = leavesOf(levels);
    const ModelSummary s = summarize(m);
    EXPECT_EQ(s.cellsPerLevel, (std::vector<uint64_t>{64, 56, 56}));
    EXPECT_DOUBLE_EQ(s.leafVolume, 4096.0);
    EXPECT_NO_THROW(validate(m));
}

TEST(BlockStructured, RatioFourThenTwo) {
    // Widths 8, 2, 1 (Chombo plt025000's ratios 4 and 2). Level 1: finest [8, 24)^3 in two blocks;
    // level 2: finest [10, 14)^3, on level-1 boundaries but not on level-0 (width 8) ones.
    const std::vector<BlockLevel> levels = {
        makeLevel(8, {cubeBlock(0, 3, 0.0f)}),
        makeLevel(
            2, {makeBlock({4, 4, 4}, {7, 11, 11}, 1.0f), makeBlock({8, 4, 4}, {11, 11, 11}, 1.5f)}),
        makeLevel(1, {cubeBlock(10, 13, 2.0f)})};
    const Model m = leavesOf(levels);
    const ModelSummary s = summarize(m);
    // Per ExaBrick level: width 1 all 64; width 2: 512 less the 2^3 under level 2; width 8: 64
    // less the 2^3 under level 1.
    EXPECT_EQ(s.cellsPerLevel, (std::vector<uint64_t>{64, 504, 0, 56}));
    EXPECT_DOUBLE_EQ(s.leafVolume, 32.0 * 32.0 * 32.0);
    EXPECT_NO_THROW(validate(m));
    EXPECT_EQ(valueAt(m, {0, 0, 0}), 0.0f);
    EXPECT_EQ(valueAt(m, {8, 8, 8}), 1.0f);
    EXPECT_EQ(valueAt(m, {23, 23, 23}), 1.5f);
    EXPECT_EQ(valueAt(m, {12, 12, 12}), 2.0f);
}

TEST(BlockStructured, PlanarSlabCoversInXyOnly) {
    // 2-D widths 8, 2, 1 as one-cell-thick blocks (z = 0..0).
    const std::vector<BlockLevel> levels = {
        makeLevel(8, {makeBlock({0, 0, 0}, {3, 3, 0}, 0.0f)}),
        makeLevel(2, {makeBlock({4, 4, 0}, {11, 11, 0}, 1.0f)}),
        makeLevel(1, {makeBlock({10, 10, 0}, {13, 13, 0}, 2.0f)})};
    const Model m = leavesOf(levels, true);
    const ModelSummary s = summarize(m);
    EXPECT_EQ(s.cellsPerLevel, (std::vector<uint64_t>{16, 60, 0, 12}));
    // Each cell is as thick as it is wide, so the slab area is sum(width^2).
    double area = 0;
    for (const Cell& c : m.cells) {
        EXPECT_EQ(c.lower.z, 0);
        area += std::ldexp(1.0, 2 * c.level);
    }
    EXPECT_DOUBLE_EQ(area, 32.0 * 32.0);
    EXPECT_NO_THROW(validate(m));
    EXPECT_EQ(valueAt(m, {0, 0, 0}), 0.0f);
    EXPECT_EQ(valueAt(m, {8, 8, 1}), 1.0f);
    EXPECT_EQ(valueAt(m, {12, 12, 0}), 2.0f);

    // Without the planar flag the thin finer blocks cover the thicker cells only partly in z.
    expectContains(leafErrorOf(levels), "only partly");
}

TEST(BlockStructured, PlanarBlockMustBeOneCellThick) {
    const std::vector<BlockLevel> levels = {makeLevel(2, {makeBlock({0, 0, 0}, {3, 3, 1}, 0.0f)})};
    const std::string msg = leafErrorOf(levels, true);
    expectContains(msg, "test: level 0 block 0 is 2 cells thick in z");
}

TEST(BlockStructured, PartialCoverIsRejected) {
    // Level-1 block finest [1, 3): half of level-0 cell 0 and half of level-0 cell 1.
    const std::vector<BlockLevel> levels = {makeLevel(2, {cubeBlock(0, 3, 0.0f)}),
                                            makeLevel(1, {cubeBlock(1, 2, 1.0f)})};
    const std::string msg = leafErrorOf(levels);
    expectContains(msg, "test: a finer block covers a level 0 cell of block 0 only partly");
    expectContains(msg, "level 1 block 0 of cell width 1 is not aligned to cell width 2");
}

TEST(BlockStructured, PartialCoverIsCheckedAgainstTheNextCoarserLevel) {
    // Level 2 finest [7, 9) splits level-1 cells [6, 8) and [8, 10).
    std::vector<BlockLevel> levels = enzoLikeLevels();
    levels[2].blocks = {cubeBlock(7, 8, 2.0f)};
    const std::string msg = leafErrorOf(levels);
    expectContains(msg, "a finer block covers a level 1 cell of block 0 only partly");
}

TEST(BlockStructured, NonPowerOfTwoWidthIsRejected) {
    const std::vector<BlockLevel> levels = {makeLevel(3, {cubeBlock(0, 1, 0.0f)}),
                                            makeLevel(1, {cubeBlock(0, 2, 1.0f)})};
    const std::string msg = leafErrorOf(levels);
    expectContains(msg, "test: level 0 has cell width 3 finest cells, not a power of two");
}

TEST(BlockStructured, ValueCountMismatchIsRejected) {
    std::vector<BlockLevel> levels = {makeLevel(1, {cubeBlock(0, 1, 0.0f)})};
    levels[0].blocks[0].values[0].pop_back();
    std::string msg = leafErrorOf(levels);
    expectContains(msg, "test: level 0 block 0 has 7 values for 8 cells");

    levels[0].blocks[0].values.clear();
    msg = leafErrorOf(levels);
    expectContains(msg, "test: level 0 block 0 has 0 fields, expected 1");
}
