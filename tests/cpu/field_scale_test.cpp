// amr::applyFieldScale (--scale log): log10 of each cell's value, against values whose logarithms
// are known exactly; the floor for values <= 0 (the smallest positive value, or --log-floor); NaN
// left alone; the error for a field with no positive value; and the file readers (whole and
// streamed) taking the same logs.
#include <gtest/gtest.h>

#include <cmath>

#include "amr/readers.h"
#include "amr/space_partition.h"
#include "model_fixtures.h"
#include "test_data.h"

using namespace amrvk;

namespace {

amr::Model fiveCells(std::vector<float> values) {
    amr::Model m;
    m.source = "five.cells";
    for (int i = 0; i < int(values.size()); ++i) m.cells.push_back({{i, 0, 0}, 0});
    m.fields = {amr::Field{"rho", std::move(values)}};
    return m;
}

}  // namespace

TEST(FieldScale, LogOfPowersOfTenAndTheFloor) {
    amr::Model m = fiveCells({1e-3f, 1.0f, 1e3f, 0.0f, -2.0f, NAN});
    const amr::ScaleReport r = amr::applyFieldScale(m, amr::FieldScale::Log);
    const std::vector<float>& v = m.fields[0].values;
    EXPECT_NEAR(v[0], -3.0f, 1e-6f);
    EXPECT_EQ(v[1], 0.0f);
    EXPECT_NEAR(v[2], 3.0f, 1e-6f);
    EXPECT_NEAR(v[3], -3.0f, 1e-6f);  // 0 and -2: floored at the smallest positive value, 1e-3
    EXPECT_NEAR(v[4], -3.0f, 1e-6f);
    EXPECT_TRUE(std::isnan(v[5]));
    EXPECT_EQ(r.floored, 2u);
    EXPECT_FLOAT_EQ(float(r.floor), 1e-3f);
    bool recorded = false;
    for (const auto& [k, text] : m.attributes) recorded = recorded || (k == "logFloored" && text.find("2 cells") == 0);
    EXPECT_TRUE(recorded);
}

TEST(FieldScale, AnExplicitFloorAndLinearLeaveWhatTheySay) {
    amr::Model m = fiveCells({1e-3f, 1.0f, 100.0f, 0.0f});
    const amr::ScaleReport r = amr::applyFieldScale(m, amr::FieldScale::Log, 0.1);
    EXPECT_NEAR(m.fields[0].values[0], -1.0f, 1e-6f);  // below the floor
    EXPECT_NEAR(m.fields[0].values[2], 2.0f, 1e-6f);
    EXPECT_NEAR(m.fields[0].values[3], -1.0f, 1e-6f);
    EXPECT_EQ(r.floored, 2u);
    amr::Model same = fiveCells({-1.0f, 2.0f});
    amr::applyFieldScale(same, amr::FieldScale::Linear);
    EXPECT_EQ(same.fields[0].values, (std::vector<float>{-1.0f, 2.0f}));
}

TEST(FieldScale, NoPositiveValueIsOneLine) {
    amr::Model m = fiveCells({0.0f, -1.0f});
    const std::string e = test::errorOf([&] { amr::applyFieldScale(m, amr::FieldScale::Log); });
    EXPECT_NE(e.find("five.cells: field 'rho' has no positive value: log scale needs one (or --log-floor)"),
              std::string::npos)
        << e;
    EXPECT_EQ(amr::parseFieldScale("log"), amr::FieldScale::Log);
    EXPECT_NE(test::errorOf([] { amr::parseFieldScale("ln"); }).find("--scale: 'ln' is not auto, linear or log"),
              std::string::npos);
}

TEST(FieldScale, ReadersWholeAndStreamedTakeTheSameLogs) {
    amr::Model m = test::makeThreeLevelCloud();
    m.fields.resize(1);
    m.fields[0].values[7] = 0.0f;  // one cell to floor
    const std::filesystem::path base = test::scratchDir() / "logscale";
    amr::writeExaBrick(m, base);
    amr::ReadOptions ro;
    ro.scale = amr::FieldScale::Log;
    const amr::Model whole = amr::readModel(std::filesystem::path(base) += ".cells", ro);
    const float lo = amr::smallestPositive(m.fields[0].values);
    ASSERT_EQ(whole.fields[0].values.size(), m.fields[0].values.size());
    for (size_t i = 0; i < m.cells.size(); ++i)
        ASSERT_EQ(whole.fields[0].values[i], float(std::log10(std::max(double(m.fields[0].values[i]), double(lo)))))
            << i;
    // The streamed census (data-parallel MPI) sees the same range.
    const amr::CellCensus c = amr::censusOf(std::filesystem::path(base) += ".cells", ro);
    const auto [mn, mx] = std::minmax_element(whole.fields[0].values.begin(), whole.fields[0].values.end());
    EXPECT_EQ(c.valueLo, *mn);
    EXPECT_EQ(c.valueHi, *mx);
    EXPECT_EQ(c.logFloor, double(lo)) << "the floor every rank's readPart takes";
    // A given --log-floor reaches the census and the parts: a rank's cells equal the whole read's.
    ro.logFloor = 0.5;
    const amr::CellCensus given = amr::censusOf(std::filesystem::path(base) += ".cells", ro);
    EXPECT_EQ(given.logFloor, 0.5);
    amr::ReadOptions partOptions = ro;
    partOptions.logFloor = given.logFloor;
    const amr::Model part = amr::readPart(std::filesystem::path(base) += ".cells", partOptions, given.bounds);
    const amr::Model wholeGiven = amr::readModel(std::filesystem::path(base) += ".cells", ro);
    ASSERT_EQ(part.fields[0].values.size(), wholeGiven.fields[0].values.size());
    EXPECT_EQ(given.valueLo, *std::min_element(wholeGiven.fields[0].values.begin(), wholeGiven.fields[0].values.end()));
    EXPECT_FLOAT_EQ(given.valueLo, float(std::log10(0.5)));
}

