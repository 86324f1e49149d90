#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <tuple>

#include "amr/readers.h"
#include "core/error.h"
#include "test_data.h"

using namespace amrvk;
using namespace amrvk::amr;
namespace fs = std::filesystem;

namespace {

template <typename T>
fs::path writeRaw(const fs::path& path, const std::vector<T>& voxels) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(voxels.data()), static_cast<std::streamsize>(voxels.size() * sizeof(T)));
    return path;
}

size_t voxelIndex(glm::ivec3 d, int x, int y, int z) {
    return static_cast<size_t>(x + d.x * (y + d.y * z));
}

// Every voxel lies in exactly one cell, every cell inside the volume, each value the exact
// voxel average (within float rounding).
template <typename T>
void expectExactCover(const Model& m, glm::ivec3 d, const std::vector<T>& voxels) {
    std::vector<int> covered(voxels.size(), 0);
    double volume = 0;
    const auto& values = m.field("value").values;
    for (size_t i = 0; i < m.cells.size(); ++i) {
        const Cell& c = m.cells[i];
        const int w = 1 << c.level;
        ASSERT_LE(c.lower.x + w, d.x);
        ASSERT_LE(c.lower.y + w, d.y);
        ASSERT_LE(c.lower.z + w, d.z);
        double sum = 0;
        for (int z = c.lower.z; z < c.lower.z + w; ++z)
            for (int y = c.lower.y; y < c.lower.y + w; ++y)
                for (int x = c.lower.x; x < c.lower.x + w; ++x) {
                    covered[voxelIndex(d, x, y, z)]++;
                    sum += static_cast<double>(voxels[voxelIndex(d, x, y, z)]);
                }
        volume += std::ldexp(1.0, 3 * c.level);
        EXPECT_NEAR(values[i], sum / std::ldexp(1.0, 3 * c.level), 1e-5 * (1 + std::abs(values[i])));
    }
    EXPECT_DOUBLE_EQ(volume, static_cast<double>(d.x) * d.y * d.z);
    for (size_t i = 0; i < covered.size(); ++i) ASSERT_EQ(covered[i], 1) << "voxel " << i;
}

std::map<int, int> cellsPerLevel(const Model& m) {
    std::map<int, int> n;
    for (const Cell& c : m.cells) n[c.level]++;
    return n;
}

float valueAt(const Model& m, glm::ivec3 lower, int level) {
    for (size_t i = 0; i < m.cells.size(); ++i)
        if (m.cells[i].lower == lower && m.cells[i].level == level) return m.fields[0].values[i];
    ADD_FAILURE() << "no cell at " << lower.x << "," << lower.y << "," << lower.z << " level " << level;
    return NAN;
}

// 8x8x4 uint8 with four 4x4x4 blocks: constant 10; constant 20 but voxel (7,3,3) = 21;
// eight 2x2x2 constants 30..37; all-distinct values 100 + 3 i.
std::vector<uint8_t> handMadeVolume() {
    const glm::ivec3 d(8, 8, 4);
    std::vector<uint8_t> v(256);
    int distinct = 0;
    for (int z = 0; z < 4; ++z)
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 8; ++x) {
                uint8_t& o = v[voxelIndex(d, x, y, z)];
                if (x < 4 && y < 4) o = 10;
                else if (y < 4) o = (x == 7 && y == 3 && z == 3) ? 21 : 20;
                else if (x < 4) o = static_cast<uint8_t>(30 + (x / 2) + 2 * ((y - 4) / 2) + 4 * (z / 2));
                else o = static_cast<uint8_t>(100 + 2 * distinct++);
            }
    return v;
}

}  // namespace

TEST(RawReader, HandMadeVolumeThresholdZero) {
    fs::path p = writeRaw(test::scratchDir() / "hand_8x8x4_uint8.raw", handMadeVolume());
    Model m = readModel(p, ReadOptions{});  // .raw detected; dims and type from the name
    EXPECT_EQ(m.format, "raw");
    ASSERT_EQ(m.fields.size(), 1u);
    EXPECT_EQ(m.fields[0].name, "value");
    EXPECT_EQ(m.availableFields, std::vector<std::string>{"value"});
    EXPECT_EQ(m.voxelToWorld.origin, glm::dvec3(0.0));
    EXPECT_EQ(m.voxelToWorld.scale, glm::dvec3(1.0));
    // 1 (constant block) + 7 + 8 (block with one odd voxel) + 8 (2x2x2 constants) + 64 (distinct).
    EXPECT_EQ(m.cellCount(), 88u);
    auto perLevel = cellsPerLevel(m);
    EXPECT_EQ(perLevel[2], 1);
    EXPECT_EQ(perLevel[1], 15);
    EXPECT_EQ(perLevel[0], 72);
    EXPECT_EQ(valueAt(m, {0, 0, 0}, 2), 10.0f);
    EXPECT_EQ(valueAt(m, {4, 0, 0}, 1), 20.0f);
    EXPECT_EQ(valueAt(m, {7, 3, 3}, 0), 21.0f);
    EXPECT_EQ(valueAt(m, {6, 2, 2}, 0), 20.0f);
    EXPECT_EQ(valueAt(m, {2, 6, 2}, 1), 37.0f);
    expectExactCover(m, {8, 8, 4}, handMadeVolume());
}

