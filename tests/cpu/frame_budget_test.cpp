// The frame budget: previews shrink until a sample fits the budget, tiles are as many rows as fit,
// and the estimate follows the measured cost.
#include "viewer/logic/frame_budget.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using amrvk::viewer::FrameBudget;

TEST(FrameBudget, PreviewAndTilesFitTheBudget) {
    FrameBudget b(0.05);
    // lavapipe-like: 1 s for a 1024 x 768 sample.
    b.record(1.0, 1024 * 768);
    EXPECT_NEAR(b.secondsPerPixelSample(), 1.0 / (1024 * 768), 1e-15);
    const int s = b.previewScale(1024, 768);
    EXPECT_EQ(s, 8);  // 1/64 of the pixels: 16 ms; 1/16 would be 62 ms
    EXPECT_LE(double(1024 / s) * (768 / s) * b.secondsPerPixelSample(), 0.05);
    const uint32_t rows = b.rowsPerFrame(1024, 768);
    EXPECT_EQ(rows, 38u);  // 38 rows x 1024 px: 49.5 ms
    // A fast GPU: everything at once.
    FrameBudget g(0.05);
    g.record(0.002, 1024 * 768);
    EXPECT_EQ(g.previewScale(1024, 768), 1);
    EXPECT_EQ(g.rowsPerFrame(1024, 768), 768u);
    // Extremely slow: the smallest preview and one row at least.
    FrameBudget slow(0.05);
    slow.record(100.0, 1024 * 768);
    EXPECT_EQ(slow.previewScale(1024, 768), 32);
    EXPECT_EQ(slow.rowsPerFrame(1024, 768), 1u);
}

TEST(FrameBudget, TheRestOfTheFrameComesOutOfTheBudget) {
    FrameBudget b(0.05);
    for (int i = 0; i < 50; ++i) b.recordOtherWork(0.02);  // UI + display: 20 ms a frame
    EXPECT_NEAR(b.budgetSeconds(), 0.03, 1e-6);
    for (int i = 0; i < 50; ++i) b.recordOtherWork(1.0);  // a very slow UI: the tracer keeps 1/10
    EXPECT_NEAR(b.budgetSeconds(), 0.005, 1e-12);
}

TEST(FrameBudget, FollowsTheMeasuredCost) {
    FrameBudget b(0.05);
    b.record(1.0, 1000);
    b.record(3.0, 1000);
    EXPECT_NEAR(b.secondsPerPixelSample(), 2e-3, 1e-12);
    b.record(0.0, 1000);  // nothing measured: ignored
    b.record(1.0, 0);
    EXPECT_NEAR(b.secondsPerPixelSample(), 2e-3, 1e-12);
}

TEST(FrameBudget, TilesAreSizedFromTheCostOfTheSameRowsInThePreviousSample) {
    // A 100 x 100 picture whose top half is empty sky (0.1 us a row) and bottom half dense (9 ms a row).
    FrameBudget b(0.05);
    const auto rowCost = [](uint32_t r) { return r < 50 ? 1e-7 : 9e-3; };
    for (uint32_t r = 0; r < 100; ++r) b.recordRows(rowCost(r), r, 1, 100, 100);
    // From the top: all 50 cheap rows and 5 dense ones (45 ms); a 6th would make 54 ms.
    EXPECT_EQ(b.rowsPerFrame(100, 100, 0), 55u);
    // The running mean (near the dense rows' cost, the last measured) would trace 5 rows of sky a
    // frame: 11 times as many frames for the top half.
    EXPECT_LE(uint32_t(0.05 / (100 * b.secondsPerPixelSample())), 5u);
    // Inside the dense half: 5 rows.
    EXPECT_EQ(b.rowsPerFrame(100, 100, 60), 5u);
    // Near the end, no more rows than are left; always at least one.
    EXPECT_EQ(b.rowsPerFrame(100, 100, 98), 2u);
    b.recordRows(1.0, 70, 1, 100, 100);  // one very slow row
    EXPECT_EQ(b.rowsPerFrame(100, 100, 70), 1u);

    // A tile's time is spread evenly over its rows: 4 rows in 40 ms = 10 ms each, so 5 fit.
    FrameBudget t(0.05);
    t.recordRows(0.04, 0, 4, 100, 100);
    EXPECT_EQ(t.rowsPerFrame(100, 100, 0), 5u);

    // A new image size drops the profile: back to the mean cost.
    b.recordRows(0.001, 0, 10, 200, 50);
    const uint32_t meanRows = uint32_t(std::floor(0.05 / (200 * b.secondsPerPixelSample())));
    EXPECT_EQ(b.rowsPerFrame(200, 50, 20), std::min(std::max(meanRows, 1u), 30u));
}