// --scale auto (amr::autoScaleOf): log where every finite value is positive and the largest is at
// least 100 times the smallest; NaN and infinities are ignored; chunks seen one by one
// (FiniteExtremes, the streamed ExaBrick read) decide as the whole does; resolvedScale of a file
// (one streamed pass) decides what readModel does with the values whole.
TEST(FieldScale, AutoTakesTheLogWhereEveryValueIsPositiveAndTheySpanTwoDecades) {
    using amr::FieldScale;
    auto decide = [](std::vector<float> v) { return amr::autoScaleOf(std::span<const float>(v)); };
    EXPECT_EQ(decide({1.0f, 99.9f}), FieldScale::Linear);
    EXPECT_EQ(decide({1.0f, 100.0f}), FieldScale::Log);
    EXPECT_EQ(decide({0.0f, 1e6f}), FieldScale::Linear) << "a zero: no log";
    EXPECT_EQ(decide({-1.0f, 1e6f}), FieldScale::Linear);
    EXPECT_EQ(decide({NAN, 2.0f, 400.0f, INFINITY}), FieldScale::Log) << "non-finite values are ignored";
    EXPECT_EQ(decide({NAN, -INFINITY}), FieldScale::Linear) << "no finite value";
    EXPECT_EQ(decide({}), FieldScale::Linear);
    // In chunks: the extremes of the whole, whichever chunk holds them.
    const std::vector<float> a = {5.0f, 7.0f}, b = {NAN, 600.0f}, c = {0.5f};
    amr::FiniteExtremes e;
    for (const auto* chunk : {&a, &b, &c}) e.add(*chunk);
    EXPECT_EQ(e.lo, 0.5f);
    EXPECT_EQ(e.hi, 600.0f);
    EXPECT_EQ(e.autoScale(), FieldScale::Log);
    // A file: the streamed decision and the whole read's agree, both ways.
    for (const bool spans : {true, false}) {
        amr::Model m = test::makeThreeLevelCloud();
        m.fields.resize(1);
        for (size_t i = 0; i < m.fields[0].values.size(); ++i)
            m.fields[0].values[i] = spans ? std::pow(10.0f, float(i % 5)) : 1.0f + float(i % 5);
        const std::filesystem::path base = test::scratchDir() / (spans ? "auto_log" : "auto_linear");
        amr::writeExaBrick(m, base);
        const std::filesystem::path cells = std::filesystem::path(base) += ".cells";
        amr::ReadOptions ro;
        ro.scale = FieldScale::Auto;
        const FieldScale streamed = amr::resolvedScale(cells, ro);
        EXPECT_EQ(streamed, spans ? FieldScale::Log : FieldScale::Linear);
        EXPECT_EQ(amr::scaleOf(amr::readModel(cells, ro)), streamed);
    }
}

// A field large enough to be done in parallel chunks (64 from 65,536 values on): the logs, the
// floored count, the smallest positive value and the finite extremes are those of one pass over
// the values, whatever the thread count; the smallest positive value and the extremes sit in
// the last chunk, the floored cells in every one.
TEST(FieldScale, LargeFieldsInChunksMatchOnePass) {
    const size_t n = 300007;
    std::vector<float> values(n);
    for (size_t i = 0; i < n; ++i) {
        const float x = float(1 + (i * 7919) % 100000) * 0.01f;  // 0.01 .. 1000
        values[i] = i % 97 == 0 ? 0.0f : i % 89 == 0 ? -x : i % 83 == 0 ? NAN : i % 79 == 0 ? INFINITY : x;
    }
    values[n - 2] = 1e-6f;  // the smallest positive value
    values[n - 3] = 5e6f;   // the largest finite one
    float smallest = 0, lo = INFINITY, hi = -INFINITY;
    for (float v : values) {
        if (v > 0 && std::isfinite(v) && (smallest == 0 || v < smallest)) smallest = v;
        if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    }
    ASSERT_EQ(smallest, 1e-6f);
    EXPECT_EQ(amr::smallestPositive(values), smallest);
    amr::FiniteExtremes e;
    e.add(values);
    EXPECT_EQ(e.lo, lo);
    EXPECT_EQ(e.hi, 5e6f);
    EXPECT_EQ(e.hi, hi);

    amr::Model m;
    m.source = "large.cells";
    m.cells.resize(n, amr::Cell{{0, 0, 0}, 0});  // one cell n times: the scale reads values only
    m.fields = {amr::Field{"rho", values}};
    const amr::ScaleReport r = amr::applyFieldScale(m, amr::FieldScale::Log);
    uint64_t floored = 0;
    for (size_t i = 0; i < n; ++i) {
        const float v = values[i];
        if (std::isnan(v)) {
            EXPECT_TRUE(std::isnan(m.fields[0].values[i])) << i;
            continue;
        }
        floored += !(double(v) >= double(smallest));
        ASSERT_EQ(m.fields[0].values[i], float(std::log10(std::max(double(v), double(smallest))))) << i;
    }
    EXPECT_GT(floored, n / 100);
    EXPECT_EQ(r.floored, floored);
    EXPECT_EQ(r.floor, double(smallest));
}
