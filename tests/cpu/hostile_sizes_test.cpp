// Hostile input, round 3 (issue 34, docs/fuzzing.md): every reader with crafted sizes. One valid
// data set per format (ExaBrick and raw written here, AMReX and RAMSES from the synthetic
// writers, Enzo and Chombo copies of the real outputs) with one size or count rewritten to 0, 1,
// 2^31 - 1, 2^32, 2^63, -1, or a value inconsistent with another header. Each case must end in
// the model (where the size is legal) or in one amrvk::Error of one line naming the file; never
// another exception type, a crash, or an allocation the input did not pay for (the memory budget
// is 1 GiB here and the address space 6 GiB, so an unchecked size fails the case instead of
// swamping the machine).
#include <gtest/gtest.h>
#include <hdf5.h>
#include <sys/resource.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <typeinfo>
#include <vector>

#include "amr/model.h"
#include "amr/readers.h"
#include "amrex_synthetic.h"
#include "core/checked_size.h"
#include "core/error.h"
#include "ramses_synthetic.h"
#include "test_data.h"

namespace fs = std::filesystem;
using namespace amrvk;
using namespace amrvk::test;

namespace {

constexpr const char* kEnzo = "enzo_tiny_cosmology/DD0018";
constexpr const char* kChombo = "chombo_mushy_layer_2d/plt000100.2d.hdf5";

// A case writes its files into `dir` and returns what to read, with options.
struct Input {
    fs::path path;
    amr::ReadOptions options;
};
struct SizeCase {
    std::string name;
    std::function<Input(const fs::path& dir)> make;
    std::string expect;           // a fragment of the error; "" = the read must succeed
    const char* needs = nullptr;  // real data set the case copies (skipped where absent)
};
void PrintTo(const SizeCase& c, std::ostream* os) { *os << c.name; }

// ---- ExaBrick ----

struct Cell4 {
    int32_t x, y, z, level;
};
const std::vector<Cell4> kFive = {{0, 0, 0, 1}, {2, 0, 0, 0}, {3, 0, 0, 0}, {2, 1, 0, 0}, {3, 1, 0, 0}};

Input exabrick(const fs::path& dir, const std::vector<Cell4>& cells, size_t scalars) {
    writeAll(dir / "c.cells", std::string(reinterpret_cast<const char*>(cells.data()), cells.size() * sizeof(Cell4)));
    const std::vector<float> v(scalars, 1.0f);
    writeAll(dir / "c.scalars", std::string(reinterpret_cast<const char*>(v.data()), v.size() * 4));
    return {dir / "c.cells", {}};
}
// The file's length set to `bytes` (sparse: nothing is written).
void resize(const fs::path& p, uintmax_t bytes) { fs::resize_file(p, bytes); }

SizeCase exaCells(std::string name, std::vector<Cell4> cells, size_t scalars, std::string expect) {
    return {std::move(name), [=](const fs::path& d) { return exabrick(d, cells, scalars); }, std::move(expect)};
}
SizeCase exaLevel(std::string name, int32_t level) {
    return exaCells(std::move(name), {{0, 0, 0, level}}, 1, "c.cells");
}

// ---- raw ----

SizeCase raw(std::string name, std::string file, uintmax_t bytes, glm::ivec3 dims, std::string type,
             std::string expect) {
    return {std::move(name),
            [=](const fs::path& d) {
                writeAll(d / file, "");
                resize(d / file, bytes);
                Input in{d / file, {}};
                in.options.format = "raw";
                in.options.rawDims = dims;
                in.options.rawType = type;
                return in;
            },
            std::move(expect)};
}

// ---- AMReX: the synthetic 3-D plotfile, one line of one file replaced ----

std::string withLine(const std::string& text, size_t line, const std::string& value) {
    size_t at = 0;
    for (size_t i = 0; i < line; ++i) at = text.find('\n', at) + 1;
    return text.substr(0, at) + value + text.substr(text.find('\n', at));
}

SizeCase amrex(std::string name, std::string file, size_t line, std::string value, std::string expect) {
    return {std::move(name),
            [=](const fs::path& d) {
                const fs::path root = d / "plt";
                for (auto& [rel, bytes] : amrvk::test::amrex::plotfileFiles({})) {
                    fs::create_directories((root / rel).parent_path());
                    writeAll(root / rel, rel == file ? withLine(bytes, line, value) : bytes);
                }
                return Input{root, {}};
            },
            std::move(expect)};
}

// ---- RAMSES: the synthetic 3-D output, one Fortran record or info line rewritten ----

// The int32 at `index` inside record `record` of a Fortran unformatted file.
void patchRecord(std::string& bytes, int record, size_t index, int32_t value) {
    size_t at = 0;
    for (int r = 0; r < record; ++r) {
        int32_t n;
        std::memcpy(&n, bytes.data() + at, 4);
        at += size_t(n) + 8;
    }
    std::memcpy(bytes.data() + at + 4 + 4 * index, &value, 4);
}
// The length marker in front of (or behind) record `record`.
void patchMarker(std::string& bytes, int record, bool behind, int32_t value) {
    size_t at = 0;
    for (int r = 0; r < record; ++r) {
        int32_t n;
        std::memcpy(&n, bytes.data() + at, 4);
        at += size_t(n) + 8;
    }
    int32_t n;
    std::memcpy(&n, bytes.data() + at, 4);
    std::memcpy(bytes.data() + at + (behind ? size_t(n) + 4 : 0), &value, 4);
}

SizeCase ramses(std::string name, std::function<void(std::map<std::string, std::string>&)> edit, std::string expect) {
    return {std::move(name),
            [=](const fs::path& d) {
                const fs::path root = d / "output_00001";
                fs::create_directories(root);
                auto files = amrvk::test::ramses::outputFiles({});
                edit(files);
                for (auto& [rel, bytes] : files) writeAll(root / rel, bytes);
                return Input{root, {}};
            },
            std::move(expect)};
}
SizeCase ramsesAmr(std::string name, int record, size_t index, int32_t value, std::string expect) {
    return ramses(
        std::move(name), [=](auto& f) { patchRecord(f["amr_00001.out00001"], record, index, value); },
        std::move(expect));
}
SizeCase ramsesInfo(std::string name, std::string from, std::string to, std::string expect) {
    return ramses(
        std::move(name),
        [=](auto& f) {
            std::string& t = f["info_00001.txt"];
            t.replace(t.find(from), from.size(), to);
        },
        std::move(expect));
}

// ---- Enzo: a copy of DD0018's text files (the grid files linked), one value replaced ----

SizeCase enzo(std::string name, std::string file, std::string from, std::string to, std::string expect) {
    return {std::move(name),
            [=](const fs::path& d) {
                const fs::path real = dataDir() / kEnzo;
                fs::create_directories(d / "DD0018");
                for (const char* n : {"DD0018.cpu0000", "DD0018.cpu0001"})
                    fs::create_symlink(real / n, d / "DD0018" / n);
                for (const char* n : {"DD0018", "DD0018.hierarchy"}) {
                    std::string text = readAll(real / n);
                    if (n == file) {
                        const size_t at = text.find(from);
                        EXPECT_NE(at, std::string::npos) << from;
                        if (at != std::string::npos) text.replace(at, from.size(), to);
                    }
                    writeAll(d / "DD0018" / n, text);
                }
                return Input{d / "DD0018" / "DD0018", {}};
            },
            std::move(expect), kEnzo};
}

// ---- Chombo: a copy of plt000100 with one attribute or dataset value rewritten through HDF5 ----

void writeIntAttribute(hid_t file, const char* group, const char* name, int value) {
    const hid_t g = H5Gopen2(file, group, H5P_DEFAULT);
    const hid_t a = H5Aopen(g, name, H5P_DEFAULT);
    EXPECT_GE(H5Awrite(a, H5T_NATIVE_INT, &value), 0) << group << " " << name;
    H5Aclose(a);
    H5Gclose(g);
}
void writeFirstInt64(hid_t file, const char* dataset, int64_t value) {
    const hid_t d = H5Dopen2(file, dataset, H5P_DEFAULT);
    const hid_t space = H5Dget_space(d);
    std::vector<int64_t> v(size_t(H5Sget_simple_extent_npoints(space)));
    EXPECT_GE(H5Dread(d, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), 0);
    v[v.size() > 1 ? 1 : 0] = value;  // the second box's start (the first is always 0)
    EXPECT_GE(H5Dwrite(d, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), 0);
    H5Sclose(space);
    H5Dclose(d);
}
SizeCase chombo(std::string name, std::function<void(hid_t)> edit, std::string expect) {
    return {std::move(name),
            [=](const fs::path& d) {
                const fs::path copy = d / "plt000100.2d.hdf5";
                writeAll(copy, readAll(dataDir() / kChombo));
                const hid_t f = H5Fopen(copy.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
                EXPECT_GE(f, 0);
                edit(f);
                H5Fclose(f);
                return Input{copy, {}};
            },
            std::move(expect), kChombo};
}
SizeCase chomboInt(std::string name, const char* group, const char* attribute, int value, std::string expect) {
    return chombo(
        std::move(name), [=](hid_t f) { writeIntAttribute(f, group, attribute, value); }, std::move(expect));
}

constexpr int32_t kIntMax = INT32_MAX;
constexpr uintmax_t k4G = uintmax_t(1) << 32;

std::vector<SizeCase> cases() {
    std::vector<SizeCase> c;
    // ExaBrick: record counts, levels and coordinates at the limits, sparse files of 4 GiB.
    c.push_back(exaCells("ExaBrickNoCells", {}, 0, "c.cells"));
    c.push_back(exaCells("ExaBrickOneCell", {{0, 0, 0, 0}}, 1, ""));
    c.push_back(exaCells("ExaBrickScalarsShort", kFive, 4, "c.scalars"));
    c.push_back(exaCells("ExaBrickScalarsLong", kFive, 6, "c.scalars"));
    c.push_back(exaCells("ExaBrickScalarsEmpty", kFive, 0, "c.scalars"));
    c.push_back({"ExaBrickCells15Bytes",
                 [](const fs::path& d) {
                     Input in = exabrick(d, kFive, 5);
                     resize(d / "c.cells", 15);
                     return in;
                 },
                 "c.cells"});
    c.push_back({"ExaBrickCellsSparse4GiB",
                 [](const fs::path& d) {
                     Input in = exabrick(d, kFive, 5);
                     resize(d / "c.cells", k4G);
                     return in;
                 },
                 "c.scalars: 5 values but c.cells has 268435456 cells"});
    c.push_back({"ExaBrickBothSparse2To28Cells",  // 5 GiB of cells and values: over the budget before reading
                 [](const fs::path& d) {
                     Input in = exabrick(d, kFive, 5);
                     resize(d / "c.cells", k4G);
                     resize(d / "c.scalars", k4G / 4);
                     return in;
                 },
                 "memory budget"});
    c.push_back(exaLevel("ExaBrickLevelMinus1", -1));
    c.push_back(exaLevel("ExaBrickLevel31", 31));
    c.push_back(exaLevel("ExaBrickLevel32", 32));
    c.push_back(exaLevel("ExaBrickLevelIntMax", kIntMax));
    c.push_back(exaCells("ExaBrickCoordIntMax", {{kIntMax, 0, 0, 0}}, 1, "c.cells"));
    c.push_back(
        exaCells("ExaBrickCoordIntMin", {{0, INT32_MIN, 0, 0}}, 1, ""));  // the span is checked later (makeVolume)
    c.push_back(exaCells("ExaBrickCoordMinus1", {{0, 0, -1, 0}}, 1, ""));
    c.push_back(exaCells("ExaBrickCoordOffLevelGrid", {{1, 0, 0, 1}}, 1, "c.cells"));
    // Raw: dims of 0, 1, 2^31 - 1 and products past 2^63 bytes, file sizes of 0, 1 too many, 4 GiB.
    c.push_back(raw("RawOneVoxel", "v.raw", 1, {1, 1, 1}, "uint8", ""));
    c.push_back(raw("RawEmptyFile", "v.raw", 0, {1, 1, 1}, "uint8", "v.raw"));
    c.push_back(raw("RawOneByteTooMany", "v.raw", 2, {1, 1, 1}, "uint8", "v.raw"));
    c.push_back(raw("RawDimsZero", "v.raw", 1, {0, 1, 1}, "uint8", "raw dimensions 0x1x1 must all be positive"));
    c.push_back(raw("RawDimsNegative", "v.raw", 1, {-1, 1, 1}, "uint8", "raw dimensions -1x1x1 must all be positive"));
    c.push_back(
        raw("RawDimsIntMax", "v.raw", 1, {kIntMax, 1, 1}, "uint8", "raw dimensions 2147483647x1x1 exceed 2^30"));
    c.push_back(raw("RawDimsAtLimitProductPast2To63", "v.raw", 8, {1 << 20, 1 << 20, 1 << 20}, "float64", "v.raw"));
    c.push_back(raw("RawSparse4GiBMatchingDims", "v.raw", k4G, {1024, 1024, 4096}, "uint8", "memory budget"));
    c.push_back(raw("RawNameDimsIntMax", "v_2147483647x1x1_uint8.raw", 1, {0, 0, 0}, "", "v_2147483647x1x1_uint8.raw"));
    c.push_back(raw("RawNameDims2To64", "v_18446744073709551616x1x1_uint8.raw", 1, {0, 0, 0}, "",
                    "v_18446744073709551616x1x1_uint8.raw"));
    c.push_back(raw("RawNameDimsZero", "v_0x0x0_uint8.raw", 0, {0, 0, 0}, "", "v_0x0x0_uint8.raw"));
    // AMReX: Header lines 1 (components), 4 (dimension), 6 (finest level), 9 (ratio), 10 (domain),
    // 16 (level 0: grids); Cell_H line 4 (box array size), 8 (FabOnDisk offset); the FAB header.
    const std::string H = "Header", C = "Level_0/Cell_H", D = "Level_0/Cell_D_00000";
    c.push_back(amrex("AmrexComponentsZero", H, 1, "0", "Header"));
    c.push_back(amrex("AmrexComponentsIntMax", H, 1, "2147483647", "Header"));
    c.push_back(amrex("AmrexComponents2To63", H, 1, "9223372036854775808", "Header"));
    c.push_back(amrex("AmrexComponentsMinus1", H, 1, "-1", "Header"));
    c.push_back(amrex("AmrexDimensionZero", H, 4, "0", "Header"));
    c.push_back(amrex("AmrexDimension2To32", H, 4, "4294967296", "Header"));
    c.push_back(amrex("AmrexFinestLevelMinus1", H, 6, "-1", "Header"));
    c.push_back(amrex("AmrexFinestLevelIntMax", H, 6, "2147483647", "Header"));
    c.push_back(amrex("AmrexRatioZero", H, 9, "0 ", "Header"));
    c.push_back(amrex("AmrexRatioIntMax", H, 9, "2147483647 ", "Header"));
    c.push_back(
        amrex("AmrexDomainIntMax", H, 10, "((0,0,0) (2147483647,3,3) (0,0,0)) ((0,0,0) (7,7,7) (0,0,0)) ", "Header"));
    c.push_back(
        amrex("AmrexDomainIntMin", H, 10, "((-2147483648,0,0) (3,3,3) (0,0,0)) ((0,0,0) (7,7,7) (0,0,0)) ", "Header"));
    c.push_back(amrex("AmrexGridsZero", H, 16, "0 0 0.5", "Header: line 17: level 0 has no boxes"));
    c.push_back(amrex("AmrexGridsIntMax", H, 16, "0 2147483647 0.5", "Header"));
    c.push_back(amrex("AmrexGrids2To32", H, 16, "0 4294967296 0.5", "Header"));
    c.push_back(amrex("AmrexBoxArrayIntMax", C, 4, "(2147483647 0", "Cell_H"));
    c.push_back(amrex("AmrexBoxArrayMinus1", C, 4, "(-1 0", "Cell_H"));
    c.push_back(amrex("AmrexFabsIntMax", C, 7, "2147483647", "Cell_H"));
    c.push_back(amrex("AmrexFabOffset2To63", C, 8, "FabOnDisk: Cell_D_00000 9223372036854775807", "Cell_D_00000"));
    c.push_back(amrex("AmrexFabOffset2To32", C, 8, "FabOnDisk: Cell_D_00000 4294967296", "Cell_D_00000"));
    c.push_back(amrex("AmrexFabOffsetMinus1", C, 8, "FabOnDisk: Cell_D_00000 -1", "Cell_H"));
    c.push_back(amrex("AmrexFabComponentsIntMax", D, 0,
                      "FAB ((8, (64 11 52 0 1 12 0 1023)),(8, (8 7 6 5 4 3 2 1)))((0,0,0) (3,3,3) (0,0,0)) 2147483647",
                      "Cell_D_00000"));
    c.push_back(amrex("AmrexFabRealBytesIntMax", D, 0,
                      "FAB ((2147483647, (64 11 52 0 1 12 0 1023)),(8, (8 7 6 5 4 3 2 1)))((0,0,0) (3,3,3) (0,0,0)) 2",
                      "Cell_D_00000"));
    c.push_back(amrex("AmrexFabBoxIntMax", D, 0,
                      "FAB ((8, (64 11 52 0 1 12 0 1023)),(8, (8 7 6 5 4 3 2 1)))((0,0,0) (2147483647,3,3) (0,0,0)) 2",
                      "Cell_D_00000"));
    // RAMSES amr file records: 0 ncpu, 1 ndim, 2 nx ny nz, 3 nlevelmax, 4 ngridmax; their markers.
    c.push_back(ramsesAmr("RamsesNcpuZero", 0, 0, 0, "amr_00001.out00001"));
    c.push_back(ramsesAmr("RamsesNcpuIntMax", 0, 0, kIntMax, "amr_00001.out00001"));
    c.push_back(ramsesAmr("RamsesNdimZero", 1, 0, 0, "amr_00001.out00001"));
    c.push_back(ramsesAmr("RamsesNdimMinus1", 1, 0, -1, "amr_00001.out00001"));
    c.push_back(ramsesAmr("RamsesNxIntMax", 2, 0, kIntMax, "amr_00001.out00001"));
    c.push_back(ramsesAmr("RamsesNxZero", 2, 1, 0, "amr_00001.out00001"));
    c.push_back(ramsesAmr("RamsesNlevelmaxIntMax", 3, 0, kIntMax, "amr_00001.out00001"));
    c.push_back(ramsesAmr("RamsesNlevelmaxMinus1", 3, 0, -1, "amr_00001.out00001"));
    c.push_back(ramsesAmr("RamsesNgridmaxIntMax", 4, 0, kIntMax, ""));  // a capacity: nothing is sized by it
    c.push_back(ramses(
        "RamsesMarkerIntMax", [](auto& f) { patchMarker(f["amr_00001.out00001"], 0, false, kIntMax); },
        "amr_00001.out00001"));
    c.push_back(ramses(
        "RamsesMarkerMinus1", [](auto& f) { patchMarker(f["amr_00001.out00001"], 1, false, -1); },
        "amr_00001.out00001"));
    c.push_back(ramses(
        "RamsesMarkersDisagree", [](auto& f) { patchMarker(f["amr_00001.out00001"], 2, true, 8); },
        "amr_00001.out00001"));
    c.push_back(ramses(
        "RamsesHydroNvarIntMax", [](auto& f) { patchRecord(f["hydro_00001.out00001"], 1, 0, kIntMax); },
        "hydro_00001.out00001"));
    c.push_back(ramses(
        "RamsesAmrFileEmpty", [](auto& f) { f["amr_00001.out00001"].clear(); }, "amr_00001.out00001"));
    c.push_back(ramsesInfo("RamsesInfoNcpuIntMax", "ncpu        =          1", "ncpu        =          2147483647",
                           "info_00001.txt"));
    c.push_back(ramsesInfo("RamsesInfoNcpu2To63", "ncpu        =          1", "ncpu        = 9223372036854775808",
                           "info_00001.txt"));
    c.push_back(
        ramsesInfo("RamsesInfoNcpuZero", "ncpu        =          1", "ncpu        =          0", "info_00001.txt"));
    c.push_back(
        ramsesInfo("RamsesInfoLevelmaxIntMax", "levelmax    =          2", "levelmax    = 2147483647", "output_00001"));
    // Enzo: grid dimensions and indices, field counts, the top grid and refinement.
    const std::string hier = "DD0018.hierarchy", par = "DD0018";
    const std::string dim1 = "GridDimension     = 38 38 22 ";
    c.push_back(enzo("EnzoGridDimensionZero", hier, dim1, "GridDimension     = 0 0 0 ", "DD0018.hierarchy"));
    // The files hold the active zone: GridDimension (with ghost zones) is only the other shape allowed.
    c.push_back(enzo("EnzoGridDimensionIntMax", hier, dim1, "GridDimension     = 2147483647 38 22 ", ""));
    c.push_back(
        enzo("EnzoGridDimension2To32", hier, dim1, "GridDimension     = 4294967296 38 22 ", "DD0018.hierarchy"));
    c.push_back(enzo("EnzoGridDimensionMinus1", hier, dim1, "GridDimension     = -1 38 22 ", "DD0018.hierarchy"));
    c.push_back(enzo("EnzoStartPastEnd", hier, "GridStartIndex    = 3 3 3 ", "GridStartIndex    = 35 3 3 ",
                     "DD0018.hierarchy"));
    c.push_back(enzo("EnzoEndIndexIntMax", hier, "GridEndIndex      = 34 34 18 ",
                     "GridEndIndex      = 2147483647 34 18 ", "DD0018.hierarchy"));
    // The fields are the grid file's datasets: the count is not used to size anything.
    c.push_back(enzo("EnzoFieldsZero", hier, "NumberOfBaryonFields = 6", "NumberOfBaryonFields = 0", ""));
    c.push_back(enzo("EnzoFieldsIntMax", hier, "NumberOfBaryonFields = 6", "NumberOfBaryonFields = 2147483647", ""));
    c.push_back(enzo("EnzoFieldsMinus1", hier, "NumberOfBaryonFields = 6", "NumberOfBaryonFields = -1", ""));
    c.push_back(enzo("EnzoGridRankZero", hier, "GridRank          = 3", "GridRank          = 0", "DD0018.hierarchy"));
    c.push_back(enzo("EnzoGridRank2To63", hier, "GridRank          = 3", "GridRank          = 9223372036854775808",
                     "DD0018.hierarchy"));
    c.push_back(
        enzo("EnzoTopGridZero", par, "TopGridDimensions   = 32 32 32", "TopGridDimensions   = 0 0 0", "DD0018"));
    c.push_back(enzo("EnzoTopGridIntMax", par, "TopGridDimensions   = 32 32 32",
                     "TopGridDimensions   = 2147483647 2147483647 2147483647", "DD0018"));
    c.push_back(enzo("EnzoRefineByZero", par, "RefineBy                       = 2",
                     "RefineBy                       = 0", "DD0018"));
    c.push_back(enzo("EnzoRefineBy2To31", par, "RefineBy                       = 2",
                     "RefineBy                       = 2147483648", "DD0018"));
    // Chombo: counts and ratios as attributes, data offsets as a dataset.
    c.push_back(chomboInt("ChomboComponentsZero", "/", "num_components", 0, "plt000100.2d.hdf5"));
    c.push_back(chomboInt("ChomboComponentsIntMax", "/", "num_components", kIntMax, "plt000100.2d.hdf5"));
    c.push_back(chomboInt("ChomboComponentsMinus1", "/", "num_components", -1, "plt000100.2d.hdf5"));
    c.push_back(chomboInt("ChomboLevelsZero", "/", "num_levels", 0, "plt000100.2d.hdf5"));
    c.push_back(chomboInt("ChomboLevelsIntMax", "/", "num_levels", kIntMax, "plt000100.2d.hdf5"));
    c.push_back(chomboInt("ChomboLevelsMinus1", "/", "num_levels", -1, "plt000100.2d.hdf5"));
    c.push_back(chomboInt("ChomboRatioZero", "level_0", "ref_ratio", 0, "plt000100.2d.hdf5"));
    c.push_back(chomboInt("ChomboRatioIntMax", "level_0", "ref_ratio", kIntMax, "plt000100.2d.hdf5"));
    c.push_back(chomboInt("ChomboRatioMinus1", "level_0", "ref_ratio", -1, "plt000100.2d.hdf5"));
    c.push_back(chomboInt("ChomboSpaceDimZero", "Chombo_global", "SpaceDim", 0, ""));  // as absent: the boxes say 2-D
    c.push_back(chomboInt("ChomboSpaceDim3With2DBoxes", "Chombo_global", "SpaceDim", 3, "plt000100.2d.hdf5"));
    c.push_back(chomboInt("ChomboSpaceDimIntMax", "Chombo_global", "SpaceDim", kIntMax, "plt000100.2d.hdf5"));
    c.push_back(chombo(
        "ChomboOffset2To63", [](hid_t f) { writeFirstInt64(f, "level_0/data:offsets=0", INT64_MAX); },
        "plt000100.2d.hdf5"));
    c.push_back(chombo(
        "ChomboOffsetMinus1", [](hid_t f) { writeFirstInt64(f, "level_0/data:offsets=0", -1); }, "plt000100.2d.hdf5"));
    c.push_back(chombo(
        "ChomboOffset2To32", [](hid_t f) { writeFirstInt64(f, "level_0/data:offsets=0", int64_t(k4G)); },
        "plt000100.2d.hdf5"));
    return c;
}

class HostileSizes : public ::testing::TestWithParam<SizeCase> {};

// An address-space cap for the read (not under ASan, whose shadow memory needs terabytes).
struct AddressSpaceCap {
#if defined(__SANITIZE_ADDRESS__)
    AddressSpaceCap() = default;
#else
    rlimit before{};
    AddressSpaceCap() {
        getrlimit(RLIMIT_AS, &before);
        rlimit cap = before;
        cap.rlim_cur = std::min<rlim_t>(before.rlim_max, rlim_t(6) << 30);
        setrlimit(RLIMIT_AS, &cap);
    }
    ~AddressSpaceCap() { setrlimit(RLIMIT_AS, &before); }
#endif
};

TEST_P(HostileSizes, EndsInTheModelOrOneLineNamingTheFile) {
    const SizeCase& c = GetParam();
    if (c.needs) AMRVK_REQUIRE_DATA(c.needs);
    setenv("AMRVK_MEMORY_BUDGET", "1073741824", 1);  // read once per process: ctest runs each case alone
    if (c.expect.find("memory budget") != std::string::npos && memoryBudgetBytes() != (uint64_t(1) << 30))
        GTEST_SKIP() << "the memory budget was read before this case set it (run it alone, as ctest does)";
    const Input in = c.make(scratchDir());
    std::string outcome;
    {
        const AddressSpaceCap cap;
        try {
            const amr::Model m = amr::readModel(in.path, in.options);
            outcome = "read " + std::to_string(m.cellCount()) + " cells";
        } catch (const Error& e) {
            outcome = e.what();
            EXPECT_EQ(outcome.find('\n'), std::string::npos) << outcome;
        } catch (const std::exception& e) {
            ADD_FAILURE() << "not an amrvk::Error: " << typeid(e).name() << ": " << e.what();
        }
    }
    std::printf("%s: %s\n", c.name.c_str(), outcome.c_str());
    if (c.expect.empty())
        EXPECT_EQ(outcome.rfind("read ", 0), 0u) << outcome;
    else
        expectContains(outcome, c.expect);
}

INSTANTIATE_TEST_SUITE_P(Readers, HostileSizes, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<SizeCase>& i) { return i.param.name; });

}  // namespace
