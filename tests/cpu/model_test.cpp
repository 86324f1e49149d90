#include <gtest/gtest.h>

#include "amr/model.h"
#include "core/error.h"

using namespace amrvk;
using namespace amrvk::amr;

namespace {
Model twoLevelModel() {
    Model m;
    m.source = "test";
    // One level-1 cell at the origin and eight level-0 cells filling the next level-1 slot.
    m.cells.push_back({{0, 0, 0}, 1});
    for (int i = 0; i < 8; ++i) m.cells.push_back({{2 + (i & 1), (i >> 1) & 1, (i >> 2) & 1}, 0});
    m.fields.push_back({"v", std::vector<float>(m.cells.size(), 1.0f)});
    m.availableFields = {"v"};
    return m;
}
}  // namespace

TEST(Model, ValidModelPasses) {
    Model m = twoLevelModel();
    EXPECT_NO_THROW(validate(m));
    ModelSummary s = summarize(m);
    EXPECT_EQ(s.minLevel, 0);
    EXPECT_EQ(s.maxLevel, 1);
    ASSERT_EQ(s.cellsPerLevel.size(), 2u);
    EXPECT_EQ(s.cellsPerLevel[0], 8u);
    EXPECT_EQ(s.cellsPerLevel[1], 1u);
    EXPECT_EQ(s.bounds.lower, glm::i64vec3(0));
    EXPECT_EQ(s.bounds.upper, glm::i64vec3(4, 2, 2));
    EXPECT_DOUBLE_EQ(s.leafVolume, 16.0);
}

TEST(Model, MisalignedCellIsRejected) {
    Model m = twoLevelModel();
    m.cells.set(0, {{1, 0, 0}, m.cells[0].level});
    try {
        validate(m);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("not aligned"), std::string::npos) << e.what();
    }
}

TEST(Model, OverlappingCellsAreRejected) {
    Model m = twoLevelModel();
    m.cells.push_back({{1, 1, 1}, 0});  // inside the level-1 cell at the origin
    m.fields[0].values.push_back(1.0f);
    try {
        validate(m);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("overlapping"), std::string::npos) << e.what();
    }
}

TEST(Model, DuplicateCellsAreRejected) {
    Model m = twoLevelModel();
    m.cells.push_back(m.cells[3]);
    m.fields[0].values.push_back(1.0f);
    EXPECT_THROW(validate(m), Error);
}

TEST(Model, FieldLengthMismatchIsRejected) {
    Model m = twoLevelModel();
    m.fields[0].values.pop_back();
    EXPECT_THROW(validate(m), Error);
}

TEST(Model, NanPolicyRejectNamesFieldAndCell) {
    Model m = twoLevelModel();
    m.fields[0].values[4] = std::numeric_limits<float>::quiet_NaN();
    try {
        applyNanPolicy(m, NanPolicy::Reject);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find("'v'"), std::string::npos) << msg;
        EXPECT_NE(msg.find("cell 4"), std::string::npos) << msg;
    }
}

TEST(Model, NanPolicyDropRemovesCellsInEveryField) {
    Model m = twoLevelModel();
    m.fields.push_back({"w", std::vector<float>(m.cells.size(), 2.0f)});
    m.fields[0].values[4] = std::numeric_limits<float>::infinity();
    m.fields[1].values[6] = std::numeric_limits<float>::quiet_NaN();
    applyNanPolicy(m, NanPolicy::Drop);
    EXPECT_EQ(m.cells.size(), 7u);
    EXPECT_EQ(m.fields[0].values.size(), 7u);
    EXPECT_EQ(m.fields[1].values.size(), 7u);
    for (const Field& f : m.fields)
        for (float v : f.values) EXPECT_TRUE(std::isfinite(v));
    EXPECT_NO_THROW(validate(m));
}

TEST(Model, FieldStatsAreVolumeWeighted) {
    Model m = twoLevelModel();
    m.fields[0].values[0] = 9.0f;  // the level-1 cell has volume 8, the others volume 1
    FieldStats st = computeFieldStats(m, m.fields[0]);
    EXPECT_FLOAT_EQ(st.minValue, 1.0f);
    EXPECT_FLOAT_EQ(st.maxValue, 9.0f);
    EXPECT_DOUBLE_EQ(st.volumeWeightedMean, (9.0 * 8 + 8.0) / 16.0);
}
