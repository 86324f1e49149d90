// Enzo reader on the real enzo_tiny_cosmology DD0018 output (oracles in
// shared/data/amr/FORMATS.md 6) and on damaged copies of it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>

#include "amr/model.h"
#include "amr/readers.h"
#include "core/error.h"
#include "model_fixtures.h"
#include "test_data.h"

namespace fs = std::filesystem;
using namespace amrvk;
using namespace amrvk::amr;

using namespace amrvk::test;

namespace {

const char* kParam = "enzo_tiny_cosmology/DD0018/DD0018";

fs::path dataPath(const std::string& name) {
    return test::dataDir() / "enzo_tiny_cosmology" / "DD0018" / name;
}

// Copies DD0018 and DD0018.hierarchy (the text files) into dir/DD0018/; returns the new
// parameter file path.
fs::path copyTextFiles(const fs::path& dir) {
    fs::create_directories(dir / "DD0018");
    for (const char* name : {"DD0018", "DD0018.hierarchy"})
        writeAll(dir / "DD0018" / name, readAll(dataPath(name)));
    return dir / "DD0018" / "DD0018";
}

bool nearPrinted(double value, double printed) {
    return std::abs(value - printed) <= 1e-5 * std::abs(printed);
}

const std::vector<uint64_t> kLeavesPerLevel = {816, 8330, 20202, 86535, 21619};

}  // namespace

TEST(EnzoReader, RealOutputMatchesOracles) {
    AMRVK_REQUIRE_DATA(kParam);
    ReadOptions o;
    o.fields = {"Density"};
    const Model m = readModel(test::dataDir() / kParam, o);
    EXPECT_EQ(m.format, "enzo");
    EXPECT_EQ(m.source, (test::dataDir() / kParam).string());
    for (const char* f : {"Density", "x-velocity", "TotalEnergy", "Metal_Density", "Temperature",
                          "Dark_Matter_Density"})
        EXPECT_NE(std::find(m.availableFields.begin(), m.availableFields.end(), f),
                  m.availableFields.end())
            << f;
    EXPECT_EQ(m.availableFields.size(), 8u);
    ASSERT_EQ(m.fields.size(), 1u);

    // All cells per Enzo level 0..4: 32768, 89192, 21256, 8432, 816, every grid nested in one of
    // the next coarser level, so leaves = cells - (next finer level's cells) / 8. Index 0 = finest
    // (Enzo level 4, 16^3 finest cells per root cell).
    const ModelSummary s = summarize(m);
    EXPECT_EQ(m.cellCount(), 137502u);
    EXPECT_EQ(s.cellsPerLevel, kLeavesPerLevel);
    EXPECT_EQ(s.bounds.lower, glm::i64vec3(0));
    EXPECT_EQ(s.bounds.upper, glm::i64vec3(512));
    EXPECT_DOUBLE_EQ(s.leafVolume, s.bounds.volume());  // the leaves tile the domain
    EXPECT_NO_THROW(validate(m));

    // Domain [0, 1]^3 in code units, root 32^3.
    for (int a = 0; a < 3; ++a) {
        EXPECT_DOUBLE_EQ(m.voxelToWorld.origin[a], 0.0);
        EXPECT_DOUBLE_EQ(m.voxelToWorld.scale[a], 1.0 / 512.0);
    }

    // Density (code units) over all cells 0.0123641 ... 1029.37; both extremes are leaves.
    const FieldStats st = computeFieldStats(m, m.field("Density"));
    EXPECT_TRUE(nearPrinted(st.minValue, 0.0123641)) << st.minValue;
    EXPECT_TRUE(nearPrinted(st.maxValue, 1029.37)) << st.maxValue;

    // Grid 3 (level 1, global start (0, 16, 58), 4x2x6 cells): its value at (x 2, y 1, z 5) is the
    // leaf of width 8 at finest (16, 136, 504).
    bool found = false;
    for (size_t i = 0; i < m.cells.size(); ++i)
        if (m.cells[i].lower == glm::ivec3(16, 136, 504) && m.cells[i].level == 3) {
            found = true;
            EXPECT_NEAR(m.fields[0].values[i], 0.438362f, 1e-6f);
        }
    EXPECT_TRUE(found);

    std::map<std::string, std::string> attrs(m.attributes.begin(), m.attributes.end());
    EXPECT_EQ(attrs["gridsPerLevel"], "2 63 28 15 3");
    EXPECT_EQ(attrs["CosmologyCurrentRedshift"], "1.1456033320512");
}

