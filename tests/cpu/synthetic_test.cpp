#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>

#include "amr/cell_hash.h"
#include "amr/readers.h"
#include "amr/synthetic.h"
#include "amr/synthetic_fields.h"
#include "core/error.h"
#include "test_data.h"

using namespace amrvk;
using namespace amrvk::amr;
namespace fs = std::filesystem;

namespace {

SyntheticParams params(SyntheticKind kind, uint64_t cells, uint64_t seed = 1, int block = 8) {
    SyntheticParams p;
    p.kind = kind;
    p.cells = cells;
    p.seed = seed;
    p.blockCells = block;
    return p;
}

// Cell-octree parameters (one cell per leaf), the generator before blocks.
SyntheticParams cellParams(SyntheticKind kind, uint64_t cells, uint64_t seed = 1) {
    return params(kind, cells, seed, 1);
}

// FNV-1a 64 over the cell records, then the values.
uint64_t digest(const Model& m) {
    uint64_t h = 0xcbf29ce484222325ull;
    auto add = [&](const void* data, size_t bytes) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
    };
    for (const Cell& c : m.cells) add(&c, sizeof(Cell));
    add(m.fields[0].values.data(), m.fields[0].values.size() * sizeof(float));
    return h;
}

// Every cell lies in a complete aligned block of block^3 same-level cells, and each block's
// cells are consecutive in the output. Returns the number of blocks.
uint64_t expectFullBlocks(const Model& m, int block) {
    const uint64_t volume = uint64_t(block) * uint64_t(block) * uint64_t(block);
    EXPECT_EQ(m.cellCount() % volume, 0u);
    CellHash hash(m.cells);
    uint64_t blocks = 0, misses = 0;
    for (size_t i = 0; i < m.cells.size(); ++i) {
        const Cell& c = m.cells[i];
        const int w = 1 << c.level;
        const glm::ivec3 origin = c.lower & glm::ivec3(~(block * w - 1));
        const Cell& first = m.cells[i - i % volume];
        if (first.lower != origin || first.level != c.level) ++misses;
        if (c.lower != origin) continue;
        ++blocks;
        for (int z = 0; z < block; ++z)
            for (int y = 0; y < block; ++y)
                for (int x = 0; x < block; ++x)
                    if (hash.find(origin + glm::ivec3(x, y, z) * w, c.level) == CellHash::kNone) ++misses;
    }
    EXPECT_EQ(misses, 0u);
    EXPECT_EQ(blocks * volume, m.cellCount());
    return blocks;
}

std::string readBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

fs::path withSuffix(fs::path base, const std::string& suffix) {
    base += suffix;
    return base;
}

void expectWithinFactor(uint64_t got, uint64_t target, double factor) {
    EXPECT_GE(static_cast<double>(got) * factor, static_cast<double>(target)) << got << " vs " << target;
    EXPECT_LE(static_cast<double>(got), static_cast<double>(target) * factor) << got << " vs " << target;
}

// Largest level difference between a leaf and the leaf just outside one of its faces.
int largestFaceJump(const Model& m) {
    CellHash hash(m.cells);
    int best = 0;
    for (const Cell& c : m.cells) {
        const int w = 1 << c.level;
        for (int axis = 0; axis < 3; ++axis) {
            for (int side = 0; side < 2; ++side) {
                glm::ivec3 p = c.lower;
                p[axis] += side ? w : -1;
                if (p[axis] < 0) continue;
                for (int32_t level : hash.levels()) {
                    glm::ivec3 lower = p & glm::ivec3(~((1 << level) - 1));
                    if (hash.find(lower, level) != CellHash::kNone) {
                        best = std::max(best, std::abs(level - c.level));
                        break;
                    }
                }
            }
        }
    }
    return best;
}

// The leaves tile the domain cube (volume summed in double: relative tolerance).
void expectFillsDomain(const ModelSummary& s, int rootLevel) {
    const double domain = std::ldexp(1.0, 3 * rootLevel);
    EXPECT_NEAR(s.leafVolume, domain, domain * 1e-12);
}

std::string amrvkBinary() { return std::string(AMRVK_BINARY_DIR) + "/bin/amrvk"; }

}  // namespace

class SyntheticKinds : public ::testing::TestWithParam<SyntheticKind> {};

