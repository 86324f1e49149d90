// RAMSES reader: the three real outputs in shared/data/amr read with the oct and leaf counts per
// level and the density ranges and sums of FORMATS.md section 6 (computed there by an independent
// reader and, for the 3-D one, by yt); the leaves must tile the domain exactly. Hostile copies of
// the real files (truncated, mismatched record markers, huge counts, a missing or inconsistent
// domain file) must each give one line naming the file.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "amr/model.h"
#include "amr/readers.h"
#include "ramses_synthetic.h"
#include "test_data.h"

namespace fs = std::filesystem;
using namespace amrvk;
using namespace amrvk::amr;
using namespace amrvk::test;

namespace {

const char* kGalaxy = "ramses_galaxy_3d/output_00010";
const char* kSedov = "ramses_sedov_2d/output_00002";
const char* kMultimat = "ramses_multimat_2d/output_00001";

struct Sums {
    double min = std::numeric_limits<double>::infinity(), max = -min, sum = 0;
};
Sums sums(const Field& f) {
    Sums s;
    for (float v : f.values) {
        s.min = std::min(s.min, double(v));
        s.max = std::max(s.max, double(v));
        s.sum += double(v);
    }
    return s;
}

std::string attribute(const Model& m, const std::string& key) {
    for (const auto& [k, v] : m.attributes)
        if (k == key) return v;
    return "(absent)";
}

// Sum of leaf volumes (3-D) or areas (2-D) in finest-cell units: the leaves tile the domain
// exactly when this equals the domain's size, and validate() finds no overlap.
double covered(const Model& m, bool planar) {
    double total = 0;
    for (const Cell& c : m.cells) {
        const double w = double(cellWidth(c.level));
        total += planar ? w * w : w * w * w;
    }
    return total;
}

// Offsets of the first records of a Fortran sequential file (each: leading length).
std::vector<size_t> recordOffsets(const std::string& bytes, size_t count) {
    std::vector<size_t> out;
    size_t at = 0;
    while (out.size() < count && at + 4 <= bytes.size()) {
        out.push_back(at);
        int32_t len = 0;
        std::memcpy(&len, bytes.data() + at, 4);
        at += 8 + size_t(len);
    }
    return out;
}

void putInt(std::string& bytes, size_t at, int32_t v) { std::memcpy(bytes.data() + at, &v, 4); }

// A writable copy of a sample output under the test's scratch directory.
fs::path copyOutput(const char* relative) {
    const fs::path src = dataDir() / relative;
    const fs::path dst = scratchDir() / src.filename();
    fs::create_directories(dst);
    for (const auto& e : fs::directory_iterator(src)) writeAll(dst / e.path().filename(), readAll(e.path()));
    for (const auto& e : fs::directory_iterator(dst))
        fs::permissions(e.path(), fs::perms::owner_all, fs::perm_options::add);
    return dst;
}

// Writes a synthetic output to DIR/output_00001 and returns that directory.
fs::path writeSynthetic(const fs::path& dir, const ramses::Synthetic& s) {
    const fs::path out = dir / "output_00001";
    fs::create_directories(out);
    for (const auto& [name, bytes] : ramses::outputFiles(s)) writeAll(out / name, bytes);
    return out;
}

// Every leaf of a synthetic output: 2^ndim - 1 leaves of RAMSES level 1 (amrvk level 1) and 2^ndim
// of level 2 (amrvk level 0), each with synthValue of its centre for every variable.
void checkSynthetic(const Model& m, const ramses::Synthetic& s) {
    const int cells = 1 << s.ndim;
    ASSERT_EQ(m.cellCount(), size_t(2 * cells - 1));
    ASSERT_EQ(m.fields.size(), size_t(ramses::nvarOf(s)));
    validate(m);
    EXPECT_EQ(covered(m, s.ndim == 2), s.ndim == 3 ? 64.0 : 16.0);
    for (size_t i = 0; i < m.cellCount(); ++i) {
        const Cell& c = m.cells[i];
        const double w = double(cellWidth(c.level));
        glm::dvec3 centre = (glm::dvec3(c.lower) + w / 2) / 4.0;  // 4 finest cells per coarse cell
        if (s.ndim == 2) {
            EXPECT_EQ(c.lower.z, 0);
            centre.z = 0;
        }
        for (int v = 0; v < ramses::nvarOf(s); ++v)
            EXPECT_NEAR(m.fields[size_t(v)].values[i], ramses::synthValue(v, centre), 1e-3)
                << "cell " << describeCell(c) << " variable " << v;
    }
    // World: boxlen per coarse cell from 0.
    EXPECT_DOUBLE_EQ(m.voxelToWorld.toWorld(glm::dvec3(4)).x, s.boxlen);
    EXPECT_EQ(m.voxelToWorld.origin, glm::dvec3(0.0));
}

}  // namespace

