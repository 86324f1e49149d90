// amr/space_partition: the census, the partition for any number of parts, and the part a rank
// reads, checked independently: boxes against the bounds and the cells by brute force, balance
// against the cell counts, and the part's reconstruction against the whole data's at random
// points (amr::ReferenceSampler, the brute-force tent sum), which is what makes data-parallel
// rendering exact at partition faces.
#include "amr/space_partition.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "amr/readers.h"
#include "amr/sampler.h"
#include "core/error.h"
#include "model_fixtures.h"
#include "test_data.h"

using namespace amrvk;

TEST(SpacePartition, CensusMatchesTheModel) {
    const amr::Model m = test::makeThreeLevelCloud();
    const amr::CellCensus c = amr::censusOf(m);
    const amr::ModelSummary s = amr::summarize(m);
    EXPECT_EQ(c.cells, m.cells.size());
    EXPECT_EQ(c.bounds.lower, s.bounds.lower);
    EXPECT_EQ(c.bounds.upper, s.bounds.upper);
    EXPECT_EQ(c.minLevel, s.minLevel);
    EXPECT_EQ(c.maxLevel, s.maxLevel);
    const auto [lo, hi] = std::minmax_element(m.fields[0].values.begin(), m.fields[0].values.end());
    EXPECT_EQ(c.valueLo, *lo);
    EXPECT_EQ(c.valueHi, *hi);
    uint64_t counted = 0;
    for (uint64_t n : c.counts) counted += n;
    EXPECT_EQ(counted, m.cells.size());
    EXPECT_LE(std::max({c.bins.x, c.bins.y, c.bins.z}), amr::CellCensus::kMaxBins);
}

TEST(SpacePartition, BoxesTileTheBoundsAndOwnEveryCellOnceForAnyCount) {
    const amr::Model m = test::makeThreeLevelCloud();
    const amr::CellCensus c = amr::censusOf(m);
    for (int parts = 1; parts <= 7; ++parts) {
        SCOPED_TRACE(parts);
        const std::vector<amr::Box3l> boxes = amr::partitionByCells(c, parts);
        ASSERT_EQ(boxes.size(), size_t(parts));
        double volume = 0;
        for (size_t i = 0; i < boxes.size(); ++i) {
            volume += boxes[i].volume();
            for (size_t j = i + 1; j < boxes.size(); ++j) {
                const glm::i64vec3 lo = glm::max(boxes[i].lower, boxes[j].lower);
                const glm::i64vec3 hi = glm::min(boxes[i].upper, boxes[j].upper);
                EXPECT_TRUE((amr::Box3l{lo, hi}.empty())) << "boxes " << i << " and " << j << " overlap";
            }
        }
        EXPECT_EQ(volume, c.bounds.volume());
        std::vector<uint64_t> owned(boxes.size(), 0);
        for (const amr::Cell& cell : m.cells) {
            int owners = 0;
            for (size_t i = 0; i < boxes.size(); ++i)
                if (amr::ownsCell(boxes[i], cell)) {
                    ++owners;
                    ++owned[i];
                }
            ASSERT_EQ(owners, 1) << amr::describeCell(cell);
        }
        // Balanced as far as 128 bins per axis allow: no part above 1.3x the mean on this cloud.
        const double mean = double(m.cells.size()) / parts;
        for (uint64_t n : owned) {
            EXPECT_GT(n, 0u);
            EXPECT_LE(double(n), 1.3 * mean);
        }
    }
}

TEST(SpacePartition, APartReconstructsTheWholeFieldInsideItsBox) {
    amr::Model m = test::makeThreeLevelCloud();
    const amr::CellCensus c = amr::censusOf(m);
    const amr::ReferenceSampler whole(m, m.fields[0]);
    std::mt19937 rng(11);
    for (int parts : {2, 3, 5}) {
        const std::vector<amr::Box3l> boxes = amr::partitionByCells(c, parts);
        for (const amr::Box3l& box : boxes) {
            amr::Model part;
            part.fields = {amr::Field{m.fields[0].name, {}}};
            for (size_t i = 0; i < m.cells.size(); ++i)
                if (amr::supportMeets(m.cells[i], box)) {
                    part.cells.push_back(m.cells[i]);
                    part.fields[0].values.push_back(m.fields[0].values[i]);
                }
            ASSERT_LT(part.cells.size(), m.cells.size());
            const amr::ReferenceSampler local(part, part.fields[0]);
            // Random points, and points on the box's faces (where the halo matters).
            for (int k = 0; k < 4000; ++k) {
                glm::dvec3 p;
                for (int a = 0; a < 3; ++a)
                    p[a] = std::uniform_real_distribution<double>(double(box.lower[a]), double(box.upper[a]))(rng);
                if (k % 2) {
                    const int a = k % 3;
                    p[a] = double((k / 2) % 2 ? box.lower[a] : box.upper[a]) - ((k / 2) % 2 ? 0.0 : 1e-9);
                }
                const amr::Sample w = whole.sample(p), l = local.sample(p);
                ASSERT_NEAR(l.weightSum, w.weightSum, 1e-12 * std::max(1.0, w.weightSum));
                ASSERT_NEAR(l.value, w.value, 1e-9 * std::max(1.0, std::abs(w.value)));
            }
        }
    }
}