TEST(RawReader, ThresholdMergesWithinRangeAndAverages) {
    fs::path p = writeRaw(test::scratchDir() / "hand_8x8x4_uint8.raw", handMadeVolume());
    ReadOptions o;
    o.rawThreshold = 1.0;
    Model m = readModel(p, o);
    EXPECT_EQ(m.cellCount(), 74u);  // the 20/21 block merges: max - min = 1
    EXPECT_EQ(valueAt(m, {4, 0, 0}, 2), static_cast<float>((63 * 20 + 21) / 64.0));
    expectExactCover(m, {8, 8, 4}, handMadeVolume());
    o.rawThreshold = 7.0;  // the 30..37 block merges too, distinct values (step 2) never
    Model m7 = readModel(p, o);
    EXPECT_EQ(valueAt(m7, {0, 4, 0}, 2), 33.5f);
    EXPECT_EQ(m7.cellCount(), 67u);
}

TEST(RawReader, ConstantVolumeGivesMaximalPowerOfTwoBlocks) {
    const glm::ivec3 d(12, 8, 4);
    std::vector<float> v(12 * 8 * 4, 3.5f);
    fs::path p = writeRaw(test::scratchDir() / "const_12x8x4_float32.raw", v);
    Model m = readModel(p, ReadOptions{});
    // The 16^3 padded cube splits into 8^3 blocks (all overlap the padding), then into six
    // 4^3 blocks that lie inside: one cell each.
    EXPECT_EQ(m.cellCount(), 6u);
    for (size_t i = 0; i < m.cells.size(); ++i) {
        EXPECT_EQ(m.cells[i].level, 2);
        EXPECT_EQ(m.fields[0].values[i], 3.5f);
    }
    expectExactCover(m, d, v);

    std::vector<uint16_t> cube(16 * 16 * 16, 7);
    Model one = readModel(writeRaw(test::scratchDir() / "cube_16x16x16_uint16.raw", cube), ReadOptions{});
    ASSERT_EQ(one.cellCount(), 1u);
    EXPECT_EQ(one.cells[0].level, 4);
    EXPECT_EQ(one.fields[0].values[0], 7.0f);
}

TEST(RawReader, ThresholdZeroOnRandomVolumeKeepsEveryVoxel) {
    const glm::ivec3 d(6, 5, 7);
    std::vector<float> v(6 * 5 * 7);
    uint32_t s = 12345;
    for (float& x : v) {
        s = s * 1664525u + 1013904223u;
        x = static_cast<float>(s >> 8) / 16777216.0f;
    }
    fs::path p = writeRaw(test::scratchDir() / "random_6x5x7_float.raw", v);  // "_float" alias
    Model m = readModel(p, ReadOptions{});
    ASSERT_EQ(m.cellCount(), v.size());
    for (size_t i = 0; i < m.cells.size(); ++i) {
        const Cell& c = m.cells[i];
        EXPECT_EQ(c.level, 0);
        EXPECT_EQ(m.fields[0].values[i], v[voxelIndex(d, c.lower.x, c.lower.y, c.lower.z)]);
    }
}

TEST(RawReader, NonPowerOfTwoDimsCoverTheVolumeExactly) {
    const glm::ivec3 d(13, 7, 5);
    std::vector<uint8_t> v(13 * 7 * 5);
    for (int z = 0; z < d.z; ++z)
        for (int y = 0; y < d.y; ++y)
            for (int x = 0; x < d.x; ++x)
                v[voxelIndex(d, x, y, z)] = static_cast<uint8_t>((x / 4) + 3 * (y / 4) + 9 * (z / 4));
    fs::path p = writeRaw(test::scratchDir() / "blocks.raw", v);
    ReadOptions o;
    o.rawDims = d;
    o.rawType = "uint8";
    Model m = readModel(p, o);  // validates
    EXPECT_NO_THROW(validate(m));
    EXPECT_LT(m.cellCount(), v.size());
    EXPECT_GT(cellsPerLevel(m)[2], 0);
    expectExactCover(m, d, v);
}