TEST(RamsesReader, SyntheticOutputsOfEveryLayoutReadTheirCellValues) {
    using S = ramses::Synthetic;
    int n = 0;
    for (int ndim : {2, 3})
        for (int ncpu : {1, 2})
            for (int realBytes : {4, 8})
                for (bool bisection : {false, true})
                    for (bool boundaries : {false, true})
                        for (S::Descriptor d : {S::None, S::Old, S::New}) {
                            S s{.ndim = ndim,
                                .ncpu = ncpu,
                                .realBytes = realBytes,
                                .bisection = bisection,
                                .boundaries = boundaries,
                                .boxlen = 2.5,
                                .descriptor = d};
                            SCOPED_TRACE(testing::Message() << "ndim " << ndim << " ncpu " << ncpu << " reals "
                                                            << realBytes << " bisection " << bisection << " boundaries "
                                                            << boundaries << " descriptor " << d);
                            const fs::path dir = writeSynthetic(scratchDir() / std::to_string(n++), s);
                            const Model m = readModel(dir, {});
                            checkSynthetic(m, s);
                            EXPECT_EQ(m.availableFields[0], d == S::None ? "density" : "rho");
                        }
}

TEST(RamsesReader, Galaxy3dEightDomainsIsTheUniform64CubeOfFormatsMd) {
    AMRVK_REQUIRE_DATA(kGalaxy);
    const Model m = readModel(dataDir() / kGalaxy, {});
    EXPECT_EQ(m.format, "ramses");
    EXPECT_EQ(m.availableFields,
              (std::vector<std::string>{"density", "velocity_x", "velocity_y", "velocity_z", "pressure", "scalar_00"}));
    ASSERT_EQ(m.fields.size(), 6u);
    EXPECT_EQ(attribute(m, "octsPerLevel"), "1 8 64 512 4096 32768");
    EXPECT_EQ(attribute(m, "domains"), "8");
    const ModelSummary s = summarize(m);
    EXPECT_EQ(s.cellsPerLevel, std::vector<uint64_t>{262144});  // all leaves on RAMSES level 6
    EXPECT_EQ(s.bounds.lower, glm::i64vec3(0));
    EXPECT_EQ(s.bounds.upper, glm::i64vec3(64));
    validate(m);                                   // no two leaves overlap ...
    EXPECT_EQ(covered(m, false), 64.0 * 64 * 64);  // ... and they fill the domain
    const Sums d = sums(m.field("density"));
    EXPECT_NEAR(d.min, 0.0183587, 1e-7);
    EXPECT_NEAR(d.max, 217.156, 1e-3);
    EXPECT_NEAR(d.sum, 484588.48476868507, 484588.48 * 1e-6);  // float values, double sum
    // World: the unit box (boxlen 1, code units).
    EXPECT_EQ(m.voxelToWorld.toWorld(glm::dvec3(64)), glm::dvec3(1.0));
    EXPECT_EQ(m.voxelToWorld.toWorld(glm::dvec3(0)), glm::dvec3(0.0));
}

