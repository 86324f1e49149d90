// AMReX plotfile reader: the real PeleLM plotfile (oracles in shared/data/amr/FORMATS.md 6) and
// small synthetic plotfiles written here for what the real one lacks (2-D, ghost cells, float32,
// big-endian, raw VisMF versions 2-4, refinement ratio 3).
#include <optional>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <fstream>
#include <functional>
#include <sstream>

#include "amr/model.h"
#include "amr/readers.h"
#include "core/error.h"
#include "model_fixtures.h"
#include "test_data.h"
#include "amrex_synthetic.h"

namespace fs = std::filesystem;
using namespace amrvk;
using namespace amrvk::amr;

using namespace amrvk::test;
using namespace amrvk::test::amrex;

namespace {

const char* kPlotfile = "amrex_pelelm_3d/example_plt_3d";

// Writes a fresh (writable) copy of the first `keep` bytes of `src` (all when keep is npos).
void copyPrefix(const fs::path& src, const fs::path& dst, size_t keep = std::string::npos) {
    const std::string bytes = readAll(src);
    fs::create_directories(dst.parent_path());
    std::ofstream out(dst, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(std::min(keep, bytes.size())));
}

void copyPlotfile(const fs::path& src, const fs::path& dst) {
    for (const auto& entry : fs::recursive_directory_iterator(src))
        if (entry.is_regular_file())
            copyPrefix(entry.path(), dst / fs::relative(entry.path(), src));
}

std::optional<Cell> findCell(const Model& m, glm::ivec3 lower, int level, size_t* index) {
    for (size_t i = 0; i < m.cells.size(); ++i)
        if (m.cells[i].lower == lower && m.cells[i].level == level) {
            *index = i;
            return m.cells[i];
        }
    return std::nullopt;
}

// ---- synthetic plotfiles ----

// Writes the files of a synthetic plotfile under dir.
void writeSynthetic(const fs::path& dir, const Synthetic& s) {
    for (const auto& [name, bytes] : plotfileFiles(s)) {
        fs::create_directories((dir / name).parent_path());
        writeAll(dir / name, bytes);
    }
}

// Checks every leaf of a synthetic plotfile (ratio 2) against synthValue.
void checkSynthetic(const Model& m, const Synthetic& s) {
    ASSERT_EQ(m.fields.size(), 2u);
    EXPECT_EQ(m.fields[0].name, "a");
    EXPECT_EQ(m.fields[1].name, "b(x)");
    const size_t fine = s.dim == 3 ? 64 : 16;
    const size_t coarse = s.dim == 3 ? 64 - 8 : 16 - 4;
    ModelSummary sum = summarize(m);
    ASSERT_EQ(sum.cellsPerLevel.size(), 2u);
    EXPECT_EQ(sum.cellsPerLevel[0], fine);
    EXPECT_EQ(sum.cellsPerLevel[1], coarse);
    EXPECT_EQ(sum.bounds.lower, glm::i64vec3(0));
    EXPECT_EQ(sum.bounds.upper, s.dim == 3 ? glm::i64vec3(8) : glm::i64vec3(8, 8, 2));
    for (size_t i = 0; i < m.cells.size(); ++i) {
        const Cell& c = m.cells[i];
        const int l = 1 - c.level;  // AMReX level: 0 coarse, 1 fine
        const glm::ivec3 idx = c.lower / (c.level ? 2 : 1);
        if (s.dim == 2) {
            EXPECT_EQ(c.lower.z, 0);
        }
        for (int f = 0; f < 2; ++f)
            ASSERT_EQ(m.fields[static_cast<size_t>(f)].values[i],
                      synthValue(l, f, idx.x, idx.y, idx.z))
                << "cell " << i << " field " << f;
    }
    EXPECT_DOUBLE_EQ(m.voxelToWorld.scale.x, 0.125);
    EXPECT_DOUBLE_EQ(m.voxelToWorld.scale.z, 0.125);
    EXPECT_NO_THROW(validate(m));
}

}  // namespace

