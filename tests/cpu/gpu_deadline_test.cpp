// The adaptive --gpu-timeout (core/gpu_deadline.h): only the floor before a pace is measured, then
// a limit that grows with the submission's paths at the slowest pace seen, forgotten on reset().
#include "core/gpu_deadline.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <vector>

#include "core/error.h"

using amrvk::GpuDeadline;

TEST(GpuDeadline, OnlyTheFloorBeforeAPaceIsMeasured) {
    GpuDeadline d(10);
    EXPECT_FALSE(d.measured());
    EXPECT_EQ(d.limit(4096), 10);
    EXPECT_EQ(d.limit(uint64_t(1) << 40), 10);  // the probe is small; nothing bigger comes first
}

TEST(GpuDeadline, TheLimitGrowsWithTheWorkAtTheSlowestPace) {
    GpuDeadline d(10);
    d.record(0.5, 4096);  // a probe: 0.5 s for 4096 paths
    ASSERT_TRUE(d.measured());
    const double pace = 0.5 / 4096;
    EXPECT_DOUBLE_EQ(d.limit(4096), 16);  // 32 x 0.5 s
    EXPECT_EQ(d.limit(100), 10);          // 0.4 s of work: the floor
    EXPECT_DOUBLE_EQ(d.limit(8192), GpuDeadline::kMargin * pace * 8192);
    // A 64-spp batch of a 4K image: hours at this pace, and the limit follows.
    const uint64_t batch = uint64_t(64) * 3840 * 2160;
    EXPECT_DOUBLE_EQ(d.limit(batch), GpuDeadline::kMargin * pace * double(batch));
    // A faster submission keeps the slowest pace; a slower one raises it.
    d.record(0.1, 4096);
    EXPECT_DOUBLE_EQ(d.limit(batch), GpuDeadline::kMargin * pace * double(batch));
    d.record(4.0, 4096);
    EXPECT_DOUBLE_EQ(d.limit(batch), GpuDeadline::kMargin * (4.0 / 4096) * double(batch));
}

TEST(GpuDeadline, ResetForgetsThePaceAndAnInstantSubmissionStillCounts) {
    GpuDeadline d(10);
    d.record(100, 1000);
    EXPECT_GT(d.limit(1000), 10);
    d.reset();
    EXPECT_FALSE(d.measured());
    EXPECT_EQ(d.limit(1000), 10);
    d.record(0, 1000);  // the clock saw nothing pass: measured, and only the floor holds
    EXPECT_TRUE(d.measured());
    EXPECT_EQ(d.limit(1000), 10);
    d.record(1, 0);  // no paths: no pace
    EXPECT_EQ(d.limit(1000), 10);
}

TEST(GpuDeadline, TheTestFloorComesFromTheEnvironmentAndIsChecked) {
    ::setenv("AMRVK_TEST_GPU_TIMEOUT_FLOOR", "0.25", 1);
    EXPECT_EQ(GpuDeadline().floorSeconds(), 0.25);
    ::setenv("AMRVK_TEST_GPU_TIMEOUT_FLOOR", "-1", 1);
    EXPECT_THROW(GpuDeadline(), amrvk::Error);
    ::setenv("AMRVK_TEST_GPU_TIMEOUT_FLOOR", "3s", 1);
    EXPECT_THROW(GpuDeadline(), amrvk::Error);
    ::unsetenv("AMRVK_TEST_GPU_TIMEOUT_FLOOR");
    EXPECT_EQ(GpuDeadline().floorSeconds(), GpuDeadline::kFloorSeconds);
}

TEST(GpuDeadline, UnmeasuredWorkIsSplitIntoAProbeAndGrowingPartsThatCoverIt) {
    GpuDeadline d(10);
    using Parts = std::vector<GpuDeadline::Part>;
    auto covers = [](const Parts& parts, uint64_t work) {
        uint64_t next = 0;
        for (const GpuDeadline::Part& p : parts) {
            if (p.first != next || p.count == 0) return false;
            next += p.count;
        }
        return next == work;
    };
    // 64 + 256 + 1024 + the rest (of 4096): each part 4x the last, the last cut to what is left.
    const Parts parts = d.submissions(2000, 64);
    ASSERT_EQ(parts.size(), 4u);
    EXPECT_EQ(parts[0].count, 64u);
    EXPECT_EQ(parts[1].count, 256u);
    EXPECT_EQ(parts[2].count, 1024u);
    EXPECT_EQ(parts[3].count, 2000u - 64 - 256 - 1024);
    EXPECT_TRUE(covers(parts, 2000));
    EXPECT_EQ(d.submissions(10, 64).size(), 1u);  // smaller than the probe: one part
    EXPECT_TRUE(covers(d.submissions(10, 64), 10));
    EXPECT_TRUE(d.submissions(0, 64).empty());
    for (uint64_t work : {uint64_t(1), uint64_t(64), uint64_t(65), uint64_t(1) << 32}) {
        EXPECT_TRUE(covers(d.submissions(work, 64), work)) << work;
        EXPECT_LE(d.submissions(work, 64).size(), 18u) << work;  // log4 of the work: few submissions
    }
    // Measured: all at once, however large.
    d.record(1, 64);
    EXPECT_EQ(d.submissions(uint64_t(1) << 32, 64).size(), 1u);
    EXPECT_TRUE(covers(d.submissions(uint64_t(1) << 32, 64), uint64_t(1) << 32));
}
