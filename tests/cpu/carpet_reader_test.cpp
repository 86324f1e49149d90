// Carpet reader on the real WaveToy checkpoint (shared/data/amr/FORMATS.md 4.5, SOURCES.md 3) and
// on damaged copies of it. Oracles: the file's own attributes, FORMATS.md's per-level point counts
// (20^3 + 3 x 25^3 vertices, active 16^3 and 3 x 21^3), and values computed independently with
// h5py/numpy from the datasets (mean of each cell's 8 corner vertices, leaves as documented in
// docs/formats.md).
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <cstring>
#include <functional>

#include "amr/model.h"
#include "amr/readers.h"
#include "core/error.h"
#include "test_data.h"

namespace fs = std::filesystem;
using namespace amrvk;
using namespace amrvk::amr;
using namespace amrvk::test;

namespace {

const char* kWaveToy = "carpet_wavetoy_3d/CarpetWaveToyCheckpoint_test.it_64.h5";

std::string attribute(const Model& m, const std::string& key) {
    for (const auto& [k, v] : m.attributes)
        if (k == key) return v;
    ADD_FAILURE() << "no attribute " << key;
    return {};
}

float valueAt(const Model& m, glm::ivec3 lower, int level) {
    for (size_t i = 0; i < m.cells.size(); ++i)
        if (m.cells[i].lower == lower && m.cells[i].level == level) return m.fields[0].values[i];
    ADD_FAILURE() << "no leaf at " << lower.x << "," << lower.y << "," << lower.z << " level " << level;
    return 0.0f;
}

}  // namespace

TEST(CarpetReader, WaveToyIsDetectedAsCarpet) {
    AMRVK_REQUIRE_DATA(kWaveToy);
    EXPECT_EQ(detectFormat(test::dataDir() / kWaveToy), "carpet");
    EXPECT_TRUE(isCarpetFile(test::dataDir() / kWaveToy));
    // Chombo plotfiles stay Chombo.
    const char* chombo = "chombo_mushy_layer_2d/plt000100.2d.hdf5";
    if (fs::exists(test::dataDir() / chombo)) {
        EXPECT_EQ(detectFormat(test::dataDir() / chombo), "chombo");
    }
}

TEST(CarpetReader, WaveToyMatchesAttributesAndPointCounts) {
    AMRVK_REQUIRE_DATA(kWaveToy);
    const Model m = readModel(test::dataDir() / kWaveToy, ReadOptions{});
    EXPECT_EQ(m.format, "carpet");
    EXPECT_EQ(m.availableFields, (std::vector<std::string>{"WAVETOY::phi"}));
    // FORMATS.md 4.5 / SOURCES.md 3: 4 levels, rl0 20^3 points, rl1..3 25^3; active 16^3 and 21^3.
    EXPECT_EQ(attribute(m, "levels"), "4");
    EXPECT_EQ(attribute(m, "carpetReflevels"), "4");
    EXPECT_EQ(attribute(m, "componentsPerLevel"), "1 1 1 1");
    EXPECT_EQ(attribute(m, "refinementRatios"), "2 2 2");
    EXPECT_EQ(attribute(m, "pointsPerLevel"), "8000 15625 15625 15625");
    EXPECT_EQ(attribute(m, "activePointsPerLevel"), "4096 9261 9261 9261");
    EXPECT_EQ(attribute(m, "iteration"), "64");
    EXPECT_EQ(attribute(m, "timelevel"), "0");
    EXPECT_NEAR(std::stod(attribute(m, "time")), 0.42105263157894735, 1e-5);

    // Cells between active vertices: rl0 15^3 (width 8), rl1 cut to whole rl0 cells 18^3 (covers
    // 9^3 rl0 cells), rl2 20^3 (covers 10^3 rl1 cells), rl3 20^3 (covers 10^3 rl2 cells).
    const ModelSummary s = summarize(m);
    EXPECT_EQ(s.cellsPerLevel, (std::vector<uint64_t>{8000, 7000, 4832, 2646}));
    EXPECT_EQ(m.cellCount(), 22478u);
    EXPECT_EQ(s.bounds.lower, glm::i64vec3(0));
    EXPECT_EQ(s.bounds.upper, glm::i64vec3(120));
    EXPECT_DOUBLE_EQ(s.leafVolume, 120.0 * 120.0 * 120.0);  // the leaves tile rl0's active cells
    EXPECT_NO_THROW(validate(m));

    // Voxel 0 is rl0 vertex 2 (the first active one) at -1 + 2 * 2/19; a voxel is rl3's delta 2/152.
    const double delta0 = 2.0 / 19.0;
    for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(m.voxelToWorld.origin[a], -1.0 + 2 * delta0, 1e-12);
        EXPECT_NEAR(m.voxelToWorld.scale[a], delta0 / 8, 1e-12);
    }
    // rl3's first active vertex (finest index 66, voxel 50) sits at rl3's origin + 2 delta.
    EXPECT_NEAR(m.voxelToWorld.toWorld(glm::dvec3(50)).x, -0.15789473684210525 + 2 * delta0 / 8, 1e-9);
}

