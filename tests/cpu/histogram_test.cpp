// Field histograms: counts per bin by cells or by volume (8^level per cell), values outside the
// range and NaN counted apart, the top value in the last bin.
#include "viewer/logic/histogram.h"

#include <gtest/gtest.h>

#include "core/error.h"

using namespace amrvk;

TEST(Histogram, CountsCellsOrVolume) {
    amr::Model m;
    m.cells = {{{0, 0, 0}, 0}, {{1, 0, 0}, 0}, {{2, 0, 0}, 1}, {{4, 0, 0}, 2}, {{8, 0, 0}, 0}, {{9, 0, 0}, 0},
               {{10, 0, 0}, 0}};
    amr::Field f{"v", {0.0f, 0.49f, 0.5f, 1.0f, -3.0f, 7.0f, NAN}};
    const viewer::Histogram h = viewer::fieldHistogram(m, f, 0.0f, 1.0f, 2);
    ASSERT_EQ(h.counts.size(), 2u);
    EXPECT_EQ(h.counts[0], 2.0);  // 0 and 0.49
    EXPECT_EQ(h.counts[1], 2.0);  // 0.5 and 1 (the top value goes in the last bin)
    EXPECT_EQ(h.below, 1.0);
    EXPECT_EQ(h.above, 1.0);
    EXPECT_EQ(h.nan, 1.0);
    EXPECT_EQ(h.maxCount(), 2.0);
    const viewer::Histogram v = viewer::fieldHistogram(m, f, 0.0f, 1.0f, 2, viewer::HistogramWeight::Volume);
    EXPECT_EQ(v.counts[0], 2.0);
    EXPECT_EQ(v.counts[1], 8.0 + 64.0);
    EXPECT_THROW(viewer::fieldHistogram(m, f, 1.0f, 1.0f, 4), Error);
    EXPECT_THROW(viewer::fieldHistogram(m, f, 0.0f, 1.0f, 0), Error);
}
