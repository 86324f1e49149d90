// amr::CellArray: 8-byte cells where they fit, 16-byte ones otherwise, always the same values.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <vector>

#include "amr/cell_array.h"
#include "core/error.h"
#include "core/file_io.h"

using namespace amrvk;
using amr::Cell;
using amr::CellArray;

namespace {

// Cells that fit, at every level and at the edges of each field.
std::vector<Cell> edgeCells() {
    std::vector<Cell> out;
    for (int level = 0; level <= 30; ++level) {
        const auto at = [&](int64_t k) { return int32_t(k << level); };
        const int64_t maxX = (int64_t{1} << CellArray::kXBits) - 1, maxZ = (int64_t{1} << CellArray::kZBits) - 1;
        for (int64_t kx : {int64_t{0}, int64_t{1}, maxX})
            for (int64_t kz : {int64_t{0}, maxZ}) {
                if ((kx << level) > INT32_MAX || (kz << level) > INT32_MAX) continue;
                out.push_back({{at(kx), at(kz), at(kz)}, level});
            }
    }
    return out;
}

std::filesystem::path tempFile(const char* name) { return std::filesystem::path(testing::TempDir()) / name; }

void writeRecords(const std::filesystem::path& path, const std::vector<Cell>& cells, uint64_t trailer) {
    AtomicFileWriter w(path);
    w.write(cells.data(), cells.size() * sizeof(Cell));
    w.write(&trailer, sizeof(trailer));
    w.commit();
}

std::vector<Cell> randomFittingCells(size_t n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::vector<Cell> cells(n);
    for (Cell& c : cells) {
        c.level = int32_t(rng() % 9);
        c.lower = glm::ivec3(int32_t(rng() % 4096), int32_t(rng() % 4096), int32_t(rng() % 4096)) << c.level;
    }
    return cells;
}

}  // namespace

TEST(CellArray, EveryFittingCellComesBackExactlyFromEightBytes) {
    const std::vector<Cell> cells = edgeCells();
    ASSERT_GT(cells.size(), 100u);
    CellArray a;
    for (const Cell& c : cells) {
        EXPECT_TRUE(CellArray::fits(c)) << c.lower.x << " " << c.lower.z << " level " << c.level;
        EXPECT_EQ(CellArray::decode(CellArray::pack(c)), c);
        a.push_back(c);
        CellArray one;
        one.resize(1);
        EXPECT_TRUE(one.tryStore(0, std::span<const Cell>(&c, 1)));
        EXPECT_EQ(one[0], c);
    }
    EXPECT_TRUE(a.compact());
    EXPECT_LE(a.size() * 8, a.bytes());
    EXPECT_LT(a.bytes(), a.size() * 16);
    ASSERT_EQ(a.size(), cells.size());
    for (size_t i = 0; i < cells.size(); ++i) EXPECT_EQ(a[i], cells[i]) << i;
    // The packing is not the identity on some other layout: distinct cells, distinct codes.
    EXPECT_NE(CellArray::pack({{1, 0, 0}, 0}), CellArray::pack({{0, 1, 0}, 0}));
    EXPECT_NE(CellArray::pack({{0, 0, 2}, 1}), CellArray::pack({{0, 0, 1}, 0}));
}

TEST(CellArray, ACellThatDoesNotFitTurnsTheArrayWideAndKeepsEveryValue) {
    const std::vector<Cell> misfits = {
        {{-1, 0, 0}, 0},                            // negative corner
        {{0, -8, 0}, 3},                            //
        {{3, 0, 0}, 1},                             // not a multiple of its width
        {{0, 0, 1 << 19}, 0},                       // z beyond 19 bits
        {{1 << 20, 0, 0}, 0},                       // x beyond 20 bits
        {{0, 0, 0}, 31},                            // level beyond kMaxLevel
        {{0, 0, 0}, -1},                            // negative level (validate names it)
        {{INT32_MIN, INT32_MAX, INT32_MIN}, 5},     // anything at all, as a hostile file holds it
    };
    for (const Cell& bad : misfits) {
        EXPECT_FALSE(CellArray::fits(bad)) << bad.lower.x << " " << bad.lower.y << " " << bad.lower.z << " " << bad.level;
        CellArray one;  // the reader's packing pass agrees
        one.resize(1);
        EXPECT_FALSE(one.tryStore(0, std::span<const Cell>(&bad, 1)));
        const std::vector<Cell> good = randomFittingCells(1000, 3);
        CellArray a;
        for (const Cell& c : good) a.push_back(c);
        ASSERT_TRUE(a.compact());
        a.push_back(bad);
        EXPECT_FALSE(a.compact());
        ASSERT_EQ(a.size(), good.size() + 1);
        for (size_t i = 0; i < good.size(); ++i) ASSERT_EQ(a[i], good[i]);
        EXPECT_EQ(a.back(), bad);
        EXPECT_GE(a.bytes(), a.size() * 16);

        CellArray b;  // and by set() in place
        for (const Cell& c : good) b.push_back(c);
        b.set(500, bad);
        EXPECT_FALSE(b.compact());
        EXPECT_EQ(b[500], bad);
        EXPECT_EQ(b[499], good[499]);
        EXPECT_EQ(b[501], good[501]);
    }
}