TEST(CarpetReader, WaveToyValuesAreCornerMeans) {
    AMRVK_REQUIRE_DATA(kWaveToy);
    const Model m = readModel(test::dataDir() / kWaveToy, ReadOptions{});
    // h5py/numpy: the mean of the 8 corners of the named cells, and over all leaves.
    EXPECT_NEAR(valueAt(m, glm::ivec3(50), 0), 0.928110669, 1e-6);              // rl3, vertex 66
    EXPECT_NEAR(valueAt(m, glm::ivec3(0), 3), 0.782128081, 1e-6);               // rl0, vertex 2
    EXPECT_NEAR(valueAt(m, glm::ivec3(16, 0, 0), 3), 0.802636194, 1e-6);        // rl0, vertex (4,2,2)
    const FieldStats st = computeFieldStats(m, m.defaultField());
    EXPECT_NEAR(st.minValue, 0.782128081, 1e-6);
    EXPECT_NEAR(st.maxValue, 0.933400237, 1e-6);
    EXPECT_NEAR(st.volumeWeightedMean, 0.868849079, 1e-6);
}

TEST(CarpetReader, UnknownFieldListsAvailable) {
    AMRVK_REQUIRE_DATA(kWaveToy);
    ReadOptions o;
    o.fields = {"phi"};
    expectError([&] { readModel(test::dataDir() / kWaveToy, o); }, {"unknown field 'phi'", "WAVETOY::phi"});
}

TEST(CarpetReader, TruncatedCopyIsReported) {
    AMRVK_REQUIRE_DATA(kWaveToy);
    const fs::path victim = test::scratchDir() / "carpet_truncated.h5";
    const std::string bytes = readAll(test::dataDir() / kWaveToy);
    writeAll(victim, bytes.substr(0, bytes.size() / 2));
    const std::string msg = errorOf([&] { readCarpet(victim, ReadOptions{}); });
    expectContains(msg, victim.string());
    EXPECT_EQ(msg.find('\n'), std::string::npos);
}

// ---- hostile files: one attribute or dataset of a copy of the real file rewritten ----

namespace {

const char* kRl2 = "WAVETOY::phi it=64 tl=0 rl=2";

// A writable copy of the WaveToy file with `edit(file)` applied through the HDF5 library.
fs::path editedCopy(const std::function<void(hid_t)>& edit) {
    const fs::path copy = test::scratchDir() / "carpet_edited.h5";
    writeAll(copy, readAll(test::dataDir() / kWaveToy));
    const hid_t f = H5Fopen(copy.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    EXPECT_GE(f, 0);
    edit(f);
    H5Fclose(f);
    return copy;
}

template <typename T>
void writeNumbers(hid_t f, const char* dataset, const char* attr, std::vector<T> v) {
    const hid_t d = H5Dopen2(f, dataset, H5P_DEFAULT);
    const hid_t a = H5Aopen(d, attr, H5P_DEFAULT);
    EXPECT_GE(H5Awrite(a, std::is_same_v<T, int> ? H5T_NATIVE_INT : H5T_NATIVE_DOUBLE, v.data()), 0);
    H5Aclose(a);
    H5Dclose(d);
}

void writeActive(hid_t f, const char* dataset, const std::string& text) {
    const hid_t d = H5Dopen2(f, dataset, H5P_DEFAULT);
    EXPECT_GE(H5Adelete(d, "active"), 0);
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, text.size());
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t a = H5Acreate2(d, "active", type, space, H5P_DEFAULT, H5P_DEFAULT);
    EXPECT_GE(H5Awrite(a, type, text.data()), 0);
    H5Aclose(a);
    H5Sclose(space);
    H5Tclose(type);
    H5Dclose(d);
}

std::string rl2Active(const std::string& boxes) {
    return "bboxset<CCTK_INT4,3>(set<bbox>:{" + boxes + "},stride:[2,2,2],offset:[0,0,0])";
}

}  // namespace

