// Viewer scripts: actions with frames, quoted arguments, comments; one-line errors naming the
// file and line, before frame 0, for unknown actions, wrong argument counts, bad numbers and
// values, frames going back, combinations that cannot run and shader edits outside --shader-dir.
#include "viewer/logic/script.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "test_data.h"

using namespace amrvk;

TEST(Script, ParsesActionsFramesAndQuotes) {
    const auto actions = viewer::parseScript(R"(# warm up first
0 mode ae
10 orbit 120 -40   # a drag
10 tf-range 0 3.5
12 scale log
12 log-floor 1e-3
20 edit-shader lib/phase.glsl "return kInvFourPi" "return 2.0 * kInvFourPi \"x\\"
30 screenshot "out dir/shot.png"
31 quit
)", "s.txt");
    ASSERT_EQ(actions.size(), 8u);
    EXPECT_EQ(actions[0].frame, 0u);
    EXPECT_EQ(actions[1].name, "orbit");
    EXPECT_EQ(actions[1].number(0), 120.0);
    EXPECT_EQ(actions[1].number(1), -40.0);
    EXPECT_EQ(actions[1].where, "s.txt:3");
    EXPECT_EQ(actions[3].name, "scale");
    EXPECT_EQ(actions[3].args[0], "log");
    EXPECT_EQ(actions[4].number(0), 1e-3);
    EXPECT_EQ(actions[5].args[1], "return kInvFourPi");
    EXPECT_EQ(actions[5].args[2], "return 2.0 * kInvFourPi \"x\\");
    EXPECT_EQ(actions[6].args[0], "out dir/shot.png");
    EXPECT_EQ(actions[7].name, "quit");
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
        {"0 density -1", {"s.txt:1", "density -1 must be >= 0"}},
        {"0 mode pt", {"s.txt:1", "mode", "--mode 'pt'", "ae|ss|ms|dvr"}},
        {"0 traversal octree", {"s.txt:1", "--traversal 'octree'"}},
        {"0 sampler cube", {"s.txt:1", "--sampler 'cube'"}},
        {"0 backend cuda", {"s.txt:1", "--backend 'cuda'"}},
        {"0 grid 0", {"s.txt:1", "grid", "[1, 4096]"}},
        {"0 grid 8x8", {"s.txt:1", "expected auto, N or NxMxK"}},
        {"0 tf-preset rainbow", {"s.txt:1", "tf-preset", "rainbow"}},
        {"0 tf-range 3 1", {"s.txt:1", "LO 3 must be below HI 1"}},
        {"0 scale ln", {"s.txt:1", "scale", "'ln' is not auto, linear or log"}},
        {"0 scale", {"s.txt:1", "scale takes 1 argument(s), not 0"}},
        {"0 log-floor -1", {"s.txt:1", "log floor -1 must be >= 0"}},
        {"0 log-floor tiny", {"s.txt:1", "log-floor", "not a number"}},
        {"0 screenshot shot.jpg", {"s.txt:1", "unknown image type"}},
        {"0 capture-window shot.exr", {"s.txt:1", "unknown image type (use .png)"}},
        {"0 edit-shader /etc/passwd a b", {"s.txt:1", "must be a path relative to --shader-dir"}},
        {"0 legend yes", {"s.txt:1", "legend", "'yes': expected on or off"}},
        {"0 tf-colors gamma", {"s.txt:1", "tf-colors 'gamma': expected linear|srgb"}},
    };
    for (const auto& c : cases) {
        const std::string e = test::errorOf([&] { viewer::parseScript(c.text, "s.txt"); });
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
        for (const auto& f : c.fragments) EXPECT_NE(e.find(f), std::string::npos) << "'" << f << "' not in: " << e;
    }
}

TEST(Script, TheContextIsCheckedBeforeFrameZero) {
    namespace fs = std::filesystem;
    const fs::path dir = test::scratchDir() / "script-context";
    fs::remove_all(dir);
    fs::create_directories(dir / "shaders/passes");
    fs::create_directories(dir / "shaders/lib");
    test::writeAll(dir / "shaders/passes/path_trace.comp", "void main() {}\n");
    test::writeAll(dir / "shaders/lib/tf.glsl", "// tf\n");
    test::writeAll(dir / "victim.txt", "precious\n");
    fs::create_symlink(dir / "victim.txt", dir / "shaders/lib/link.glsl");
    viewer::ScriptContext ctx{dir / "shaders/passes", {}};

    // A combination that cannot run, reached by two lines: the second is named.
    std::string e = test::errorOf([&] {
        viewer::checkScript(viewer::parseScript("0 traversal abr\n5 sampler dense\n", "s.txt"), ctx);
    });
    EXPECT_NE(e.find("s.txt:2"), std::string::npos) << e;
    EXPECT_NE(e.find("grid-dda or grid-bvh"), std::string::npos) << e;
    // ... and the same lines in the other order are fine (dense under grid-dda, then back to grid).
    EXPECT_NO_THROW(viewer::checkScript(
        viewer::parseScript("0 sampler dense\n1 sampler grid\n2 traversal abr\n", "s.txt"), ctx));

    // Shader edits: inside the sources (also through ..), never outside, never through a link out.
    EXPECT_NO_THROW(viewer::checkScript(viewer::parseScript("0 edit-shader path_trace.comp a b\n"
                                                              "1 edit-shader ../lib/tf.glsl a b\n", "s.txt"), ctx));
    for (const char* file : {"../../victim.txt", "../lib/link.glsl", "../lib/missing.glsl"}) {
        e = test::errorOf([&] {
            viewer::checkScript(viewer::parseScript(std::string("3 edit-shader ") + file + " a b\n", "s.txt"), ctx);
        });
        EXPECT_NE(e.find("s.txt:1"), std::string::npos) << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    }
    EXPECT_NE(test::errorOf([&] {
                  viewer::checkScript(viewer::parseScript("0 edit-shader ../../victim.txt a b\n", "s.txt"), ctx);
              }).find("leads outside the shader sources"),
              std::string::npos);
    e = test::errorOf([&] {
        viewer::checkScript(viewer::parseScript("0 edit-shader path_trace.comp a b\n", "s.txt"), {{}, {}});
    });
    EXPECT_NE(e.find("needs --shader-dir"), std::string::npos) << e;
    EXPECT_EQ(test::readAll(dir / "victim.txt"), "precious\n");
}