TEST(AmrexReader, RealPlotfileMatchesOracles) {
    AMRVK_REQUIRE_DATA(kPlotfile);
    ReadOptions o;
    o.fields = {"temp"};
    const Model m = readModel(test::dataDir() / kPlotfile, o);
    EXPECT_EQ(m.format, "amrex");
    ASSERT_EQ(m.availableFields.size(), 38u);
    EXPECT_EQ(m.availableFields[5], "temp");
    EXPECT_EQ(m.availableFields[20], "Y(CH2(S))");
    ASSERT_EQ(m.fields.size(), 1u);

    // Levels 8^3, 16^3, 32^3 each cover the domain: only the 32^3 finest cells are leaves.
    const ModelSummary s = summarize(m);
    EXPECT_EQ(m.cellCount(), 32768u);
    EXPECT_EQ(s.cellsPerLevel, (std::vector<uint64_t>{32768}));
    EXPECT_EQ(s.bounds.lower, glm::i64vec3(0));
    EXPECT_EQ(s.bounds.upper, glm::i64vec3(32));
    EXPECT_DOUBLE_EQ(s.leafVolume, s.bounds.volume());
    EXPECT_NO_THROW(validate(m));

    // Domain [0, 0.016]^3; finest dx = 0.002 / 2 / 2.
    const glm::dvec3 lo = m.voxelToWorld.toWorld(glm::dvec3(s.bounds.lower));
    const glm::dvec3 hi = m.voxelToWorld.toWorld(glm::dvec3(s.bounds.upper));
    for (int a = 0; a < 3; ++a) {
        EXPECT_DOUBLE_EQ(lo[a], 0.0);
        EXPECT_NEAR(hi[a], 0.016, 1e-15);
        EXPECT_NEAR(m.voxelToWorld.scale[a], 0.0005, 1e-18);
    }

    // temp on the finest level (all leaves): 297.99999999999994 ... 1579.8536855390937.
    const FieldStats st = computeFieldStats(m, m.field("temp"));
    EXPECT_FLOAT_EQ(st.minValue, static_cast<float>(297.99999999999994));
    EXPECT_FLOAT_EQ(st.maxValue, static_cast<float>(1579.8536855390937));

    // One value checked against the FAB bytes: finest cell (5, 17, 30).
    size_t i = 0;
    ASSERT_TRUE(findCell(m, {5, 17, 30}, 0, &i));
    EXPECT_FLOAT_EQ(m.fields[0].values[i], static_cast<float>(1579.7857281345207));

    bool hasTime = false;
    for (const auto& [k, v] : m.attributes)
        if (k == "time") {
            hasTime = true;
            EXPECT_EQ(v, "1.3924182125972017e-08");
        }
    EXPECT_TRUE(hasTime);
}

TEST(AmrexReader, HeaderPathAndAllFields) {
    AMRVK_REQUIRE_DATA(kPlotfile);
    const Model m = readModel(test::dataDir() / kPlotfile / "Header", ReadOptions{});
    ASSERT_EQ(m.fields.size(), 38u);
    EXPECT_EQ(m.cellCount(), 32768u);
    const FieldStats density = computeFieldStats(m, m.field("density"));
    EXPECT_GT(density.minValue, 0.0f);
    size_t i = 0;
    ASSERT_TRUE(findCell(m, {5, 17, 30}, 0, &i));
    EXPECT_FLOAT_EQ(m.field("density").values[i], static_cast<float>(0.21436366927536127));
}

// Its first field is x_velocity; the picture's default is its density (issue 52, point 10).
TEST(AmrexReader, TheDefaultFieldIsTheDensity) {
    AMRVK_REQUIRE_DATA(kPlotfile);
    const Model m = readModel(test::dataDir() / kPlotfile, ReadOptions{});
    EXPECT_EQ(m.availableFields.front(), "x_velocity");
    EXPECT_EQ(m.defaultField().name, "density");
    Model chunkField;
    visitCells(test::dataDir() / kPlotfile, ReadOptions{}, [&](const Model& chunk) { chunkField = chunk; });
    ASSERT_EQ(chunkField.fields.size(), 1u);
    EXPECT_EQ(chunkField.fields[0].name, "density");
}

TEST(AmrexReader, UnknownFieldListsAvailable) {
    AMRVK_REQUIRE_DATA(kPlotfile);
    ReadOptions o;
    o.fields = {"temperature"};
    const std::string msg = errorOf([&] { readAmrex(test::dataDir() / kPlotfile, o); });
    expectContains(msg, "unknown field 'temperature'");
    expectContains(msg, "temp, RhoRT");
    EXPECT_EQ(msg.find('\n'), std::string::npos);
}