TEST_P(SyntheticKinds, TenThousandCellsAreValidMultiLevelAndNearTheTarget) {
    for (uint64_t seed : {1u, 2u, 3u}) {
        SyntheticStats st;
        Model m = makeSyntheticModel(cellParams(GetParam(), 10000, seed), &st);
        m.source = "synthetic";
        ASSERT_NO_THROW(validate(m));
        expectWithinFactor(m.cellCount(), 10000, 1.4);
        EXPECT_EQ(st.cells, m.cellCount());
        EXPECT_TRUE(st.targetReached);
        ModelSummary s = summarize(m);
        EXPECT_EQ(s.minLevel, st.minLevel);
        EXPECT_EQ(s.maxLevel, st.maxLevel);
        EXPECT_GE(s.maxLevel - s.minLevel + 1, 3) << "seed " << seed;
        EXPECT_EQ(s.minLevel, 0) << "the finest level should be reached";
        // Inside the domain, leaves filling it completely.
        const int64_t domain = int64_t{1} << st.rootLevel;
        EXPECT_GE(glm::min(s.bounds.lower.x, glm::min(s.bounds.lower.y, s.bounds.lower.z)), 0);
        EXPECT_LE(glm::max(s.bounds.upper.x, glm::max(s.bounds.upper.y, s.bounds.upper.z)), domain);
        expectFillsDomain(s, st.rootLevel);
        for (float v : m.fields[0].values) {
            ASSERT_TRUE(std::isfinite(v));
            ASSERT_GT(v, 0.0f);
        }
        EXPECT_EQ(m.fields[0].name, "scalars");
        EXPECT_EQ(m.availableFields, std::vector<std::string>{"scalars"});
    }
}

TEST_P(SyntheticKinds, SameSeedIsIdenticalOtherSeedDiffers) {
    Model a = makeSyntheticModel(params(GetParam(), 50000, 7));
    Model b = makeSyntheticModel(params(GetParam(), 50000, 7));
    Model c = makeSyntheticModel(params(GetParam(), 50000, 8));
    ASSERT_EQ(a.cellCount(), b.cellCount());
    EXPECT_TRUE(a.cells == b.cells);
    EXPECT_EQ(a.fields[0].values, b.fields[0].values);
    const bool sameCells = a.cellCount() == c.cellCount() &&
                           a.cells == c.cells;
    EXPECT_FALSE(sameCells && a.fields[0].values == c.fields[0].values);
}

TEST_P(SyntheticKinds, LargerTargetsUseCountingPassesAndLandNearTheTarget) {
    SyntheticStats st;
    Model m = makeSyntheticModel(cellParams(GetParam(), 300000, 5), &st);
    expectWithinFactor(m.cellCount(), 300000, 1.4);
    EXPECT_TRUE(st.targetReached);
    ModelSummary s = summarize(m);
    EXPECT_GE(s.maxLevel - s.minLevel + 1, 4);
    expectFillsDomain(s, st.rootLevel);
}

INSTANTIATE_TEST_SUITE_P(All, SyntheticKinds,
                         ::testing::Values(SyntheticKind::Cloud, SyntheticKind::Shells, SyntheticKind::Teapot),
                         [](const auto& p) { return std::string(syntheticKindName(p.param)); });

TEST(Synthetic, TeapotIsATinyObjectInAHugeCoarseDomain) {
    SyntheticStats st;
    Model m = makeSyntheticModel(cellParams(SyntheticKind::Teapot, 10000, 4), &st);
    EXPECT_GE(st.rootLevel, 20);
    ModelSummary s = summarize(m);
    EXPECT_GE(s.bounds.size().x, int64_t{1} << 16);
    EXPECT_GE(s.maxLevel - s.minLevel, 12);
    EXPECT_GE(largestFaceJump(m), 3);
    // Almost every cell belongs to the object: the stadium is a few dozen cells per level.
    EXPECT_GT(s.cellsPerLevel[0] + s.cellsPerLevel[1] + s.cellsPerLevel[2], m.cellCount() * 3 / 4);
}