TEST(CarpetHostile, ActiveRegionOutsideTheDataIsRejected) {
    AMRVK_REQUIRE_DATA(kWaveToy);
    // rl2 holds level points 26..50; claim 28..60 (finest 56..120).
    const fs::path copy = editedCopy([](hid_t f) {
        writeActive(f, kRl2, rl2Active("([56,56,56]:[120,96,96]:[2,2,2]/[28,28,28]:[60,48,48]/[33,21,21]/1)"));
    });
    expectError([&] { readCarpet(copy, {}); }, {copy.string(), kRl2, "owns points 28..60 on axis 0 outside its 25 points from 26"});
}

TEST(CarpetHostile, MalformedActiveIsRejected) {
    AMRVK_REQUIRE_DATA(kWaveToy);
    for (const auto& [text, fragment] : std::vector<std::pair<std::string, std::string>>{
             {"garbage", "is not a Carpet bboxset"},
             {rl2Active("([56,56,56]:[96,96,96]:[2,2,3]/x)"), "is not one power of two on every axis"},
             {rl2Active("([57,56,56]:[96,96,96]:[2,2,2]/x)"), "is empty or not on stride 2"},
             {rl2Active("([99999999999,56,56]:[96,96,96]:[2,2,2]/x)"), "'99999999999' is not an index in"},
         }) {
        SCOPED_TRACE(text);
        const fs::path copy = editedCopy([&](hid_t f) { writeActive(f, kRl2, text); });
        expectError([&] { readCarpet(copy, {}); }, {copy.string(), kRl2, fragment});
    }
}

// Long text (issue 52, point 1): a 30,000-character dataset name and a 60,000-digit number in
// `active` crashed the reader (std::regex recursed per character). Now each gives one short line.
TEST(CarpetHostile, LongNamesAndNumbersGiveOneShortLine) {
    AMRVK_REQUIRE_DATA(kWaveToy);
    const std::string longName = std::string(30000, 'X') + " it=64 tl=0 rl=0";
    fs::path copy = editedCopy([&](hid_t f) {
        EXPECT_GE(H5Lmove(f, "WAVETOY::phi it=64 tl=0 rl=0", f, longName.c_str(), H5P_DEFAULT, H5P_DEFAULT), 0);
    });
    std::string msg = errorOf([&] { readCarpet(copy, {}); });
    expectContains(msg, "'WAVETOY::phi' has no dataset of timelevel 0 on refinement level 0");
    EXPECT_LT(msg.size(), 300u);
    copy = editedCopy([](hid_t f) {
        writeActive(f, kRl2, rl2Active("([" + std::string(60000, '1') + ",56,56]:[96,96,96]:[2,2,2]/x)"));
    });
    msg = errorOf([&] { readCarpet(copy, {}); });
    expectContains(msg, "'" + std::string(40, '1') + "... (60000 bytes)' is not an index in");
    EXPECT_LT(msg.size(), 300u);
}

// A level or iteration beyond the reader's limit was skipped (3 levels read of 4; issue 52,
// point 9): now an error naming the dataset.
TEST(CarpetHostile, NumbersBeyondTheLimitAreNamedNotSkipped) {
    AMRVK_REQUIRE_DATA(kWaveToy);
    const fs::path copy = editedCopy([](hid_t f) {
        EXPECT_GE(H5Lmove(f, "WAVETOY::phi it=64 tl=0 rl=3", f, "WAVETOY::phi it=64 tl=0 rl=2147483648", H5P_DEFAULT,
                          H5P_DEFAULT),
                  0);
    });
    expectError(
        [&] { readCarpet(copy, {}); },
        {copy.string(), "'WAVETOY::phi it=64 tl=0 rl=2147483648': rl=2147483648 is beyond this reader's limit"});
}

