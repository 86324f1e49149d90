// Chombo reader on the two real 2-D mushy-layer plotfiles (oracles in shared/data/amr/FORMATS.md 6)
// and on damaged copies of them.
#include <gtest/gtest.h>
#include <hdf5.h>

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

const char* kPlt25000 = "chombo_mushy_layer_2d/plt025000.2d.hdf5";
const char* kPlt100 = "chombo_mushy_layer_2d/plt000100.2d.hdf5";

bool nearPrinted(double value, double printed) {
    return std::abs(value - printed) <= 1e-5 * std::abs(printed);
}

// Leaves of a 2-D slab: each cell is as thick as it is wide, so the area is sum(width^2).
double slabArea(const Model& m) {
    double area = 0;
    for (const Cell& c : m.cells) area += std::ldexp(1.0, 2 * c.level);
    return area;
}

float valueAt(const Model& m, glm::ivec3 lower, int level) {
    for (size_t i = 0; i < m.cells.size(); ++i)
        if (m.cells[i].lower == lower && m.cells[i].level == level) return m.fields[0].values[i];
    ADD_FAILURE() << "no leaf at " << lower.x << "," << lower.y << "," << lower.z << " level "
                  << level;
    return 0.0f;
}

}  // namespace

TEST(ChomboReader, Plt025000MatchesOracles) {
    AMRVK_REQUIRE_DATA(kPlt25000);
    ReadOptions o;
    o.fields = {"Temperature"};
    const Model m = readModel(test::dataDir() / kPlt25000, o);
    EXPECT_EQ(m.format, "chombo");
    ASSERT_EQ(m.availableFields.size(), 14u);
    EXPECT_EQ(m.availableFields[2], "Temperature");
    EXPECT_EQ(m.availableFields[13], "yFs");

    // Boxes 1, 8, 8; ratios 4, 2: Chombo level 0 (32^2 cells) has width 8 (ExaBrick level 3),
    // level 1 (6144 cells) width 2, level 2 (4608 cells) width 1 - 11,776 cells in all. Level 1
    // covers 384 level-0 cells and level 2 covers 1152 level-1 cells, so 640 + 4992 + 4608 =
    // 10,240 leaves. FORMATS.md 6 says 10,984 leaves; that number does not tile the domain (it
    // matches neither this file's boxes nor an independent count) - see the reader report.
    const ModelSummary s = summarize(m);
    EXPECT_EQ(m.cellCount(), 10240u);
    EXPECT_EQ(s.cellsPerLevel, (std::vector<uint64_t>{4608, 4992, 0, 640}));
    EXPECT_EQ(s.bounds.lower, glm::i64vec3(0));
    EXPECT_EQ(s.bounds.upper, glm::i64vec3(256, 256, 8));
    EXPECT_DOUBLE_EQ(slabArea(m), 256.0 * 256.0);  // the leaves tile the 2-D domain
    EXPECT_NO_THROW(validate(m));

    // dx 0.03125 / 0.0078125 / 0.00390625, domain [0, 1]^2.
    EXPECT_EQ(m.voxelToWorld.origin, glm::dvec3(0.0));
    EXPECT_EQ(m.voxelToWorld.scale, glm::dvec3(0.00390625));
    EXPECT_EQ(m.voxelToWorld.toWorld(glm::dvec3(256.0)).x, 1.0);

    // Temperature over the leaves: 0.0095969 ... 1.16496.
    const FieldStats st = computeFieldStats(m, m.field("Temperature"));
    EXPECT_TRUE(nearPrinted(st.minValue, 0.0095969)) << st.minValue;
    EXPECT_TRUE(nearPrinted(st.maxValue, 1.16496)) << st.maxValue;

    // Values from data:datatype=0: level 2 box 0 cell (3, 190); level 0 cell (4, 1).
    EXPECT_FLOAT_EQ(valueAt(m, {3, 190, 0}, 0), static_cast<float>(0.9218101239101113));
    EXPECT_FLOAT_EQ(valueAt(m, {32, 8, 0}, 3), static_cast<float>(1.1617408547760775));

    std::map<std::string, std::string> attrs(m.attributes.begin(), m.attributes.end());
    EXPECT_EQ(attrs["boxesPerLevel"], "1 8 8");
    EXPECT_EQ(attrs["refinementRatios"], "4 2");
    EXPECT_EQ(attrs["iteration"], "25000");
}

TEST(ChomboReader, Plt000100MatchesOracles) {
    AMRVK_REQUIRE_DATA(kPlt100);
    ReadOptions o;
    o.fields = {"Temperature"};
    const Model m = readModel(test::dataDir() / kPlt100, o);
    ASSERT_EQ(m.availableFields.size(), 15u);

    // Cells 256, 768, 2176 (ratios 2, 2): leaves 256 - 768/4, 768 - 2176/4, 2176 = 2,464.
    const ModelSummary s = summarize(m);
    EXPECT_EQ(m.cellCount(), 2464u);
    EXPECT_EQ(s.cellsPerLevel, (std::vector<uint64_t>{2176, 224, 64}));
    EXPECT_EQ(s.bounds.upper, glm::i64vec3(64, 64, 4));
    EXPECT_DOUBLE_EQ(slabArea(m), 64.0 * 64.0);
    EXPECT_NO_THROW(validate(m));
    EXPECT_EQ(m.voxelToWorld.scale, glm::dvec3(0.015625));

    const FieldStats st = computeFieldStats(m, m.field("Temperature"));
    EXPECT_TRUE(nearPrinted(st.minValue, 0.10069)) << st.minValue;
    EXPECT_TRUE(nearPrinted(st.maxValue, 1.30736)) << st.maxValue;
}

