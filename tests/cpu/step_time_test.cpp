// When a data set is (amr/step_time.h): read from the attributes each reader records, and from
// the real Enzo and AMReX outputs of ../shared/data/amr.
#include "amr/step_time.h"

#include <gtest/gtest.h>

#include "amr/readers.h"
#include "test_data.h"

using namespace amrvk;
using amr::StepTime;

TEST(StepTime, RedshiftOfACosmologicalRunElseTheTime) {
    auto kindAndValue = [](const std::vector<std::pair<std::string, std::string>>& a) {
        const std::optional<StepTime> t = amr::stepTimeOf(a);
        return t ? std::pair(int(t->kind), t->value) : std::pair(-1, 0.0);
    };
    // Enzo, comoving: the redshift, whatever the time.
    EXPECT_EQ(
        kindAndValue({{"InitialTime", "0.81"}, {"CosmologyCurrentRedshift", "3.5"}, {"ComovingCoordinates", "1"}}),
        std::pair(int(StepTime::Kind::Redshift), 3.5));
    // Not comoving: a CosmologyCurrentRedshift means nothing; the time.
    EXPECT_EQ(
        kindAndValue({{"InitialTime", "0.81"}, {"CosmologyCurrentRedshift", "3.5"}, {"ComovingCoordinates", "0"}}),
        std::pair(int(StepTime::Kind::Time), 0.81));
    EXPECT_EQ(kindAndValue({{"time", "1.25e-3 "}}), std::pair(int(StepTime::Kind::Time), 1.25e-3));
    // None, or not a number: no time rather than a wrong one.
    EXPECT_EQ(kindAndValue({}), std::pair(-1, 0.0));
    EXPECT_EQ(kindAndValue({{"time", "nan"}}), std::pair(-1, 0.0));
    EXPECT_EQ(kindAndValue({{"time", "0.5 s"}}), std::pair(-1, 0.0));
    EXPECT_EQ(amr::describe({StepTime::Kind::Redshift, 3.5}), "z = 3.5");
    EXPECT_EQ(amr::describe({StepTime::Kind::Time, 0.125}), "t = 0.125");
}

TEST(StepTime, RealOutputsSayWhenTheyAre) {
    // enzo_tiny_cosmology DD0018's parameter file: ComovingCoordinates = 1,
    // CosmologyCurrentRedshift = 1.1456033320512, InitialTime = 90.816474721178.
    const std::optional<StepTime> t =
        amr::stepTimeOf(amr::readModel(test::dataDir() / "enzo_tiny_cosmology" / "DD0018" / "DD0018", {}).attributes);
    ASSERT_TRUE(t.has_value());
    EXPECT_EQ(t->kind, StepTime::Kind::Redshift);
    EXPECT_DOUBLE_EQ(t->value, 1.1456033320512);
}