// Misleading messages (issue 52, point 16): cells of 1e-300 or 1e300 were reported as a camera
// whose eye and target coincide, or that is not finite; a finite 1e300 as "non-finite (inf)"; a
// 2-D dataset among 3-D levels as a gap in the levels; an iteration of 2^32 as a missing
// timelevel. Each now names what is wrong.
TEST(CarpetHostile, Round4MessagesNameWhatIsWrong) {
    AMRVK_REQUIRE_DATA(kWaveToy);
    // Scaled by 1e-20 the file stays inside the limits: the check rejects only what it names.
    for (const double factor : {1e-20, 1e-300, 1e300}) {
        SCOPED_TRACE(factor);
        const fs::path copy = editedCopy([&](hid_t f) {
            for (int rl = 0; rl < 4; ++rl) {
                const std::string name = "WAVETOY::phi it=64 tl=0 rl=" + std::to_string(rl);
                for (const char* attr : {"delta", "origin"}) {
                    const hid_t d = H5Dopen2(f, name.c_str(), H5P_DEFAULT);
                    const hid_t a = H5Aopen(d, attr, H5P_DEFAULT);
                    std::vector<double> v(3);
                    EXPECT_GE(H5Aread(a, H5T_NATIVE_DOUBLE, v.data()), 0);
                    H5Aclose(a);
                    H5Dclose(d);
                    for (double& x : v) x *= factor;
                    writeNumbers<double>(f, name.c_str(), attr, v);
                }
            }
        });
        if (factor == 1e-20) {
            EXPECT_NEAR(readModel(copy, {}).voxelToWorld.scale.x, 0.1052631578947368 / 8 * 1e-20, 1e-30);
            continue;
        }
        expectError([&] { readModel(copy, {}); }, {copy.string(), ": a finest cell is", "wide on axis 0",
                                                   "amrvk's world coordinates hold cell sizes in [1e-30, 1e+30]"});
    }
    fs::path copy = editedCopy([](hid_t f) {
        const hid_t d = H5Dopen2(f, "WAVETOY::phi it=64 tl=0 rl=0", H5P_DEFAULT);
        std::vector<double> v(20 * 20 * 20, 1e300);
        EXPECT_GE(H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), 0);
        H5Dclose(d);
    });
    expectError([&] { readModel(copy, {}); },
                {copy.string(), "'WAVETOY::phi it=64 tl=0 rl=0' has a cell whose corners' mean is 1e+300",
                 "beyond the 32-bit floats"});
    copy = editedCopy([](hid_t f) {
        EXPECT_GE(H5Ldelete(f, kRl2, H5P_DEFAULT), 0);
        const hsize_t dims[2] = {25, 25};
        const hid_t space = H5Screate_simple(2, dims, nullptr);
        const hid_t d = H5Dcreate2(f, kRl2, H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        EXPECT_GE(d, 0);
        H5Dclose(d);
        H5Sclose(space);
    });
    expectError([&] { readModel(copy, {}); },
                {copy.string(),
                 "'WAVETOY::phi it=64 tl=0 rl=2' has 2 axes where the other datasets of 'WAVETOY::phi' "
                 "have 3 (amrvk reads 3-D Carpet grids)"});
    copy = editedCopy([](hid_t f) {
        EXPECT_GE(H5Lmove(f, "WAVETOY::phi it=64 tl=0 rl=0", f, "WAVETOY::phi it=4294967296 tl=0 rl=0", H5P_DEFAULT,
                          H5P_DEFAULT),
                  0);
    });
    expectError([&] { readModel(copy, {}); }, {copy.string(), "it=4294967296 is beyond this reader's limit"});
}

TEST(CarpetHostile, GeometryThatDisagreesWithTheIndicesIsRejected) {
    AMRVK_REQUIRE_DATA(kWaveToy);
    fs::path copy = editedCopy([](hid_t f) { writeNumbers<double>(f, kRl2, "delta", {0.05, 0.05, 0.05}); });
    expectError([&] { readCarpet(copy, {}); }, {copy.string(), kRl2, "its iorigin and stride give"});
    copy = editedCopy([](hid_t f) { writeNumbers<int>(f, kRl2, "iorigin", {27, 26, 26}); });
    expectError([&] { readCarpet(copy, {}); }, {copy.string(), kRl2, "its iorigin and stride give"});
    copy = editedCopy([](hid_t f) { writeNumbers<double>(f, kRl2, "delta", {std::nan(""), 1, 1}); });
    expectError([&] { readCarpet(copy, {}); }, {copy.string(), kRl2, "need finite values and delta > 0"});
    copy = editedCopy([](hid_t f) { writeNumbers<int>(f, kRl2, "iorigin", {1 << 30, 26, 26}); });
    expectError([&] { readCarpet(copy, {}); }, {copy.string(), kRl2, "iorigin: 1073741824 is outside"});
}

