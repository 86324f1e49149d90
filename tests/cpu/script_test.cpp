// Viewer scripts: actions with frames, quoted arguments, comments; one-line errors naming the
// file and line for unknown actions, wrong argument counts, bad numbers and frames going back.
#include <gtest/gtest.h>

#include "core/error.h"
#include "session/script.h"
#include "test_data.h"

using namespace amrvk;

TEST(Script, ParsesActionsFramesAndQuotes) {
    const auto actions = session::parseScript(R"(# warm up first
0 mode ae
10 orbit 120 -40   # a drag
10 tf-range 0 3.5
20 edit-shader lib/phase.glsl "return kInvFourPi" "return 2.0 * kInvFourPi \"x\\"
30 screenshot "out dir/shot.png"
31 quit
)", "s.txt");
    ASSERT_EQ(actions.size(), 6u);
    EXPECT_EQ(actions[0].frame, 0u);
    EXPECT_EQ(actions[1].name, "orbit");
    EXPECT_EQ(actions[1].number(0), 120.0);
    EXPECT_EQ(actions[1].number(1), -40.0);
    EXPECT_EQ(actions[1].where, "s.txt:3");
    EXPECT_EQ(actions[3].args[1], "return kInvFourPi");
    EXPECT_EQ(actions[3].args[2], "return 2.0 * kInvFourPi \"x\\");
    EXPECT_EQ(actions[4].args[0], "out dir/shot.png");
    EXPECT_EQ(actions[5].name, "quit");
}

TEST(Script, ErrorsNameTheFileAndLine) {
    const struct {
        const char* text;
        std::vector<std::string> fragments;
    } cases[] = {
        {"0 fly 1 2", {"s.txt:1", "unknown action 'fly'", "orbit"}},
        {"\n0 orbit 1", {"s.txt:2", "orbit takes 2 argument(s), not 1"}},
        {"0 zoom lots", {"s.txt:1", "zoom", "not a number"}},
        {"x zoom 1", {"s.txt:1", "frame 'x'"}},
        {"-1 zoom 1", {"s.txt:1", "frame '-1'"}},
        {"5 zoom 1\n4 zoom 1", {"s.txt:2", "frame 4 comes before frame 5"}},
        {"0 screenshot \"a.png", {"s.txt:1", "unterminated quote"}},
        {"3", {"s.txt:1", "expected FRAME ACTION"}},
        {"0 density nan", {"s.txt:1", "not a number"}},
    };
    for (const auto& c : cases) {
        const std::string e = test::errorOf([&] { session::parseScript(c.text, "s.txt"); });
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
        for (const auto& f : c.fragments) EXPECT_NE(e.find(f), std::string::npos) << "'" << f << "' not in: " << e;
    }
}