// Units (issue 33, point 5): the comoving run's code units from its cosmology, each field's own.
// The density unit must turn the sample's code values into the cgs values of its VTK export
// (FORMATS.md 6: 0.0123641 ... 1029.37 code units, 3.08695e-31 ... 2.57002e-26 g/cm^3);
// tests/python/test_units_yt.py checks every unit against yt's.
TEST(EnzoReader, FieldsCarryTheirCodeUnitsFromTheCosmology) {
    AMRVK_REQUIRE_DATA(kParam);
    const Model m = readModel(dataPath("DD0018"), ReadOptions{});
    std::map<std::string, std::string> units;
    for (const Field& f : m.fields) units[f.name] = f.units;
    EXPECT_EQ(units["Density"], "code units (1 = 2.4967e-29 g/cm^3)");
    EXPECT_EQ(units["Dark_Matter_Density"], units["Density"]);
    EXPECT_EQ(units["Metal_Density"], units["Density"]);
    EXPECT_EQ(units["x-velocity"], "code units (1 = 1.4624e+09 cm/s)");
    EXPECT_EQ(units["TotalEnergy"], "code units (1 = 2.1386e+18 erg/g)");
    EXPECT_EQ(units["Temperature"], "K");
    std::map<std::string, std::string> attrs(m.attributes.begin(), m.attributes.end());
    const double density = std::stod(attrs.at("DensityUnits"));
    const FieldStats st = computeFieldStats(m, m.field("Density"));
    EXPECT_NEAR(density * st.minValue, 3.08695e-31, 1e-4 * 3.08695e-31);
    EXPECT_NEAR(density * st.maxValue, 2.57002e-26, 1e-4 * 2.57002e-26);
}

// A run without comoving coordinates states its units in DensityUnits, LengthUnits and TimeUnits;
// without them the units are not known, and a unit line that is not a number is one line.
TEST(EnzoReader, UnitLinesGiveTheUnitsOfARunWithoutCosmology) {
    AMRVK_REQUIRE_DATA(kParam);
    const fs::path dir = test::scratchDir();
    const fs::path param = copyTextFiles(dir);
    for (const char* cpu : {"DD0018.cpu0000", "DD0018.cpu0001"})
        fs::create_symlink(dataPath(cpu), dir / "DD0018" / cpu);
    std::string text = readAll(param);
    const std::string key = "ComovingCoordinates                   = 1";
    const size_t at = text.find(key);
    ASSERT_NE(at, std::string::npos);
    text.replace(at, key.size(), "ComovingCoordinates = 0");
    writeAll(param, text);
    ReadOptions o;
    o.fields = {"Density", "x-velocity"};
    Model m = readEnzo(param, o);
    EXPECT_EQ(m.field("Density").units, "");  // nothing says what a code unit is
    EXPECT_EQ(m.field("x-velocity").units, "");

    writeAll(param, text + "DensityUnits = 1.5e-24\nLengthUnits = 3e21\nTimeUnits = 1e13\n");
    m = readEnzo(param, o);
    EXPECT_EQ(m.field("Density").units, "code units (1 = 1.5e-24 g/cm^3)");
    EXPECT_EQ(m.field("x-velocity").units, "code units (1 = 3e+08 cm/s)");

    // Scales that are not normal numbers are not known either (issue 52, point 9: "DensityUnits inf"
    // beside units "not known"): inf, a velocity of 1e308 / 1e-308, one of 1e-308 / 1e300.
    for (const char* lines : {"DensityUnits = inf\nLengthUnits = 1e308\nTimeUnits = 1e-308\n",
                              "DensityUnits = 1e-320\nLengthUnits = 1e-308\nTimeUnits = 1e300\n"}) {
        writeAll(param, text + lines);
        m = readEnzo(param, o);
        EXPECT_EQ(m.field("Density").units, "") << lines;
        EXPECT_EQ(m.field("x-velocity").units, "") << lines;
        for (const auto& [k, v] : m.attributes)
            EXPECT_TRUE(k != "DensityUnits" && k != "VelocityUnits") << k << " " << v;
    }

    writeAll(param, text + "DensityUnits = lots\n");
    const std::string msg = errorOf([&] { readEnzo(param, o); });
    expectContains(msg, param.string() + ": DensityUnits: 'lots' is not a list of numbers");
    EXPECT_EQ(msg.find('\n'), std::string::npos);
}

TEST(EnzoReader, HierarchyPathAndAllFields) {
    AMRVK_REQUIRE_DATA(kParam);
    const Model m = readModel(dataPath("DD0018.hierarchy"), ReadOptions{});
    EXPECT_EQ(m.format, "enzo");
    ASSERT_EQ(m.fields.size(), 8u);
    EXPECT_EQ(m.fields[0].name, "Density");
    EXPECT_EQ(summarize(m).cellsPerLevel, kLeavesPerLevel);
    const FieldStats t = computeFieldStats(m, m.field("Temperature"));
    EXPECT_GT(t.minValue, 0.0f);
    EXPECT_GT(t.maxValue, t.minValue);
}

TEST(EnzoReader, UnknownFieldListsAvailable) {
    AMRVK_REQUIRE_DATA(kParam);
    ReadOptions o;
    o.fields = {"density"};
    const std::string msg = errorOf([&] { readEnzo(test::dataDir() / kParam, o); });
    expectContains(msg, "unknown field 'density'");
    expectContains(msg, "Density, x-velocity");
    EXPECT_EQ(msg.find('\n'), std::string::npos);
}