TEST(CarpetHostile, LevelAttributesAreChecked) {
    AMRVK_REQUIRE_DATA(kWaveToy);
    fs::path copy = editedCopy([](hid_t f) { writeNumbers<int>(f, kRl2, "level", {1}); });
    expectError([&] { readCarpet(copy, {}); }, {copy.string(), kRl2, "has attribute level 1 but its name says rl=2"});
    copy = editedCopy([](hid_t f) { writeNumbers<int>(f, kRl2, "ioffset", {1, 0, 0}); });
    expectError([&] { readCarpet(copy, {}); }, {copy.string(), kRl2, "only vertex-centred Carpet grids"});
    copy = editedCopy([](hid_t f) { EXPECT_GE(H5Ldelete(f, kRl2, H5P_DEFAULT), 0); });
    expectError([&] { readCarpet(copy, {}); }, {copy.string(), "refinement levels up to rl=3 but only 3"});
    copy = editedCopy([](hid_t f) {
        const hid_t d = H5Dopen2(f, kRl2, H5P_DEFAULT);
        EXPECT_GE(H5Adelete(d, "origin"), 0);
        H5Dclose(d);
    });
    expectError([&] { readCarpet(copy, {}); }, {copy.string(), kRl2, "has no attribute 'origin'"});
}

TEST(CarpetReader, EveryComponentOfALevelIsRead) {
    AMRVK_REQUIRE_DATA(kWaveToy);
    // rl3 split into two components on the same array: c=0 owns x 66..75, c=1 x 76..86 (finest
    // index). The cells between them (x 75..76) have corners in both and are rl3's too, so the
    // leaves are those of the whole file, with the same values.
    const char* rl3 = "WAVETOY::phi it=64 tl=0 rl=3";
    const std::string c0 = std::string(rl3) + " c=0", c1 = std::string(rl3) + " c=1";
    const fs::path copy = editedCopy([&](hid_t f) {
        EXPECT_GE(H5Lmove(f, rl3, f, c0.c_str(), H5P_DEFAULT, H5P_DEFAULT), 0);
        EXPECT_GE(H5Ocopy(f, c0.c_str(), f, c1.c_str(), H5P_DEFAULT, H5P_DEFAULT), 0);
        const std::string pre = "bboxset<CCTK_INT4,3>(set<bbox>:{(";
        const std::string post = ":[1,1,1]/x)},stride:[1,1,1],offset:[0,0,0])";
        writeActive(f, c0.c_str(), pre + "[66,66,66]:[75,86,86]" + post);
        writeActive(f, c1.c_str(), pre + "[76,66,66]:[86,86,86]" + post);
    });
    const Model m = readModel(copy, ReadOptions{});
    EXPECT_EQ(attribute(m, "componentsPerLevel"), "1 1 1 2");
    EXPECT_EQ(attribute(m, "activePointsPerLevel"), "4096 9261 9261 9261");  // 21^2 x (10 + 11)
    const ModelSummary s = summarize(m);
    EXPECT_EQ(s.cellsPerLevel, (std::vector<uint64_t>{8000, 7000, 4832, 2646}));
    EXPECT_DOUBLE_EQ(s.leafVolume, 120.0 * 120.0 * 120.0);
    EXPECT_NO_THROW(validate(m));
    // Every leaf's value as in the whole file: c=0's cells, the seam's, c=1's.
    const Model whole = readModel(test::dataDir() / kWaveToy, ReadOptions{});
    ASSERT_EQ(m.cells.size(), whole.cells.size());
    for (int x : {50, 58, 59, 60, 69})
        EXPECT_EQ(valueAt(m, glm::ivec3(x, 50, 50), 0), valueAt(whole, glm::ivec3(x, 50, 50), 0)) << x;
    EXPECT_EQ(computeFieldStats(m, m.defaultField()).volumeWeightedMean,
              computeFieldStats(whole, whole.defaultField()).volumeWeightedMean);
}