// Units (issue 33, point 5) from the info file: unit_d 1.66e-24 g/cm^3, unit_l 3.0857e21 cm and
// unit_t 3.1557e13 s, so a code velocity is unit_l / unit_t cm/s and a code pressure unit_d times
// its square; a passive scalar is not known. tests/python/test_units_yt.py checks them against yt.
TEST(RamsesReader, FieldsCarryTheirCodeUnitsFromTheInfoFile) {
    AMRVK_REQUIRE_DATA(kGalaxy);
    const Model m = readModel(dataDir() / kGalaxy, {.fields = {"density", "velocity_y", "pressure", "scalar_00"}});
    EXPECT_EQ(m.field("density").units, "code units (1 = 1.66e-24 g/cm^3)");
    EXPECT_EQ(m.field("velocity_y").units, "code units (1 = 9.7782e+07 cm/s)");
    EXPECT_EQ(m.field("pressure").units, "code units (1 = 1.5872e-08 dyn/cm^2)");
    EXPECT_EQ(m.field("scalar_00").units, "");
}

TEST(RamsesReader, Sedov2dOldFormatHasAdaptiveLeavesOnSevenLevels) {
    AMRVK_REQUIRE_DATA(kSedov);
    const Model m = readModel(dataDir() / kSedov / "info_00002.txt", {});
    // No hydro_file_descriptor.txt: RAMSES's default names for 2-D, nvar 5.
    EXPECT_EQ(m.availableFields,
              (std::vector<std::string>{"density", "velocity_x", "velocity_y", "pressure", "scalar_00"}));
    EXPECT_EQ(attribute(m, "octsPerLevel"), "1 4 16 64 177 425 917 1832 3311 4652");
    EXPECT_EQ(attribute(m, "dimensions"), "2");
    const ModelSummary s = summarize(m);
    // RAMSES levels 10..4 are amrvk levels 0..6.
    EXPECT_EQ(s.cellsPerLevel, (std::vector<uint64_t>{18608, 8592, 4017, 1836, 783, 283, 79}));
    EXPECT_EQ(m.cellCount(), 34198u);
    validate(m);
    EXPECT_EQ(covered(m, true), 1024.0 * 1024);  // the leaves tile the unit square
    // A one-cell slab: every cell starts at z = 0 and is as deep as it is wide.
    for (const Cell& c : m.cells) ASSERT_EQ(c.lower.z, 0);
    EXPECT_EQ(s.bounds.upper, glm::i64vec3(1024, 1024, 64));
    const Sums d = sums(m.defaultField());
    EXPECT_EQ(m.defaultField().name, "density");
    EXPECT_NEAR(d.min, 0.017063, 1e-6);
    EXPECT_NEAR(d.max, 19.1204, 1e-4);
}

TEST(RamsesReader, Multimat2dNamesItsVariablesAndRefinesAtInterfaces) {
    AMRVK_REQUIRE_DATA(kMultimat);
    ReadOptions o;
    o.fields = {"density", "vol_frac_01"};
    const Model m = readModel(dataDir() / kMultimat, o);
    EXPECT_EQ(m.availableFields.size(), 8u);
    EXPECT_EQ(m.availableFields.back(), "true_dens_02");
    ASSERT_EQ(m.fields.size(), 2u);
    EXPECT_EQ(m.fields[1].name, "vol_frac_01");
    EXPECT_EQ(attribute(m, "octsPerLevel"), "1 4 16 64 252 738 1162");
    const ModelSummary s = summarize(m);
    EXPECT_EQ(s.cellsPerLevel, (std::vector<uint64_t>{4648, 1790, 270, 4}));  // RAMSES levels 7..4
    validate(m);
    EXPECT_EQ(covered(m, true), 128.0 * 128);
    const Sums d = sums(m.fields[0]);
    EXPECT_NEAR(d.min, 1e-10, 1e-15);
    EXPECT_NEAR(d.max, 8.89999, 1e-5);
    const Sums f = sums(m.fields[1]);  // a volume fraction
    EXPECT_GE(f.min, 0.0);
    EXPECT_LE(f.max, 1.0 + 1e-6);

    o.fields = {"Density"};
    expectError([&] { readModel(dataDir() / kMultimat, o); }, {"unknown field 'Density'", "true_dens_02"});
}