TEST(SpacePartition, AWrongHaloIsCaught) {
    // Power of the test above: a part grown by too little (cells meeting the box itself only)
    // reconstructs differently near its faces.
    amr::Model m = test::makeThreeLevelCloud();
    const amr::CellCensus c = amr::censusOf(m);
    const amr::ReferenceSampler whole(m, m.fields[0]);
    const amr::Box3l box = amr::partitionByCells(c, 2)[0];
    amr::Model part;
    part.fields = {amr::Field{m.fields[0].name, {}}};
    for (size_t i = 0; i < m.cells.size(); ++i) {
        const amr::Cell& cell = m.cells[i];
        const glm::i64vec3 lo(cell.lower), hi = lo + glm::i64vec3(amr::cellWidth(cell.level));
        if ((amr::Box3l{glm::max(lo, box.lower), glm::min(hi, box.upper)}.empty())) continue;
        part.cells.push_back(cell);
        part.fields[0].values.push_back(m.fields[0].values[i]);
    }
    const amr::ReferenceSampler local(part, part.fields[0]);
    std::mt19937 rng(3);
    int differ = 0;
    for (int k = 0; k < 2000; ++k) {
        glm::dvec3 p;
        for (int a = 0; a < 3; ++a)
            p[a] = std::uniform_real_distribution<double>(double(box.lower[a]), double(box.upper[a]))(rng);
        p.x = double(box.upper.x) - 0.25;  // just inside the face the cut runs along
        differ += std::abs(local.sample(p).value - whole.sample(p).value) > 1e-9 * std::max(1.0, whole.sample(p).value);
    }
    EXPECT_GT(differ, 0);
}

TEST(SpacePartition, ReadPartStreamsTheCellsThatMeetTheBox) {
    amr::Model m = test::makeThreeLevelCloud();
    const std::filesystem::path base = test::scratchDir() / "partition";
    amr::writeExaBrick(m, base);
    amr::ReadOptions ro;
    // The streamed census equals the one of the model in memory.
    const amr::CellCensus streamed = amr::censusOf(std::filesystem::path(base) += ".cells", ro);
    const amr::CellCensus memory = amr::censusOf(m);
    EXPECT_EQ(streamed.counts, memory.counts);
    EXPECT_EQ(streamed.head.format, "exabrick");
    const amr::Box3l box = amr::partitionByCells(streamed, 3)[1];
    const amr::Model part = amr::readPart(std::filesystem::path(base) += ".cells", ro, box);
    size_t expected = 0;
    for (size_t i = 0; i < m.cells.size(); ++i) expected += amr::supportMeets(m.cells[i], box);
    EXPECT_EQ(part.cells.size(), expected);
    ASSERT_EQ(part.fields.size(), 1u);
    EXPECT_EQ(part.fields[0].values.size(), expected);
    // Chunks smaller than the file: the same cells in the same order.
    std::vector<amr::Cell> chunked;
    amr::visitExaBrick(
        std::filesystem::path(base) += ".cells", ro, 1000,
        [&](amr::Model& chunk) { chunked.insert(chunked.end(), chunk.cells.begin(), chunk.cells.end()); }, nullptr);
    ASSERT_EQ(chunked.size(), m.cells.size());
    EXPECT_TRUE(std::equal(chunked.begin(), chunked.end(), m.cells.begin()));
}

TEST(SpacePartition, MorePartsThanOccupiedBinsIsOneLine) {
    amr::Model m;
    m.source = "two.cells";
    m.cells = {{{0, 0, 0}, 0}, {{1, 0, 0}, 0}};
    m.fields = {amr::Field{"f", {1.0f, 2.0f}}};
    const amr::CellCensus c = amr::censusOf(m);
    EXPECT_EQ(amr::partitionByCells(c, 2).size(), 2u);
    try {
        amr::partitionByCells(c, 3);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("cannot split 2 cells into 3 parts"), std::string::npos) << e.what();
    }
}

// A rank's part keeps its field's units (issue 33, point 5): the data-parallel legend shows them.
TEST(SpacePartition, APartKeepsItsFieldsUnits) {
    AMRVK_REQUIRE_DATA("ramses_galaxy_3d/output_00010");
    amr::ReadOptions ro;
    ro.fields = {"density"};
    const amr::Box3l box{glm::i64vec3(0), glm::i64vec3(32)};
    const amr::Model part = amr::readPart(test::dataDir() / "ramses_galaxy_3d" / "output_00010", ro, box);
    ASSERT_EQ(part.fields.size(), 1u);
    EXPECT_FALSE(part.cells.empty());
    EXPECT_EQ(part.fields[0].units, "code units (1 = 1.66e-24 g/cm^3)");
}
