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