TEST(Synthetic, SmallAndDegenerateTargets) {
    for (uint64_t n : {1u, 8u, 100u}) {
        Model m = makeSyntheticModel(cellParams(SyntheticKind::Shells, n));
        m.source = "synthetic";
        EXPECT_NO_THROW(validate(m));
        EXPECT_LE(m.cellCount(), std::max<uint64_t>(15, 2 * n));
    }
    SyntheticParams p = cellParams(SyntheticKind::Cloud, 1000);
    p.levels = 1;  // a single possible cell
    EXPECT_EQ(makeSyntheticModel(p).cellCount(), 1u);
    p.levels = 3;  // at most 64 cells: the target cannot be reached
    SyntheticStats st;
    Model m = makeSyntheticModel(p, &st);
    EXPECT_LE(m.cellCount(), 64u);
    EXPECT_FALSE(st.targetReached);
    p.levels = 40;
    EXPECT_THROW(makeSyntheticModel(p), Error);
    EXPECT_THROW(parseSyntheticKind("teacup"), Error);
    EXPECT_EQ(parseSyntheticKind("teapot"), SyntheticKind::Teapot);
}

// Digests of the generator's output computed before block mode existed (x86-64, glibc): block
// size 1 must reproduce it byte for byte (cells and values; the exact best-first regime and,
// for 3e5 cells, counting passes).
TEST(Synthetic, BlockSizeOneReproducesTheCellOctreeGenerator) {
    struct Case {
        SyntheticKind kind;
        uint64_t cells, seed, count, digest;
    };
    for (const Case& c : {Case{SyntheticKind::Cloud, 10000, 1, 9997, 0xa3dc5298f65720edull},
                          Case{SyntheticKind::Shells, 10000, 2, 9997, 0xda4dd219ca034a9full},
                          Case{SyntheticKind::Teapot, 10000, 3, 9997, 0x1dac193ce179eefeull},
                          Case{SyntheticKind::Cloud, 300000, 5, 302548, 0x23e63550ff8a49a3ull}}) {
        SyntheticStats st;
        Model m = makeSyntheticModel(cellParams(c.kind, c.cells, c.seed), &st);
        EXPECT_EQ(st.blockCells, 1);
        EXPECT_EQ(m.cellCount(), c.count) << syntheticKindName(c.kind) << " " << c.cells;
        EXPECT_EQ(digest(m), c.digest) << syntheticKindName(c.kind) << " " << c.cells;
    }
}

class SyntheticBlocks : public ::testing::TestWithParam<SyntheticKind> {};

// Default blocks of 8^3 at a few 1e5 cells: valid, near the target, full aligned blocks,
// several levels; the same cells as files.
TEST_P(SyntheticBlocks, EightCubedBlocksAreFullAlignedAndMultiLevel) {
    // Shells need about 400 blocks for three levels, the teapot 512 for 8^3 blocks.
    const uint64_t n = GetParam() == SyntheticKind::Cloud    ? 100000
                       : GetParam() == SyntheticKind::Shells ? 200000
                                                             : 300000;
    SyntheticParams p = params(GetParam(), n, 3);
    EXPECT_EQ(syntheticBlockCells(p), 8);
    SyntheticStats st;
    Model m = makeSyntheticModel(p, &st);
    m.source = "synthetic";
    ASSERT_NO_THROW(validate(m));
    EXPECT_EQ(st.blockCells, 8);
    const std::pair<std::string, std::string> blockAttribute{"blockCells", "8"};
    EXPECT_NE(std::find(m.attributes.begin(), m.attributes.end(), blockAttribute), m.attributes.end());
    expectWithinFactor(m.cellCount(), n, 1.4);
    EXPECT_TRUE(st.targetReached);
    const uint64_t blocks = expectFullBlocks(m, 8);
    EXPECT_GE(blocks, 64u);
    ModelSummary s = summarize(m);
    EXPECT_EQ(s.minLevel, st.minLevel);
    EXPECT_EQ(s.maxLevel, st.maxLevel);
    expectFillsDomain(s, st.rootLevel);
    EXPECT_LE(st.maxLevel, st.rootLevel - 3) << "cells are an eighth of a node";
    if (GetParam() == SyntheticKind::Teapot) {
        EXPECT_GE(st.rootLevel, 20);
        // Block terms: one cell per block, as wide as the block.
        Model blockModel;
        for (const Cell& c : m.cells)
            if ((c.lower & glm::ivec3((8 << c.level) - 1)) == glm::ivec3(0))
                blockModel.cells.push_back(Cell{c.lower, c.level + 3});
        EXPECT_EQ(blockModel.cellCount(), blocks);
        EXPECT_GE(largestFaceJump(blockModel), 3) << "level jumps between neighbouring blocks";
        EXPECT_LE(s.minLevel, 1) << "the object is refined to (nearly) the finest level";
    } else {
        EXPECT_GE(s.maxLevel - s.minLevel + 1, 3);
    }
    for (float v : m.fields[0].values) ASSERT_TRUE(std::isfinite(v) && v > 0.0f);
}