TEST(AmrexReader, MissingHeaderAndCellHeaderAreReported) {
    AMRVK_REQUIRE_DATA(kPlotfile);
    const fs::path dir = test::scratchDir() / "plt";
    fs::create_directories(dir);
    std::string msg = errorOf([&] { readAmrex(dir, {}); });
    expectContains(msg, "Header");
    expectContains(msg, "no such file");

    copyPrefix(test::dataDir() / kPlotfile / "Header", dir / "Header");
    msg = errorOf([&] { readAmrex(dir, {}); });
    expectContains(msg, (dir / "Level_0" / "Cell_H").string());
    expectContains(msg, "no such file");
}

TEST(AmrexReader, TruncatedFabDataIsReported) {
    AMRVK_REQUIRE_DATA(kPlotfile);
    const fs::path dir = test::scratchDir() / "plt";
    copyPlotfile(test::dataDir() / kPlotfile, dir);
    const fs::path victim = dir / "Level_2" / "Cell_D_00003";
    copyPrefix(test::dataDir() / kPlotfile / "Level_2" / "Cell_D_00003", victim,
               fs::file_size(victim) - 1000);
    const std::string msg = errorOf([&] { readModel(dir, ReadOptions{}); });
    expectContains(msg, victim.string());
    expectContains(msg, "truncated");
    EXPECT_EQ(msg.find('\n'), std::string::npos);
}

TEST(AmrexReader, RoundTripThroughExaBrick) {
    AMRVK_REQUIRE_DATA(kPlotfile);
    ReadOptions o;
    o.fields = {"temp", "Y(H2)"};
    const Model m = readModel(test::dataDir() / kPlotfile, o);
    test::expectExaBrickRoundTrip(m);
}

TEST(AmrexReader, SyntheticTwoDimensionalWithGhostCells) {
    Synthetic s;
    s.dim = 2;
    s.ngrow = 1;
    const fs::path dir = test::scratchDir() / "plt2d";
    writeSynthetic(dir, s);
    checkSynthetic(readModel(dir, ReadOptions{}), s);
}

TEST(AmrexReader, SyntheticFloatBigEndianIntVectGhost) {
    Synthetic s;
    s.realBytes = 4;
    s.bigEndian = true;
    s.ngrow = 2;
    s.ngrowAsIntVect = true;
    const fs::path dir = test::scratchDir() / "plt";
    writeSynthetic(dir, s);
    checkSynthetic(readModel(dir, ReadOptions{}), s);
}

TEST(AmrexReader, SyntheticRawVisMFVersions) {
    for (int version = 2; version <= 4; ++version) {
        for (bool big : {false, true}) {
            SCOPED_TRACE("VisMF version " + std::to_string(version) + (big ? " big" : " little"));
            Synthetic s;
            s.vismfVersion = version;
            s.bigEndian = big;
            s.ngrow = version == 3 ? 1 : 0;
            s.dim = version == 4 ? 2 : 3;
            const fs::path dir =
                test::scratchDir() / ("plt" + std::to_string(version) + (big ? "be" : "le"));
            writeSynthetic(dir, s);
            checkSynthetic(readModel(dir, ReadOptions{}), s);
        }
    }
}

TEST(AmrexReader, SyntheticSingleLevel) {
    Synthetic s;
    s.levels = 1;
    const fs::path dir = test::scratchDir() / "plt";
    writeSynthetic(dir, s);
    const Model m = readModel(dir, ReadOptions{});
    EXPECT_EQ(summarize(m).cellsPerLevel, (std::vector<uint64_t>{64}));
    for (size_t i = 0; i < m.cells.size(); ++i) {
        const glm::ivec3 p = m.cells[i].lower;
        ASSERT_EQ(m.fields[1].values[i], synthValue(0, 1, p.x, p.y, p.z)) << "cell " << i;
    }
    EXPECT_DOUBLE_EQ(m.voxelToWorld.scale.y, 0.25);
}

TEST(AmrexReader, NonPowerOfTwoRatioIsRejected) {
    Synthetic s;
    s.ratio = 3;
    const fs::path dir = test::scratchDir() / "plt";
    writeSynthetic(dir, s);
    const std::string msg = errorOf([&] { readAmrex(dir, {}); });
    expectContains(msg, "refinement ratio 3");
    expectContains(msg, "power of two");
}