TEST(ChomboReader, AllFieldsByDefault) {
    AMRVK_REQUIRE_DATA(kPlt100);
    const Model m = readModel(test::dataDir() / kPlt100, ReadOptions{});
    ASSERT_EQ(m.fields.size(), 15u);
    EXPECT_EQ(m.fields[8].name, "Pressure");
    for (const Field& f : m.fields) EXPECT_EQ(f.values.size(), m.cells.size());
}

TEST(ChomboReader, UnknownFieldListsAvailable) {
    AMRVK_REQUIRE_DATA(kPlt25000);
    ReadOptions o;
    o.fields = {"temperature"};
    const std::string msg = errorOf([&] { readChombo(test::dataDir() / kPlt25000, o); });
    expectContains(msg, "unknown field 'temperature'");
    expectContains(msg, "Bulk concentration, Temperature, Porosity");
    EXPECT_EQ(msg.find('\n'), std::string::npos);
}

TEST(ChomboReader, BadFilesAreReported) {
    const fs::path dir = test::scratchDir();
    std::string msg = errorOf([&] { readChombo(dir / "missing.hdf5", {}); });
    expectContains(msg, (dir / "missing.hdf5").string());
    expectContains(msg, "no such file");

    writeAll(dir / "text.hdf5", "not an HDF5 file\n");
    msg = errorOf([&] { readChombo(dir / "text.hdf5", {}); });
    expectContains(msg, (dir / "text.hdf5").string());
    expectContains(msg, "cannot open as HDF5");
    EXPECT_EQ(msg.find('\n'), std::string::npos);
}

TEST(ChomboReader, TruncatedCopyIsReported) {
    AMRVK_REQUIRE_DATA(kPlt25000);
    const fs::path victim = test::scratchDir() / "plt025000.2d.hdf5";
    const std::string bytes = readAll(test::dataDir() / kPlt25000);
    writeAll(victim, bytes.substr(0, bytes.size() / 2));
    const std::string msg = errorOf([&] { readModel(victim, ReadOptions{}); });
    expectContains(msg, victim.string());
    EXPECT_EQ(msg.find('\n'), std::string::npos);
}

TEST(ChomboReader, RoundTripThroughExaBrick) {
    AMRVK_REQUIRE_DATA(kPlt25000);
    ReadOptions o;
    o.fields = {"Temperature", "Porosity"};
    const Model m = readModel(test::dataDir() / kPlt25000, o);
    test::expectExaBrickRoundTrip(m);
}

// ---- hostile files (robustness issue): one value of a copy of the real plotfile rewritten ----

namespace {

// A writable copy of plt000100 with `edit(file)` applied through the HDF5 library.
fs::path editedCopy(const std::function<void(hid_t)>& edit) {
    const fs::path copy = test::scratchDir() / "plt000100.2d.hdf5";
    writeAll(copy, readAll(test::dataDir() / kPlt100));
    const hid_t f = H5Fopen(copy.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    EXPECT_GE(f, 0);
    edit(f);
    H5Fclose(f);
    return copy;
}

void writeLevel0Dx(hid_t f, double dx) {
    const hid_t g = H5Gopen2(f, "level_0", H5P_DEFAULT);
    const hid_t a = H5Aopen(g, "dx", H5P_DEFAULT);
    EXPECT_GE(H5Awrite(a, H5T_NATIVE_DOUBLE, &dx), 0);
    H5Aclose(a);
    H5Gclose(g);
}

}  // namespace

TEST(ChomboHostile, DxThatIsZeroNanOrNegativeIsRejected) {
    AMRVK_REQUIRE_DATA(kPlt100);
    for (double dx : {0.0, -0.5, std::nan(""), double(INFINITY)}) {
        SCOPED_TRACE(dx);
        const fs::path copy = editedCopy([&](hid_t f) { writeLevel0Dx(f, dx); });
        expectError([&] { readChombo(copy, {}); }, {copy.string(), ": level_0 dx", "is not a finite positive cell size"});
    }
}

TEST(ChomboHostile, BoxCornersNearInt32LimitsAreRejected) {
    AMRVK_REQUIRE_DATA(kPlt100);
    // The first box of level 0 from lo_i = -2^31 to hi_i = 2^31 - 1: its extent overflows int32.
    const fs::path copy = editedCopy([](hid_t f) {
        const hid_t d = H5Dopen2(f, "level_0/boxes", H5P_DEFAULT);
        const hid_t mem = H5Tcreate(H5T_COMPOUND, 2 * sizeof(int));
        H5Tinsert(mem, "lo_i", 0, H5T_NATIVE_INT);
        H5Tinsert(mem, "hi_i", sizeof(int), H5T_NATIVE_INT);
        const hid_t space = H5Dget_space(d);
        std::vector<int> v(2 * size_t(H5Sget_simple_extent_npoints(space)));
        EXPECT_GE(H5Dread(d, mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), 0);
        v[0] = INT32_MIN;
        v[1] = INT32_MAX;
        EXPECT_GE(H5Dwrite(d, mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), 0);
        H5Sclose(space);
        H5Tclose(mem);
        H5Dclose(d);
    });
    expectError([&] { readChombo(copy, {}); }, {"'level_0/boxes' box 0", "has a corner outside [-1073741823, 1073741823]"});
}