INSTANTIATE_TEST_SUITE_P(All, SyntheticBlocks,
                         ::testing::Values(SyntheticKind::Cloud, SyntheticKind::Shells, SyntheticKind::Teapot),
                         [](const auto& p) { return std::string(syntheticKindName(p.param)); });

TEST(Synthetic, BlocksWithCountingPassesLandNearTheTarget) {
    // 312500 target blocks of 2^3: past 8x the exact best-first curve, so counting passes run.
    SyntheticStats st;
    Model m = makeSyntheticModel(params(SyntheticKind::Cloud, 2500000, 5, 2), &st);
    EXPECT_GT(st.countingPasses, 0);
    EXPECT_EQ(st.blockCells, 2);
    expectWithinFactor(m.cellCount(), 2500000, 1.4);
    expectFullBlocks(m, 2);
}

TEST(Synthetic, SmallTargetsShrinkTheBlockAndLevelsCountCellLevels) {
    struct Case {
        SyntheticKind kind;
        uint64_t cells;
        int block;
    };
    for (const Case& c : {Case{SyntheticKind::Cloud, 1000, 2}, Case{SyntheticKind::Shells, 5000, 4},
                          Case{SyntheticKind::Cloud, 32768, 8}, Case{SyntheticKind::Teapot, 10000, 2},
                          Case{SyntheticKind::Teapot, 100000, 4}, Case{SyntheticKind::Cloud, 100, 1}}) {
        SyntheticStats st;
        Model m = makeSyntheticModel(params(c.kind, c.cells), &st);
        EXPECT_EQ(st.blockCells, c.block) << syntheticKindName(c.kind) << " " << c.cells;
        expectWithinFactor(m.cellCount(), c.cells, 1.4);
        expectFullBlocks(m, c.block);
    }
    SyntheticParams p = params(SyntheticKind::Cloud, 100000);
    p.levels = 3;  // cell levels 0..2: a domain 4 blocks = 32 cells wide, at most 32768 cells
    SyntheticStats st;
    Model m = makeSyntheticModel(p, &st);
    EXPECT_EQ(st.rootLevel, 5);
    EXPECT_LE(st.maxLevel, 2);
    EXPECT_EQ(m.cellCount(), 32768u);
    EXPECT_FALSE(st.targetReached);
    p.levels = 1;  // a single block
    EXPECT_EQ(makeSyntheticModel(p).cellCount(), 512u);
    p.levels = 29;  // 2^28 blocks of 8 cells exceed the 2^30 domain limit
    EXPECT_THROW(makeSyntheticModel(p), Error);
    p.levels = 0;
    for (int bad : {0, 3, 64, -8}) {
        p.blockCells = bad;
        EXPECT_THROW(makeSyntheticModel(p), Error) << bad;
    }
}

TEST(Synthetic, FilesEqualTheInMemoryModelAndAreDeterministic) {
    const fs::path dir = test::scratchDir();
    SyntheticParams p = params(SyntheticKind::Cloud, 40000, 11);
    SyntheticStats st = generateSynthetic(p, dir / "a");
    generateSynthetic(p, dir / "b");
    EXPECT_EQ(readBytes(dir / "a.cells"), readBytes(dir / "b.cells"));
    EXPECT_EQ(readBytes(dir / "a.scalars"), readBytes(dir / "b.scalars"));
    p.seed = 12;
    generateSynthetic(p, dir / "c");
    EXPECT_NE(readBytes(dir / "a.scalars"), readBytes(dir / "c.scalars"));
    // Nothing but the outputs: no temporary files left behind.
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 6);

    Model files = readModel(dir / "a.cells", ReadOptions{});
    Model memory = makeSyntheticModel(params(SyntheticKind::Cloud, 40000, 11));
    EXPECT_EQ(st.blockCells, 8);
    EXPECT_EQ(st.cells, files.cellCount());
    EXPECT_EQ(st.bytes, files.cellCount() * 20);
    ASSERT_EQ(files.cellCount(), memory.cellCount());
    EXPECT_TRUE(files.cells == memory.cells);
    EXPECT_EQ(files.field("scalars").values, memory.fields[0].values);
}