TEST(AmrexReader, SyntheticTruncatedFabIsReported) {
    Synthetic s;
    const fs::path dir = test::scratchDir() / "plt";
    writeSynthetic(dir, s);
    const fs::path data = dir / "Level_1" / "Cell_D_00000";
    fs::resize_file(data, fs::file_size(data) - 8);
    const std::string msg = errorOf([&] { readAmrex(dir, {}); });
    expectContains(msg, data.string());
    expectContains(msg, "truncated FAB 0");
}

// ---- hostile plotfiles (robustness issue): each edits one field of a valid synthetic plotfile ----

namespace {

// Replaces the one occurrence of `from` in file `p` by `to`.
void edit(const fs::path& p, const std::string& from, const std::string& to) {
    std::string text = readAll(p);
    const size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << "'" << from << "' not in " << p;
    ASSERT_EQ(text.find(from, at + 1), std::string::npos) << "'" << from << "' twice in " << p;
    writeAll(p, text.replace(at, from.size(), to));
}

fs::path syntheticPlotfile(const Synthetic& s = {}) {
    const fs::path dir = test::scratchDir() / "plt";
    writeSynthetic(dir, s);
    return dir;
}

}  // namespace

TEST(AmrexHostile, FabBoxWhoseByteCountWrapsIsRejected) {
    // 2^21 cells per axis: 2^63 cells x 8 bytes wraps 64 bits (it used to wrap to 0 bytes, pass the
    // truncation check and read through a null pointer).
    const fs::path dir = syntheticPlotfile();
    edit(dir / "Level_1" / "Cell_D_00000", "((2,2,2) (5,5,5) (0,0,0))", "((0,0,0) (2097151,2097151,2097151) (0,0,0))");
    expectError([&] { readAmrex(dir, {}); }, {"Cell_D_00000: FAB 0", "overflows 64 bits"});
}

TEST(AmrexHostile, VisMFNgrowWhoseByteCountWrapsIsRejected) {
    Synthetic s;
    s.vismfVersion = 2;
    const fs::path dir = syntheticPlotfile(s);
    edit(dir / "Level_0" / "Cell_H", "2\n0\n2\n0\n(1 0", "2\n0\n2\n1048574\n(1 0");
    expectError([&] { readAmrex(dir, {}); }, {"FAB 0", "overflows 64 bits"});
    edit(dir / "Level_0" / "Cell_H", "2\n0\n2\n1048574\n(1 0", "2\n0\n2\n2147483647\n(1 0");
    expectError([&] { readAmrex(dir, {}); }, {"Cell_H: line 4: ngrow: 2147483647 is outside [0, 1073741823]"});
}

TEST(AmrexHostile, BoxCornersNearInt32LimitsAreRejected) {
    // hi - lo + 1 of these corners overflows int32 (undefined behaviour before the check).
    const fs::path dir = syntheticPlotfile();
    edit(dir / "Level_0" / "Cell_H", "((0,0,0) (3,3,3) (0,0,0))", "((-2147483648,0,0) (2147483647,3,3) (0,0,0))");
    expectError([&] { readAmrex(dir, {}); }, {"Cell_H: line", "has a corner outside [-1073741823, 1073741823]"});
}

TEST(AmrexHostile, ProbDomainThatIsEmptyInvertedOrNanIsRejected) {
    for (const std::string lo : {"1", "2", "nan", "-inf"}) {
        SCOPED_TRACE("prob_lo x = " + lo);
        const fs::path dir = syntheticPlotfile();
        edit(dir / "Header", "\n0 0 0 \n1 1 1 \n", "\n" + lo + " 0 0 \n1 1 1 \n");
        expectError([&] { readAmrex(dir, {}); }, {"Header: line", "prob_lo", "on axis 0",
                                                  "not a finite range with prob_lo < prob_hi"});
    }
}

TEST(AmrexHostile, ControlBytesInTheHeaderStayOnOneLineInTheError) {
    const fs::path dir = syntheticPlotfile();
    const char hostile[] = "b(x)\n\x07\x00\nX\x1b[2J\n0.5";  // a bell, a NUL, a line break, a terminal escape
    edit(dir / "Header", "b(x)\n3\n0.5", std::string(hostile, sizeof hostile - 1));
    const std::string msg = errorOf([&] { readAmrex(dir, {}); });
    expectContains(msg, "expected an integer (dimension)");
    expectContains(msg, "\\x07\\x00\\nX\\x1b[2J");
    for (char c : msg) EXPECT_TRUE(static_cast<unsigned char>(c) >= 0x20) << "control byte in: " << msg;
}
