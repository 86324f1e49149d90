// Image output: PFM and EXR round trips are bit-exact, OpenEXR readers (tinyexr) read our EXR
// files, PNG holds the sRGB encoding of the clamped linear values within one step of 8 bits;
// failures leave no file.
#include <gtest/gtest.h>
#include <tinyexr.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>

#include "core/error.h"
#include "core/image_io.h"
#include "test_data.h"

using namespace amrvk;

using namespace amrvk::test;

namespace {

Image randomImage(int w, int h, uint32_t seed, float lo, float hi) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(lo, hi);
    Image img(w, h);
    for (glm::vec4& p : img.pixels) p = glm::vec4(u(rng), u(rng), u(rng), u(rng));
    return img;
}

std::vector<uint8_t> fileBytes(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

// Every entry of dir, for checking that a failed write left nothing (no temporary either).
std::vector<std::string> listDir(const std::filesystem::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

// Reference sRGB encoding, computed independently in double.
int srgbByte(double linear) {
    if (!(linear > 0.0)) return 0;
    linear = std::min(linear, 1.0);
    double s = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
    return int(std::lround(s * 255.0));
}

void expectRgbBitExact(const Image& a, const Image& b) {
    ASSERT_EQ(a.width, b.width);
    ASSERT_EQ(a.height, b.height);
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            for (int k = 0; k < 3; ++k)
                ASSERT_EQ(std::memcmp(&a.at(x, y)[k], &b.at(x, y)[k], 4), 0)
                    << "pixel " << x << "," << y << " channel " << k << ": " << a.at(x, y)[k]
                    << " vs " << b.at(x, y)[k];
}

}  // namespace

TEST(ImageIo, PfmRoundTripIsExact) {
    auto dir = test::scratchDir();
    for (auto [w, h] : {std::pair{1, 1}, {13, 7}, {64, 3}}) {
        Image img = randomImage(w, h, uint32_t(w * 100 + h), -1e3f, 1e3f);
        img.at(0, 0) = glm::vec4(std::numeric_limits<float>::infinity(), -0.0f, 1e-40f, 0.5f);
        writeImage(dir / "a.pfm", img);
        Image back = readPfm(dir / "a.pfm");
        expectRgbBitExact(img, back);
        for (const glm::vec4& p : back.pixels) EXPECT_EQ(p.a, 1.0f);
    }
}

TEST(ImageIo, PfmStoresRowsBottomToTop) {
    auto dir = test::scratchDir();
    Image img(2, 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 2; ++x) img.at(x, y) = glm::vec4(float(10 * y + x), 0.0f, 0.0f, 1.0f);
    writeImage(dir / "rows.pfm", img);
    std::vector<uint8_t> bytes = fileBytes(dir / "rows.pfm");
    const std::string header = "PF\n2 3\n-1.0\n";
    ASSERT_EQ(bytes.size(), header.size() + 2 * 3 * 3 * 4);
    EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + long(header.size())), header);
    float first;
    std::memcpy(&first, &bytes[header.size()], 4);
    EXPECT_EQ(first, 20.0f);  // the bottom row (y = 2) comes first
}

TEST(ImageIo, ExrRoundTripIsExact) {
    auto dir = test::scratchDir();
    for (auto [w, h] : {std::pair{1, 1}, {13, 7}, {5, 40}}) {
        Image img = randomImage(w, h, uint32_t(w * 7 + h), -5.0f, 50.0f);
        writeImage(dir / "a.exr", img);
        Image back = readExr(dir / "a.exr");
        expectRgbBitExact(img, back);
        for (const glm::vec4& p : back.pixels) EXPECT_EQ(p.a, 1.0f);  // no A channel written
    }
}