TEST(Synthetic, StreamsMoreThanOneChunkAndReportsProgress) {
    const fs::path dir = test::scratchDir();
    SyntheticParams p = params(SyntheticKind::Shells, 1500000, 3);
    p.field = "density";
    int calls = 0, writing = 0;
    p.progress = [&](std::string_view phase, double fraction) {
        ++calls;
        writing += phase == "writing";
        EXPECT_GE(fraction, 0.0);
        EXPECT_LE(fraction, 1.0);
    };
    SyntheticStats st = generateSynthetic(p, dir / "big");
    EXPECT_GT(writing, 10);
    EXPECT_GE(calls, writing);
    EXPECT_GT(st.cells, 1u << 20);
    expectWithinFactor(st.cells, 1500000, 1.4);
    EXPECT_EQ(fs::file_size(dir / "big.cells"), st.cells * 16);
    EXPECT_EQ(fs::file_size(dir / "big.density.scalars"), st.cells * 4);
    EXPECT_FALSE(fs::exists(dir / "big.scalars"));
    uint64_t perLevel = 0;
    for (uint64_t n : st.cellsPerLevel) perLevel += n;
    EXPECT_EQ(perLevel, st.cells);

    p.progress = nullptr;
    Model memory = makeSyntheticModel(p);
    Model files = readModel(dir / "big", ReadOptions{});
    ASSERT_EQ(files.cellCount(), memory.cellCount());
    EXPECT_TRUE(files.cells == memory.cells);
    EXPECT_EQ(files.field("density").values, memory.field("density").values);
}

TEST(Synthetic, FailedRunLeavesNothing) {
    const fs::path dir = test::scratchDir();
    EXPECT_THROW(generateSynthetic(params(SyntheticKind::Cloud, 1000), dir / "missing" / "x"), Error);
    EXPECT_FALSE(fs::exists(dir / "missing"));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 0);
}

TEST(GenCommand, WritesFilesThatReadBackAsTheInMemoryModel) {
    if (!fs::exists(amrvkBinary())) GTEST_SKIP() << "amrvk binary not built: " << amrvkBinary();
    const fs::path dir = test::scratchDir();
    for (const char* kind : {"cloud", "shells", "teapot"}) {
        const fs::path base = dir / kind;
        const std::string cmd = amrvkBinary() + " gen " + kind + " --cells 1e4 --seed 5 -o " + base.string() +
                                " > " + (dir / "out.txt").string() + " 2>&1";
        ASSERT_EQ(std::system(cmd.c_str()), 0) << readBytes(dir / "out.txt");
        const std::string out = readBytes(dir / "out.txt");
        EXPECT_NE(out.find(" cells, levels "), std::string::npos) << out;
        EXPECT_NE(out.find(" blocks of "), std::string::npos) << out;
        Model files = readModel(withSuffix(base, ".cells"), ReadOptions{});
        Model memory = makeSyntheticModel(params(parseSyntheticKind(kind), 10000, 5));
        ASSERT_EQ(files.cellCount(), memory.cellCount()) << kind;
        EXPECT_TRUE(files.cells == memory.cells);
        EXPECT_EQ(files.fields[0].values, memory.fields[0].values);
    }
}

TEST(GenCommand, HelpAndErrors) {
    if (!fs::exists(amrvkBinary())) GTEST_SKIP() << "amrvk binary not built: " << amrvkBinary();
    const fs::path dir = test::scratchDir();
    const std::string out = (dir / "out.txt").string();
    ASSERT_EQ(std::system((amrvkBinary() + " gen --help > " + out + " 2>&1").c_str()), 0);
    std::string help = readBytes(out);
    for (const char* word :
         {"cloud", "shells", "teapot", "--cells", "--seed", "--block", "--levels", "--field", "BASE", "B^3"})
        EXPECT_NE(help.find(word), std::string::npos) << word;
    EXPECT_NE(std::system((amrvkBinary() + " gen teacup --cells 100 -o " + (dir / "x").string() + " > " + out +
                           " 2>&1").c_str()),
              0);
    EXPECT_NE(readBytes(out).find("teacup"), std::string::npos);
    EXPECT_NE(std::system((amrvkBinary() + " gen cloud -o " + (dir / "x").string() + " > " + out + " 2>&1").c_str()), 0);
    EXPECT_NE(readBytes(out).find("--cells"), std::string::npos);
    EXPECT_NE(std::system((amrvkBinary() + " gen cloud --cells 1e5 --block 3 -o " + (dir / "x").string() + " > " +
                           out + " 2>&1").c_str()),
              0);
    EXPECT_NE(readBytes(out).find("--block"), std::string::npos);
    EXPECT_FALSE(fs::exists(dir / "x.cells"));
}