TEST(RawReader, OptionsOverrideAndLittleEndianTypes) {
    const glm::ivec3 d(3, 2, 1);
    std::vector<uint8_t> bytes = {0x02, 0x01, 0, 0, 0xff, 0xff, 1, 0, 2, 0, 3, 0};  // uint16 LE
    fs::path p = writeRaw(test::scratchDir() / "le_99x99x99_uint8.raw", bytes);
    ReadOptions o;
    o.rawDims = d;
    o.rawType = "uint16";
    Model m = readModel(p, o);
    ASSERT_EQ(m.cellCount(), 6u);
    std::vector<float> expect = {258, 0, 65535, 1, 2, 3};
    for (size_t i = 0; i < m.cells.size(); ++i) {
        const Cell& c = m.cells[i];
        EXPECT_EQ(m.fields[0].values[i], expect[voxelIndex(d, c.lower.x, c.lower.y, c.lower.z)]);
    }

    std::vector<double> dv = {-1.5, 2.25, 1e10, 0.0};
    Model md = readModel(writeRaw(test::scratchDir() / "vals_2x2x1_double.raw", dv), ReadOptions{});
    ASSERT_EQ(md.cellCount(), 4u);
    std::vector<float> seen;
    for (float f : md.fields[0].values) seen.push_back(f);
    std::sort(seen.begin(), seen.end());
    EXPECT_EQ(seen, (std::vector<float>{-1.5f, 0.0f, 2.25f, 1e10f}));
}

TEST(RawReader, NanVoxelsAreNeverMerged) {
    std::vector<float> v(8, 1.0f);
    v[5] = NAN;
    fs::path p = writeRaw(test::scratchDir() / "nan_2x2x2_float32.raw", v);
    ReadOptions o;
    o.rawThreshold = 100;
    o.nanPolicy = NanPolicy::Drop;
    Model m = readModel(p, o);
    EXPECT_EQ(m.cellCount(), 7u);
    o.nanPolicy = NanPolicy::Reject;
    EXPECT_THROW(readModel(p, o), Error);
}

TEST(RawReader, SizeMismatchNamesFileAndSizes) {
    std::vector<uint8_t> v(100, 1);
    fs::path p = writeRaw(test::scratchDir() / "short_8x8x4_uint8.raw", v);
    try {
        readModel(p, ReadOptions{});
        FAIL() << "expected an error";
    } catch (const Error& e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
        EXPECT_NE(msg.find("256"), std::string::npos) << msg;
        EXPECT_NE(msg.find("100"), std::string::npos) << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
}

TEST(RawReader, UnknownTypeAndMissingDimsNameTheFile) {
    std::vector<uint8_t> v(8, 1);
    fs::path p = writeRaw(test::scratchDir() / "vol_2x2x2_uint8.raw", v);
    ReadOptions o;
    o.rawType = "int7";
    try {
        readModel(p, o);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
        EXPECT_NE(msg.find("int7"), std::string::npos) << msg;
    }
    fs::path nodims = writeRaw(test::scratchDir() / "nodims.raw", v);
    try {
        readModel(nodims, ReadOptions{});
        FAIL() << "expected an error";
    } catch (const Error& e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find(nodims.string()), std::string::npos) << msg;
        EXPECT_NE(msg.find("dimensions"), std::string::npos) << msg;
    }
    fs::path notype = writeRaw(test::scratchDir() / "vol_2x2x2.raw", v);
    try {
        readModel(notype, ReadOptions{});
        FAIL() << "expected an error";
    } catch (const Error& e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find(notype.string()), std::string::npos) << msg;
        EXPECT_NE(msg.find("type"), std::string::npos) << msg;
    }
}

TEST(RawReader, UnknownFieldIsRejected) {
    std::vector<uint8_t> v(8, 1);
    fs::path p = writeRaw(test::scratchDir() / "vol_2x2x2_uint8.raw", v);
    ReadOptions o;
    o.fields = {"density"};
    try {
        readModel(p, o);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find("density"), std::string::npos) << msg;
        EXPECT_NE(msg.find("value"), std::string::npos) << msg;
    }
    o.fields = {"value"};
    EXPECT_EQ(readModel(p, o).cellCount(), 1u);
}
