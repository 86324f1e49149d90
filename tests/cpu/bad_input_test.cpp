// Bad input: every case gives an amrvk::Error whose one-line message names the file and the fault.
#include <gtest/gtest.h>

#include <fstream>

#include "accel/brick_build.h"
#include "accel/bricks.h"
#include "amr/readers.h"
#include "core/error.h"
#include "model_fixtures.h"
#include "test_data.h"

using namespace amrvk;

namespace {

void writeBytes(const std::filesystem::path& p, const void* data, size_t bytes) {
    std::ofstream out(p, std::ios::binary);
    out.write(static_cast<const char*>(data), std::streamsize(bytes));
}

void writeCells(const std::filesystem::path& base, const std::vector<amr::Cell>& cells,
                const std::vector<float>& values) {
    writeBytes(std::filesystem::path(base.string() + ".cells"), cells.data(), cells.size() * sizeof(amr::Cell));
    writeBytes(std::filesystem::path(base.string() + ".scalars"), values.data(), values.size() * sizeof(float));
}

// Expects readModel to throw with every fragment in the message, and the message on one line.
void expectError(const std::filesystem::path& input, std::initializer_list<const char*> fragments,
                 amr::ReadOptions options = {}) {
    try {
        amr::readModel(input, options);
        ADD_FAILURE() << "no error for " << input;
    } catch (const Error& e) {
        std::string msg = e.what();
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        for (const char* f : fragments) EXPECT_NE(msg.find(f), std::string::npos) << "'" << f << "' not in: " << msg;
    }
}

const std::vector<amr::Cell> kGoodCells = {{{0, 0, 0}, 1}, {{2, 0, 0}, 0}, {{3, 0, 0}, 0},
                                           {{2, 1, 0}, 0}, {{3, 1, 0}, 0}};

}  // namespace

TEST(BadInput, MissingFile) {
    auto dir = test::scratchDir();
    expectError(dir / "nothing.cells", {"nothing.cells", "no such file"});
}

TEST(BadInput, EmptyFile) {
    auto dir = test::scratchDir();
    writeCells(dir / "e", {}, {});
    expectError(dir / "e.cells", {"e.cells", "empty"});
}

TEST(BadInput, TruncatedCellsFile) {
    auto dir = test::scratchDir();
    writeCells(dir / "t", kGoodCells, std::vector<float>(5, 1.0f));
    std::filesystem::resize_file(dir / "t.cells", 5 * 16 - 3);
    expectError(dir / "t.cells", {"t.cells", "not a multiple of the 16-byte"});
}

TEST(BadInput, TruncatedScalarsFile) {
    auto dir = test::scratchDir();
    writeCells(dir / "t", kGoodCells, std::vector<float>(5, 1.0f));
    std::filesystem::resize_file(dir / "t.scalars", 5 * 4 - 1);
    expectError(dir / "t.cells", {"t.scalars", "not a multiple of 4"});
}

TEST(BadInput, CellsScalarsCountMismatch) {
    auto dir = test::scratchDir();
    writeCells(dir / "m", kGoodCells, std::vector<float>(4, 1.0f));
    expectError(dir / "m.cells", {"m.scalars", "4 values", "5 cells"});
}

TEST(BadInput, MisalignedCell) {
    auto dir = test::scratchDir();
    auto cells = kGoodCells;
    cells[0].lower = {1, 0, 0};
    writeCells(dir / "a", cells, std::vector<float>(5, 1.0f));
    expectError(dir / "a.cells", {"a.cells", "cell 0", "not aligned"});
}

TEST(BadInput, LevelOutOfRange) {
    auto dir = test::scratchDir();
    auto cells = kGoodCells;
    cells[1].level = 31;
    writeCells(dir / "l", cells, std::vector<float>(5, 1.0f));
    expectError(dir / "l.cells", {"l.cells", "cell 1", "level outside"});
}

TEST(BadInput, OverlappingCells) {
    auto dir = test::scratchDir();
    auto cells = kGoodCells;
    cells.push_back({{1, 1, 1}, 0});  // inside the level-1 cell at the origin
    writeCells(dir / "o", cells, std::vector<float>(6, 1.0f));
    // Found by the brick build (every render, view, bench and info builds bricks), which names the
    // cells by position; amr::validate (convert) names them by index.
    amr::Model m = amr::readModel(dir / "o.cells", {});
    test::expectError([&] { amr::validate(m); }, {"o.cells", "overlapping", "cell 5", "cell 0"});
    test::expectError([&] { accel::buildBricks(m); },
                      {"o.cells", "overlapping", "(lower 1,1,1 level 0) lies inside (lower 0,0,0 level 1)"});
}

TEST(BadInput, NanIsRejectedByDefaultAndDroppedOnRequest) {
    auto dir = test::scratchDir();
    std::vector<float> values(5, 1.0f);
    values[2] = std::numeric_limits<float>::quiet_NaN();
    writeCells(dir / "n", kGoodCells, values);
    expectError(dir / "n.cells", {"n.cells", "non-finite", "cell 2", "--nan drop"});
    amr::ReadOptions drop;
    drop.nanPolicy = amr::NanPolicy::Drop;
    amr::Model m = amr::readModel(dir / "n.cells", drop);
    EXPECT_EQ(m.cells.size(), 4u);
}

TEST(BadInput, UnknownField) {
    auto dir = test::scratchDir();
    writeCells(dir / "f", kGoodCells, std::vector<float>(5, 1.0f));
    amr::ReadOptions o;
    o.fields = {"density"};
    expectError(dir / "f.cells", {"f.cells", "unknown field 'density'", "available: scalars"}, o);
}

TEST(BadInput, UnrecognisedFormat) {
    auto dir = test::scratchDir();
    writeBytes(dir / "x.dat", "hello", 5);
    expectError(dir / "x.dat", {"x.dat", "unrecognised AMR format"});
}

TEST(BadInput, ExaBrickRoundTrip) {
    amr::Model m = test::makeRefinedModel(4, {3, 2, 2}, 2, 0.5);
    test::addRandomField(m, "density", 4);
    test::addRandomField(m, "temp", 5);
    test::expectExaBrickRoundTrip(m);
}
