#include "amr/model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

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

// The field a picture shows when none is named (issue 52, point 10): the density-like one, as yt
// shows, else the first (an AMReX plotfile lists x_velocity first).
TEST(Model, TheDefaultFieldIsTheDensityLikeOneElseTheFirst) {
    EXPECT_EQ(defaultFieldIndex({"x_velocity", "y_velocity", "density", "rhoh"}), 2u);
    EXPECT_EQ(defaultFieldIndex({"Density", "Dark_Matter_Density"}), 0u);
    EXPECT_EQ(defaultFieldIndex({"velx", "RHO"}), 1u);
    EXPECT_EQ(defaultFieldIndex({"velx", "dens", "rho"}), 1u);
    EXPECT_EQ(defaultFieldIndex({"Enthalpy", "Dark_Matter_Density", "densityish"}), 0u);
    EXPECT_EQ(defaultFieldIndex({}), 0u);
    Model m = twoLevelModel();
    m.fields.insert(m.fields.begin(), {"x_velocity", m.fields[0].values});
    m.fields.push_back({"gas_density", m.fields[0].values});
    EXPECT_EQ(m.defaultField().name, "gas_density");
}

// World coordinates beyond what amrvk holds are named (issue 52, point 16: Carpet cells of
// 1e-300 were reported as a camera whose eye and target coincide).
TEST(Model, ATransformBeyondTheWorldLimitsIsRejected) {
    Model m = twoLevelModel();
    EXPECT_NO_THROW(validateCells(m));
    m.voxelToWorld.scale = glm::dvec3(1e-30);
    EXPECT_NO_THROW(validateCells(m));
    for (const auto& [scale, origin, fragment] :
         std::vector<std::tuple<double, double, std::string>>{{1e-31, 0, "test: a finest cell is 1e-31 wide on axis 0"},
                                                              {1e31, 0, "test: a finest cell is 1e+31 wide on axis 0"},
                                                              {std::nan(""), 0, "a finest cell is nan wide"},
                                                              {1, -2e30, "test: the origin is -2e+30 on axis 0"},
                                                              {1, INFINITY, "the origin is inf on axis 0"}}) {
        m.voxelToWorld.scale = glm::dvec3(scale);
        m.voxelToWorld.origin = glm::dvec3(origin);
        try {
            validateCells(m);
            ADD_FAILURE() << "accepted " << fragment;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
        }
    }
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