TEST(CellArray, SwapsAndStorageVisitsMoveCellsWithoutChangingThem) {
    const std::vector<Cell> cells = randomFittingCells(64, 5);
    for (const bool wide : {false, true}) {
        CellArray a;
        if (wide) a.widen();
        for (const Cell& c : cells) a.push_back(c);
        EXPECT_EQ(a.compact(), !wide);
        a.swapCells(0, 63);
        EXPECT_EQ(a[0], cells[63]);
        EXPECT_EQ(a[63], cells[0]);
        a.visitStorage([&](auto s) {  // rotate by one through the raw storage
            auto first = s[0];
            for (size_t i = 0; i + 1 < s.size(); ++i) s[i] = s[i + 1];
            s[s.size() - 1] = first;
            EXPECT_EQ(CellArray::decode(s[0]), cells[1]);
        });
        EXPECT_EQ(a[62], cells[0]);  // swapped to the end, then rotated one back
        std::vector<Cell> expected = cells;
        std::swap(expected[0], expected[63]);
        std::rotate(expected.begin(), expected.begin() + 1, expected.end());
        for (size_t i = 0; i < cells.size(); ++i) EXPECT_EQ(a[i], expected[i]) << i;
        EXPECT_TRUE(std::equal(a.begin(), a.end(), expected.begin()));
    }
}

TEST(CellArray, ReadsRecordsInParallelChunksCompactlyOrWideWhereOneDoesNotFit) {
    // More than one 8 MiB chunk of records, followed by a value the reader must land on.
    const std::vector<Cell> cells = randomFittingCells((size_t{8} << 20) / sizeof(Cell) + 12345, 7);
    const uint64_t trailer = 0x0123456789abcdefull;
    for (const bool lastFits : {true, false}) {
        std::vector<Cell> records = cells;
        if (!lastFits) records.back() = {{-4, 0, 0}, 2};
        const std::filesystem::path path = tempFile(lastFits ? "fit.cells" : "wide.cells");
        writeRecords(path, records, trailer);
        BinaryReader reader(path);
        CellArray a;
        a.push_back({{0, 0, 0}, 0});  // replaced, not appended to
        amr::readCells(reader, records.size(), a);
        EXPECT_EQ(a.compact(), lastFits);
        ASSERT_EQ(a.size(), records.size());
        EXPECT_TRUE(std::equal(a.begin(), a.end(), records.begin()));
        EXPECT_EQ(reader.offset(), records.size() * sizeof(Cell));
        uint64_t after = 0;
        reader.read(&after, sizeof(after));
        EXPECT_EQ(after, trailer);

        // Written back a chunk at a time: the same bytes as the file.
        const std::filesystem::path copy = tempFile("copy.cells");
        AtomicFileWriter w(copy);
        amr::writeCells(w, a);
        w.commit();
        EXPECT_EQ(std::filesystem::file_size(copy), records.size() * sizeof(Cell));
        BinaryReader back(copy);
        std::vector<Cell> reread(records.size());
        back.read(reread.data(), reread.size() * sizeof(Cell));
        EXPECT_TRUE(reread == records);
    }
}

TEST(CellArray, AShortFileIsAnErrorNamingItBeforeAnythingIsHeld) {
    const std::filesystem::path path = tempFile("short.cells");
    writeRecords(path, randomFittingCells(10, 9), 0);  // 168 bytes: 10 cells and 8 bytes
    BinaryReader reader(path);
    CellArray a;
    try {
        amr::readCells(reader, 11, a);
        FAIL() << "11 cells read from a file of 10";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("short.cells: truncated"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(a.empty());
    try {
        amr::readCells(reader, UINT64_MAX / 4, a);  // a count whose bytes overflow
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
    }
}