TEST(RamsesReader, LogScaleTakesLog10OfEachLeaf) {
    AMRVK_REQUIRE_DATA(kGalaxy);
    ReadOptions o;
    o.fields = {"density"};
    const Model linear = readModel(dataDir() / kGalaxy, o);
    o.scale = FieldScale::Log;
    o.format = "ramses";
    const Model logged = readModel(dataDir() / kGalaxy, o);
    ASSERT_EQ(logged.cellCount(), linear.cellCount());
    for (size_t i = 0; i < linear.cellCount(); i += 997)
        ASSERT_NEAR(logged.fields[0].values[i], std::log10(double(linear.fields[0].values[i])), 1e-6);
    EXPECT_NEAR(sums(logged.fields[0]).min, std::log10(0.0183587), 1e-5);
}

TEST(RamsesReader, LogScaleWithoutAFieldSkipsVariablesWithNoPositiveValue) {
    AMRVK_REQUIRE_DATA(kSedov);
    ReadOptions o;
    o.scale = FieldScale::Log;
    const Model m = readModel(dataDir() / kSedov, o);  // scalar_00 is 0 everywhere
    std::vector<std::string> loaded;
    for (const Field& f : m.fields) loaded.push_back(f.name);
    EXPECT_EQ(loaded, (std::vector<std::string>{"density", "velocity_x", "velocity_y", "pressure"}));
    expectContains(attribute(m, "logSkipped"), "scalar_00");
    EXPECT_NEAR(sums(m.field("density")).max, std::log10(19.1204), 1e-5);
    // Named, it has no logarithm: one line naming it.
    o.fields = {"density", "scalar_00"};
    expectError([&] { readModel(dataDir() / kSedov, o); }, {"field 'scalar_00' has no positive value"});
    // With a floor every field is logged.
    o.logFloor = 1e-3;
    EXPECT_EQ(sums(readModel(dataDir() / kSedov, o).field("scalar_00")).max, -3.0);
}

TEST(RamsesReader, DetectsTheDirectoryAndItsInfoFile) {
    AMRVK_REQUIRE_DATA(kSedov);
    EXPECT_EQ(detectFormat(dataDir() / kSedov), "ramses");
    EXPECT_EQ(detectFormat(dataDir() / kSedov / "info_00002.txt"), "ramses");
}

