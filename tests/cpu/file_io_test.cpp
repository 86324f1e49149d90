// core/file_io: BinaryReader::readArray (read) of arrays large enough to be read in chunks on every core
// (kParallelReadBytes), into a plain vector and into a NoInitAllocator one: every element as
// written, the offset after it, a read after it that continues there (the FILE's position is
// reset past the chunks), and a request past the end refused before anything is read.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "core/file_io.h"
#include "test_data.h"

using namespace amrvk;

TEST(FileIo, LargeArraysAreReadInChunksAndTheOffsetFollows) {
    const std::filesystem::path path = test::scratchDir() / "large.bin";
    // 40 MiB + 12 bytes: five 8 MiB chunks and a short one, then a tail read as a small array.
    const uint64_t count = (BinaryReader::kParallelReadBytes + (uint64_t{8} << 20)) / 4 + 3;
    std::vector<uint32_t> written(count + 5);
    for (size_t i = 0; i < written.size(); ++i) written[i] = uint32_t(i * 2654435761u);
    {
        std::FILE* f = std::fopen(path.c_str(), "wb");
        ASSERT_TRUE(f);
        ASSERT_EQ(std::fwrite(written.data(), 4, written.size(), f), written.size());
        std::fclose(f);
    }
    BinaryReader in(path);
    uint32_t head = 0;
    in.read(&head, 4);  // a buffered read first: the chunks start at offset 4, not 0
    EXPECT_EQ(head, written[0]);
    std::vector<uint32_t, NoInitAllocator<uint32_t>> big;
    in.readArray(big, count);
    EXPECT_EQ(in.offset(), 4 + count * 4);
    ASSERT_EQ(big.size(), count);
    for (size_t i = 0; i < count; ++i) ASSERT_EQ(big[i], written[i + 1]) << i;
    std::vector<uint32_t> tail;
    in.readArray(tail, 4);
    EXPECT_EQ(tail, std::vector<uint32_t>(written.end() - 4, written.end()));
    EXPECT_TRUE(in.atEnd());

    BinaryReader again(path);
    std::vector<uint32_t> whole;
    test::expectError([&] { again.readArray(whole, written.size() + 1); }, {"large.bin: truncated at byte"});
    again.readArray(whole, written.size());
    EXPECT_EQ(whole, written);
}

// OutputTransaction (issue 52, point 18): inside one, a committed AtomicFileWriter stays a
// temporary until the transaction commits, then every output appears at once; a transaction left
// without commit (an exception on the way) leaves neither the outputs nor a temporary, and a file
// that was there before keeps its old contents.
TEST(FileIo, AnOutputTransactionWritesEveryOutputOrNone) {
    namespace fs = std::filesystem;
    const fs::path dir = test::scratchDir() / "transaction";
    fs::remove_all(dir);
    fs::create_directories(dir);
    auto contents = [](const fs::path& p) {
        std::FILE* f = std::fopen(p.c_str(), "rb");
        std::string s(64, '\0');
        s.resize(f ? std::fread(s.data(), 1, s.size(), f) : 0);
        if (f) std::fclose(f);
        return s;
    };
    auto entries = [&] {
        size_t n = 0;
        for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
        return n;
    };
    writeFileAtomic(dir / "old.txt", "before");
    {
        OutputTransaction t;
        writeFileAtomic(dir / "a.txt", "a");
        writeFileAtomic(dir / "old.txt", "after");
        EXPECT_FALSE(fs::exists(dir / "a.txt")) << "not in place before the transaction commits";
        EXPECT_EQ(contents(dir / "old.txt"), "before");
        EXPECT_EQ(entries(), 3u) << "old.txt and two temporaries";
        // dropped without commit: what an exception between the outputs does
    }
    EXPECT_FALSE(fs::exists(dir / "a.txt"));
    EXPECT_EQ(contents(dir / "old.txt"), "before");
    EXPECT_EQ(entries(), 1u) << "no temporary left";
    {
        OutputTransaction t;
        writeFileAtomic(dir / "a.txt", "a");
        writeFileAtomic(dir / "old.txt", "after");
        t.commit();
    }
    EXPECT_EQ(contents(dir / "a.txt"), "a");
    EXPECT_EQ(contents(dir / "old.txt"), "after");
    EXPECT_EQ(entries(), 2u);
    // Outside a transaction a writer commits on its own, as before.
    writeFileAtomic(dir / "b.txt", "b");
    EXPECT_EQ(contents(dir / "b.txt"), "b");
}