namespace {

// The value of node (lower, level) of a synthetic field, reached by refining down from the root.
template <class F>
float nodeValue(const F& field, glm::ivec3 lower, int level) {
    typename F::State state, children[8];
    NodeEval evals[8];
    NodeEval eval = field.root(state);
    glm::ivec3 at(0);
    for (int l = field.rootLevel(); l > level; --l) {
        field.refine(at, l, state, children, evals);
        const int half = 1 << (l - 1);
        const glm::ivec3 o = (lower - at) / half;  // the child holding `lower`
        const int c = o.x | (o.y << 1) | (o.z << 2);
        state = children[c];
        eval = evals[c];
        at += o * half;
    }
    return eval.value;
}

// Largest change of the node values at level 3 on a 16^3 lattice over the domain between times a and b.
template <class Make>
double largestChange(Make&& make, double a, double b) {
    const auto fa = make(a), fb = make(b);
    double change = 0;
    const int step = (1 << fa.rootLevel()) / 16;
    for (int z = 0; z < 16; ++z)
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) {
                const glm::ivec3 lower = glm::ivec3(x, y, z) * step;
                change = std::max(change, double(std::abs(nodeValue(fa, lower, 3) - nodeValue(fb, lower, 3))));
            }
    return change;
}

}  // namespace

// gen --time: the field moves smoothly (changes proportional to the time step: twice the step,
// twice the change), really moves over a quarter period, and has period 1.
TEST(SyntheticTime, FieldsEvolveSmoothlyAndPeriodically) {
    const int root = 10;
    auto cloud = [&](double t) { return CloudField(3, root, t); };
    auto shells = [&](double t) { return ShellsField(3, root, t); };
    auto check = [](const char* name, auto&& make) {
        const double t0 = 0.3;
        const double small = largestChange(make, t0, t0 + 5e-4), twice = largestChange(make, t0, t0 + 1e-3);
        const double quarter = largestChange(make, t0, t0 + 0.25), period = largestChange(make, t0, t0 + 1.0);
        EXPECT_GT(small, 0.0) << name;
        EXPECT_NEAR(twice / small, 2.0, 0.4) << name << ": changes " << small << " and " << twice;
        EXPECT_GT(quarter, 50 * twice) << name << ": a quarter period changes the field";
        EXPECT_LT(period, 1e-3 * quarter) << name << ": period 1";
    };
    check("cloud", cloud);
    check("shells", shells);
}

// The outputs of a series differ: the cloud's densest cell (its contrast swings) and the cells
// of every kind (the refinement follows the field, the teapot's tiny torus included); T = 0 is
// the field without time.
TEST(SyntheticTime, OutputsDifferAndTimeZeroIsTheFieldWithoutTime) {
    auto model = [](SyntheticKind kind, double t) {
        SyntheticParams p = params(kind, 20000, 2);
        p.time = t;
        return makeSyntheticModel(p);
    };
    auto maxValue = [&](double t) {
        const Model m = model(SyntheticKind::Cloud, t);
        return *std::max_element(m.fields[0].values.begin(), m.fields[0].values.end());
    };
    EXPECT_GT(std::abs(std::log(maxValue(0.25)) - std::log(maxValue(0.75))), 0.02);
    for (SyntheticKind kind : {SyntheticKind::Cloud, SyntheticKind::Shells, SyntheticKind::Teapot})
        EXPECT_NE(digest(model(kind, 0.3)), digest(model(kind, 0.35))) << syntheticKindName(kind);
    SyntheticParams p = params(SyntheticKind::Shells, 5000, 4);
    const uint64_t without = digest(makeSyntheticModel(p));
    p.time = 0.0;
    EXPECT_EQ(digest(makeSyntheticModel(p)), without);
    p.time = 0.1;
    EXPECT_NE(digest(makeSyntheticModel(p)), without);
    p.time = std::nan("");
    EXPECT_NE(test::errorOf([&] { makeSyntheticModel(p); }).find("--time nan is outside"), std::string::npos);
}