// What an OpenEXR reader sees in our files: tinyexr's own header parser and its RGBA loader (not
// readExr) find a single-part scanline file with FLOAT channels named R, G and B holding the
// linear values bit for bit.
TEST(ImageIo, ExrIsReadByOpenExrReaders) {
    auto dir = test::scratchDir();
    Image img = randomImage(9, 4, 3, -2.0f, 20.0f);
    writeImage(dir / "a.exr", img);
    const std::string file = (dir / "a.exr").string();
    EXRVersion version;
    ASSERT_EQ(ParseEXRVersionFromFile(&version, file.c_str()), TINYEXR_SUCCESS);
    EXPECT_FALSE(version.multipart || version.tiled || version.non_image);
    EXRHeader header;
    InitEXRHeader(&header);
    const char* err = nullptr;
    ASSERT_EQ(ParseEXRHeaderFromFile(&header, &version, file.c_str(), &err), TINYEXR_SUCCESS) << (err ? err : "");
    std::vector<std::string> names;
    for (int c = 0; c < header.num_channels; ++c) {
        names.push_back(header.channels[c].name);
        EXPECT_EQ(header.pixel_types[c], TINYEXR_PIXELTYPE_FLOAT) << names.back();
    }
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"B", "G", "R"}));
    EXPECT_EQ(header.data_window.max_x - header.data_window.min_x + 1, 9);
    EXPECT_EQ(header.data_window.max_y - header.data_window.min_y + 1, 4);
    FreeEXRHeader(&header);

    float* rgba = nullptr;
    int w = 0, h = 0;
    ASSERT_EQ(LoadEXR(&rgba, &w, &h, file.c_str(), &err), TINYEXR_SUCCESS) << (err ? err : "");
    ASSERT_EQ(w, 9);
    ASSERT_EQ(h, 4);
    Image loaded(w, h);
    for (size_t i = 0; i < loaded.pixels.size(); ++i)
        loaded.pixels[i] = glm::vec4(rgba[4 * i], rgba[4 * i + 1], rgba[4 * i + 2], rgba[4 * i + 3]);
    std::free(rgba);
    expectRgbBitExact(img, loaded);  // row 0 = top in both
}

// Files from other writers: tinyexr's SaveEXR writes HALF channels (A, B, G, R) with ZIP
// compression by default; readExr reads them to half precision.
TEST(ImageIo, ExrReadsHalfAndCompressedFiles) {
    auto dir = test::scratchDir();
    const int w = 7, h = 5;
    Image img = randomImage(w, h, 4, 0.0f, 4.0f);
    std::vector<float> rgba;
    for (const glm::vec4& p : img.pixels) rgba.insert(rgba.end(), {p.r, p.g, p.b, p.a});
    const std::string file = (dir / "half.exr").string();
    const char* err = nullptr;
    ASSERT_EQ(SaveEXR(rgba.data(), w, h, 4, 1, file.c_str(), &err), TINYEXR_SUCCESS) << (err ? err : "");
    Image back = readExr(file);
    ASSERT_EQ(back.width, w);
    ASSERT_EQ(back.height, h);
    for (size_t i = 0; i < img.pixels.size(); ++i)
        for (int k = 0; k < 4; ++k)  // half: 11 significant bits
            EXPECT_NEAR(back.pixels[i][k], img.pixels[i][k], img.pixels[i][k] * 1e-3f) << i << " " << k;
}

TEST(ImageIo, PngHoldsSrgbEncodedValues) {
    auto dir = test::scratchDir();
    Image img = randomImage(17, 9, 5, -0.2f, 1.3f);
    img.at(0, 0) = glm::vec4(std::numeric_limits<float>::quiet_NaN(), 0.001f, 0.0031308f, 0.0f);
    img.at(1, 0) = glm::vec4(0.5f, 0.18f, std::numeric_limits<float>::infinity(), 0.0f);
    writeImage(dir / "a.png", img);
    Image8 back = readPng(dir / "a.png");
    ASSERT_EQ(back.width, 17);
    ASSERT_EQ(back.height, 9);
    ASSERT_EQ(back.rgba.size(), size_t(17 * 9 * 4));
    for (int y = 0; y < 9; ++y) {
        for (int x = 0; x < 17; ++x) {
            const uint8_t* p = &back.rgba[size_t(4 * (x + 17 * y))];
            for (int k = 0; k < 3; ++k)
                EXPECT_LE(std::abs(int(p[k]) - srgbByte(img.at(x, y)[k])), 1)
                    << "pixel " << x << "," << y << " channel " << k << " linear " << img.at(x, y)[k];
            EXPECT_EQ(p[3], 255);
        }
    }
    EXPECT_EQ(back.rgba[0], 0);      // NaN -> 0
    EXPECT_EQ(back.rgba[4], 188);    // 0.5 -> 188
    EXPECT_EQ(back.rgba[5], 118);    // 0.18 -> 118
    EXPECT_EQ(back.rgba[6], 255);    // +inf -> 1
    EXPECT_EQ(encodeSrgb8(2.0f), 255);
    EXPECT_EQ(encodeSrgb8(-1.0f), 0);
}