TEST(RamsesReader, HostileFilesGiveOneLineNamingTheFile) {
    AMRVK_REQUIRE_DATA(kMultimat);
    const fs::path dir = copyOutput(kMultimat);
    const fs::path amrPath = dir / "amr_00001.out00001", hydroPath = dir / "hydro_00001.out00001";
    const std::string amr = readAll(amrPath), hydro = readAll(hydroPath);
    auto expectRead = [&](std::initializer_list<std::string> parts) {
        expectError([&] { readModel(dir, {}); }, parts);
    };
    const std::vector<size_t> rec = recordOffsets(amr, 40);
    ASSERT_EQ(rec.size(), 40u);

    // Truncated in the middle of the octs.
    writeAll(amrPath, amr.substr(0, amr.size() / 2));
    expectRead({amrPath.string(), "bytes follow (truncated file?)"});
    // Trailing marker of the first record (ncpu) differs from its leading one.
    std::string bad = amr;
    putInt(bad, 8, 5);
    writeAll(amrPath, bad);
    expectRead({amrPath.string(), "'ncpu'", "leading length 4 differs from trailing length 5"});
    // A leading marker far beyond the file.
    bad = amr;
    putInt(bad, rec[7], 0x7ffffff0);
    writeAll(amrPath, bad);
    expectRead({amrPath.string(), "'boxlen'", "has length 2147483632"});
    // A huge oct count (numbl, record 21): the next record's size is checked before any allocation.
    bad = amr;
    putInt(bad, rec[21] + 4, 0x7fffffff);
    writeAll(amrPath, bad);
    expectRead({amrPath.string(), "'ind_grid'", "expected 8589934588"});
    // Huge coarse grid: nx ny nz of 2^30 - 1 each, so the coarse records' product overflows nothing
    // but no file holds them.
    bad = amr;
    for (int a = 0; a < 3; ++a) putInt(bad, rec[2] + 4 + size_t(4 * a), (1 << 30) - 1);
    writeAll(amrPath, bad);
    expectRead({amrPath.string()});
    // A negative record length (big-endian or subrecords).
    bad = amr;
    putInt(bad, 0, -4);
    writeAll(amrPath, bad);
    expectRead({amrPath.string(), "negative"});
    writeAll(amrPath, amr);

    // The hydro file's oct counts must match the AMR file's.
    const std::vector<size_t> hrec = recordOffsets(hydro, 8);
    bad = hydro;
    putInt(bad, hrec[7] + 4, 1000);  // ncache of level 1, domain 1
    writeAll(hydroPath, bad);
    expectRead({hydroPath.string(), "1000 octs on level 1"});
    writeAll(hydroPath, hydro.substr(0, hydro.size() - 3));
    expectRead({hydroPath.string()});
    writeAll(hydroPath, hydro);

    // The descriptor must name nvar variables.
    const std::string descriptor = readAll(dir / "hydro_file_descriptor.txt");
    writeAll(dir / "hydro_file_descriptor.txt", descriptor + " 9, extra, d\n");
    expectRead({"hydro_file_descriptor.txt", "more than the 8 variables"});
    std::string twice = descriptor;
    twice.replace(twice.find("velocity_y"), 10, "velocity_x");
    writeAll(dir / "hydro_file_descriptor.txt", twice);
    expectRead({"hydro_file_descriptor.txt", "variable 'velocity_x' is named twice"});
    writeAll(dir / "hydro_file_descriptor.txt", descriptor);

    // info_NNNNN.txt: ncpu out of range.
    const std::string info = readAll(dir / "info_00001.txt");
    std::string badInfo = info;
    badInfo.replace(badInfo.find("ncpu        =          1"), 25, "ncpu        =          0");
    writeAll(dir / "info_00001.txt", badInfo);
    expectRead({"info_00001.txt", "ncpu"});
    // A huge level count: refused by the AMR file's header before anything is sized by it.
    badInfo = info;
    badInfo.replace(badInfo.find("levelmax    =          7"), 24, "levelmax    = 2147483647");
    writeAll(dir / "info_00001.txt", badInfo);
    expectRead({amrPath.string(), "nlevelmax 7 differs from 2147483647 in info_00001.txt"});
    writeAll(dir / "info_00001.txt", info);

    readModel(dir, {});  // restored: reads again
}

TEST(RamsesReader, MissingOrInconsistentDomainFilesAreRefused) {
    AMRVK_REQUIRE_DATA(kGalaxy);
    const fs::path src = dataDir() / kGalaxy;
    const fs::path dir = scratchDir() / "output_00010";
    fs::create_directories(dir);
    for (const auto& e : fs::directory_iterator(src)) fs::create_symlink(e.path(), dir / e.path().filename());

    fs::remove(dir / "hydro_00010.out00003");
    expectError([&] { readModel(dir, {}); },
                {(dir / "hydro_00010.out00003").string(), "no such file", "lists 8 domains"});
    fs::create_symlink(src / "hydro_00010.out00003", dir / "hydro_00010.out00003");

    // Domain 5 claims another level count, then another dimension.
    const fs::path five = dir / "amr_00010.out00005";
    std::string bytes = readAll(src / "amr_00010.out00005");
    fs::remove(five);
    std::string bad = bytes;
    putInt(bad, 48, 7);  // nlevelmax (record 3)
    writeAll(five, bad);
    expectError([&] { readModel(dir, {}); }, {five.string(), "nlevelmax 7 differs from 6", "info_00010.txt"});
    bad = bytes;
    putInt(bad, 16, 2);  // ndim (record 1)
    writeAll(five, bad);
    expectError([&] { readModel(dir, {}); }, {five.string(), "ndim 2 differs from 3"});
    // Another domain's copy in its place: its octs are not where domain 5's are.
    writeAll(five, readAll(src / "amr_00010.out00004"));
    expectError([&] { readModel(dir, {}); }, {"hydro_00010.out00005"});
}
