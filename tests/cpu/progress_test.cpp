// The progress bar (core/progress.h): with AMRVK_PROGRESS=1 it draws on stderr, and while work is
// left it shows the time left at the rate so far: elapsed x remaining / done, read back from the
// same line (no timing is asserted); at the end the estimate is gone.
#include "core/progress.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <regex>
#include <string>

using namespace amrvk;

TEST(ProgressBar, ShowsTheTimeLeftAtTheRateSoFar) {
    ::setenv("AMRVK_PROGRESS", "1", 1);
    testing::internal::CaptureStderr();
    {
        ProgressBar bar("frames", "spp");
        bar.update(1, 4, "frame 0");
        bar.update(4, 4, "frame 3");
        bar.finish();
    }
    const std::string text = testing::internal::GetCapturedStderr();
    ::unsetenv("AMRVK_PROGRESS");
    std::smatch m;
    const std::regex partial(R"(frames \[#+ +\] 1/4 spp  ([0-9.]+) s  eta ([0-9]+) s  frame 0)");
    ASSERT_TRUE(std::regex_search(text, m, partial)) << text;
    // 3 of 4 units left after 1: three times the elapsed time, printed to whole seconds.
    EXPECT_NEAR(std::stod(m[2].str()), 3 * std::stod(m[1].str()), 0.5 + 3 * 0.05) << text;
    EXPECT_NE(text.find("4/4 spp"), std::string::npos) << text;
    const std::string last = text.substr(text.rfind("4/4 spp"));
    EXPECT_EQ(last.find("eta"), std::string::npos) << "no estimate once done: " << last;
    EXPECT_EQ(text.back(), '\n');
}

// A long build states the memory it is about to take before it starts, and what it took after.
TEST(ProgressStage, StatesTheMemoryBeforeAndTheResultAfter) {
    ::setenv("AMRVK_PROGRESS", "1", 1);
    testing::internal::CaptureStderr();
    {
        ProgressStage stage("bricks of 1000 cells", memoryNote(uint64_t(3) << 30, true));
        stage.setResult("12 bricks, " + formatBytes(384));
    }
    { ProgressStage plain("reading x"); }
    const std::string text = testing::internal::GetCapturedStderr();
    ::unsetenv("AMRVK_PROGRESS");
    EXPECT_NE(text.find("amrvk: bricks of 1000 cells (at most 3.0 GiB of memory) ...\n"), std::string::npos) << text;
    EXPECT_TRUE(std::regex_search(text, std::regex(R"(amrvk: bricks of 1000 cells done in [0-9.]+ s \(12 bricks, 384 B\)\n)")))
        << text;
    EXPECT_NE(text.find("amrvk: reading x ...\n"), std::string::npos) << text;
    EXPECT_EQ(formatBytes(1536), "1.5 KiB");
    EXPECT_EQ(memoryNote(uint64_t(19) << 20), "19.0 MiB of memory");
}