TEST(EnzoReader, MissingFilesAreReported) {
    AMRVK_REQUIRE_DATA(kParam);
    const fs::path dir = test::scratchDir();
    fs::create_directories(dir / "DD0018");
    writeAll(dir / "DD0018" / "DD0018", readAll(dataPath("DD0018")));
    std::string msg = errorOf([&] { readEnzo(dir / "DD0018" / "DD0018", {}); });
    expectContains(msg, (dir / "DD0018" / "DD0018.hierarchy").string());
    expectContains(msg, "no such file");

    const fs::path param = copyTextFiles(dir);
    msg = errorOf([&] { readEnzo(param, {}); });
    expectContains(msg, (dir / "DD0018" / "DD0018.cpu0000").string());
    expectContains(msg, "no such file");
}

TEST(EnzoReader, TruncatedGridFileIsReported) {
    AMRVK_REQUIRE_DATA(kParam);
    const fs::path dir = test::scratchDir();
    const fs::path param = copyTextFiles(dir);
    writeAll(dir / "DD0018" / "DD0018.cpu0000", readAll(dataPath("DD0018.cpu0000")));
    const std::string cpu1 = readAll(dataPath("DD0018.cpu0001"));
    const fs::path victim = dir / "DD0018" / "DD0018.cpu0001";
    writeAll(victim, cpu1.substr(0, cpu1.size() / 2));
    const std::string msg = errorOf([&] { readModel(param, ReadOptions{}); });
    expectContains(msg, victim.string());
    EXPECT_EQ(msg.find('\n'), std::string::npos);
}

TEST(EnzoReader, NonPowerOfTwoRefineByIsRejected) {
    AMRVK_REQUIRE_DATA(kParam);
    const fs::path dir = test::scratchDir();
    const fs::path param = copyTextFiles(dir);
    std::string text = readAll(param);
    const std::string key = "RefineBy                       = 2";
    const size_t at = text.find(key);
    ASSERT_NE(at, std::string::npos);
    text.replace(at, key.size(), "RefineBy                       = 3");
    writeAll(param, text);
    const std::string msg = errorOf([&] { readEnzo(param, {}); });
    expectContains(msg, param.string());
    expectContains(msg, "RefineBy 3 is not a power of two");
}

TEST(EnzoReader, RoundTripThroughExaBrick) {
    AMRVK_REQUIRE_DATA(kParam);
    ReadOptions o;
    o.fields = {"Density", "Temperature"};
    const Model m = readModel(test::dataDir() / kParam, o);
    test::expectExaBrickRoundTrip(m);
}

// ---- hostile hierarchies (robustness issue): one edited value in a copy of the real output ----

namespace {

// A copy of DD0018 (text and grid files) whose hierarchy has `from` replaced by `to` once.
fs::path editedCopy(const std::string& file, const std::string& from, const std::string& to) {
    const fs::path dir = test::scratchDir();
    const fs::path param = copyTextFiles(dir);
    for (const char* name : {"DD0018.cpu0000", "DD0018.cpu0001"})
        writeAll(dir / "DD0018" / name, readAll(dataPath(name)));
    std::string text = readAll(dir / "DD0018" / file);
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) writeAll(dir / "DD0018" / file, text.replace(at, from.size(), to));
    return param;
}

}  // namespace

TEST(EnzoHostile, GridExtentNearInt32LimitIsRejected) {
    AMRVK_REQUIRE_DATA(kParam);
    // 2^31 - 4 active cells per axis (level 26): a box whose corner is past the +-2^30 index limit.
    const std::string grid1 = "GridDimension     = 38 38 22 \nGridStartIndex    = 3 3 3 \n"
                              "GridEndIndex      = 34 34 18 \nGridLeftEdge      = 0 0 0 \nGridRightEdge     = 1 1 0.5";
    const std::string huge = "GridDimension     = 2147483647 2147483647 2147483647 \nGridStartIndex    = 3 3 3 \n"
                             "GridEndIndex      = 2147483646 2147483646 2147483646 \nGridLeftEdge      = 0 0 0 \n"
                             "GridRightEdge     = 1 1 1";
    const fs::path param = editedCopy("DD0018.hierarchy", grid1, huge);
    expectError([&] { readEnzo(param, {}); }, {"DD0018.hierarchy: grid 1", "has a corner outside [-1073741823, 1073741823]"});
}

TEST(EnzoHostile, DomainThatIsNotFiniteIsRejected) {
    AMRVK_REQUIRE_DATA(kParam);
    for (const std::string right : {"inf 1 1", "nan 1 1", "0 1 1"}) {
        SCOPED_TRACE(right);
        const fs::path param = editedCopy("DD0018", "DomainRightEdge        = 1 1 1", "DomainRightEdge        = " + right);
        expectError([&] { readEnzo(param, {}); }, {"DD0018: empty or non-finite domain on axis 0"});
    }
}
