// The shader-source watcher reports edits (size or time), new and deleted sources, and ignores
// other files.
#include "viewer/logic/file_watcher.h"

#include <gtest/gtest.h>

#include <fstream>

#include "test_data.h"

using namespace amrvk;
namespace fs = std::filesystem;

TEST(FileWatcher, ReportsEditedNewAndDeletedSources) {
    const fs::path root = test::scratchDir() / "watched";
    fs::remove_all(root);
    fs::create_directories(root / "lib");
    test::writeAll(root / "a.comp", "void main() {}\n");
    test::writeAll(root / "lib" / "b.glsl", "// b\n");
    test::writeAll(root / "notes.txt", "x");
    viewer::FileWatcher w({root});
    EXPECT_TRUE(w.poll().empty());
    test::writeAll(root / "lib" / "b.glsl", "// b, edited\n");  // size changes
    test::writeAll(root / "notes.txt", "xy");                     // not a shader source
    auto changed = w.poll();
    ASSERT_EQ(changed.size(), 1u);
    EXPECT_EQ(changed[0].filename(), "b.glsl");
    EXPECT_TRUE(w.poll().empty()) << "reported once";
    // Same size, later time.
    fs::last_write_time(root / "a.comp", fs::last_write_time(root / "a.comp") + std::chrono::seconds(5));
    changed = w.poll();
    ASSERT_EQ(changed.size(), 1u);
    EXPECT_EQ(changed[0].filename(), "a.comp");
    test::writeAll(root / "lib" / "c.h", "#define X\n");
    fs::remove(root / "a.comp");
    changed = w.poll();
    ASSERT_EQ(changed.size(), 2u);
    EXPECT_EQ(changed[0].filename(), "c.h");
    EXPECT_EQ(changed[1].filename(), "a.comp");
}
