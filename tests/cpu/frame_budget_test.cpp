// The frame budget: previews shrink until a sample fits the budget, tiles are as many rows as fit,
// and the estimate follows the measured cost.
#include <gtest/gtest.h>

#include "session/frame_budget.h"

using amrvk::session::FrameBudget;

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