TEST(ImageIo, ExtensionIsCaseInsensitive) {
    auto dir = test::scratchDir();
    Image img = randomImage(3, 2, 9, 0.0f, 1.0f);
    writeImage(dir / "a.PFM", img);
    expectRgbBitExact(img, readPfm(dir / "a.PFM"));
}

TEST(ImageIo, FailuresLeaveNoFile) {
    auto dir = test::scratchDir();
    Image img = randomImage(4, 4, 1, 0.0f, 1.0f);
    expectError([&] { writeImage(dir / "a.tiff", img); }, {"a.tiff", "unknown image extension '.tiff'"});
    expectError([&] { writeImage(dir / "noext", img); }, {"noext", "unknown image extension ''"});
    for (const char* name : {"missing/a.png", "missing/a.pfm", "missing/a.exr"})
        expectError([&] { writeImage(dir / name, img); }, {name, "cannot write"});
    // The target is a directory: refused before anything is written, nothing remains.
    std::filesystem::create_directory(dir / "taken.exr");
    expectError([&] { writeImage(dir / "taken.exr", img); }, {"taken.exr", "is a directory"});
    EXPECT_TRUE(std::filesystem::is_directory(dir / "taken.exr"));
    EXPECT_TRUE(std::filesystem::is_empty(dir / "taken.exr"));
    Image bad = img;
    bad.pixels.pop_back();
    expectError([&] { writeImage(dir / "bad.png", bad); }, {"bad.png", "image 4x4 has 15 pixels"});
    expectError([&] { writeImage(dir / "empty.pfm", Image()); }, {"empty.pfm", "image size 0x0"});
    EXPECT_EQ(listDir(dir), std::vector<std::string>{"taken.exr"});
}

TEST(ImageIo, MalformedFilesAreRejected) {
    auto dir = test::scratchDir();
    auto write = [&](const char* name, const std::string& text) {
        std::ofstream(dir / name, std::ios::binary) << text;
        return dir / name;
    };
    expectError([&] { readPfm(write("magic.pfm", "P6\n1 1\n255\nabc")); }, {"magic.pfm", "not a PFM file"});
    expectError([&] { readPfm(write("short.pfm", "PF\n2 2\n-1.0\n0123")); },
                {"short.pfm", "4 bytes after the header, expected 48"});
    expectError([&] { readPfm(write("size.pfm", "PF\nx 2\n-1.0\n")); }, {"size.pfm", "not a number"});
    expectError([&] { readExr(write("bad.exr", "not an exr file")); }, {"bad.exr", "not an OpenEXR file"});
    expectError([&] { readPng(write("bad.png", "not a png")); }, {"bad.png", "cannot read PNG"});
    Image img = randomImage(6, 5, 2, 0.0f, 1.0f);
    writeImage(dir / "cut.exr", img);
    std::filesystem::resize_file(dir / "cut.exr", std::filesystem::file_size(dir / "cut.exr") - 10);
    expectError([&] { readExr(dir / "cut.exr"); }, {"cut.exr", "cannot read OpenEXR pixels"});
    std::filesystem::resize_file(dir / "cut.exr", 40);  // inside the header
    expectError([&] { readExr(dir / "cut.exr"); }, {"cut.exr", "bad OpenEXR header"});
}

TEST(ImageIo, ScaledBilinearKeepsRampsAndConstants) {
    // A ramp linear in x sampled at pixel centres (value = centre's x) scaled 4x: every inner
    // output pixel is the ramp at its own centre in source pixels; the edges clamp.
    Image ramp(4, 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x) ramp.at(x, y) = glm::vec4(float(x), 1.0f, 2.0f, 1.0f);
    const Image big = scaledBilinear(ramp, 16, 8);
    ASSERT_EQ(big.width, 16);
    ASSERT_EQ(big.height, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x) {
            const double s = (x + 0.5) / 4.0 - 0.5;  // the output centre in source pixel coordinates
            EXPECT_NEAR(big.at(x, y).r, std::clamp(s, 0.0, 3.0), 1e-6) << x << "," << y;
            EXPECT_FLOAT_EQ(big.at(x, y).g, 1.0f);
            EXPECT_FLOAT_EQ(big.at(x, y).b, 2.0f);
        }
    // The same size: the image itself.
    const Image same = scaledBilinear(ramp, 4, 2);
    for (size_t i = 0; i < same.pixels.size(); ++i) EXPECT_EQ(same.pixels[i], ramp.pixels[i]);
}
