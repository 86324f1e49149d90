#include "core/image_io.h"

#include <png.h>
#include <tinyexr.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>

#include "core/error.h"
#include "core/file_io.h"
#include "core/strings.h"

namespace fs = std::filesystem;

namespace amrvk {

// PFM is little-endian; values are written and read with memcpy of native floats.
static_assert(std::endian::native == std::endian::little, "image_io assumes a little-endian host");

namespace {

constexpr int kMaxDimension = 1 << 20;

// Throws "FILE: LABEL WxH is not in [1, kMaxDimension] per axis" for a size outside that range.
void checkSize(const std::string& file, const char* label, int width, int height) {
    AMRVK_CHECK(width > 0 && height > 0 && width <= kMaxDimension && height <= kMaxDimension, file, ": ", label, " ",
                width, "x", height, " is not in [1, ", kMaxDimension, "] per axis");
}

void checkImage(const fs::path& path, const Image& image) {
    checkSize(path.string(), "image size", image.width, image.height);
    AMRVK_CHECK(image.pixels.size() == size_t(image.width) * size_t(image.height), path.string(),
                ": image ", image.width, "x", image.height, " has ", image.pixels.size(), " pixels");
}

// 8-bit RGBA pixels (row 0 = top) encoded as a PNG file's bytes; `what` names it in errors.
std::vector<uint8_t> encodePngRgba(const std::string& what, int width, int height, const uint8_t* rgba) {
    png_image png{.version = PNG_IMAGE_VERSION,
                  .width = static_cast<png_uint_32>(width),
                  .height = static_cast<png_uint_32>(height),
                  .format = PNG_FORMAT_RGBA};
    png_alloc_size_t bytes = 0;
    bool ok = png_image_write_to_memory(&png, nullptr, &bytes, 0, rgba, 0, nullptr) != 0;
    std::vector<uint8_t> encoded(ok ? bytes : 0);
    if (ok) ok = png_image_write_to_memory(&png, encoded.data(), &bytes, 0, rgba, 0, nullptr) != 0;
    std::string message = png.message;
    png_image_free(&png);
    AMRVK_CHECK(ok, what, ": PNG encoding failed (", message, ")");
    encoded.resize(bytes);
    return encoded;
}

// Encodes 8-bit RGBA pixels (row 0 = top) as PNG and writes them through AtomicFileWriter.
void writePngRgba(const fs::path& path, int width, int height, const uint8_t* rgba) {
    const std::vector<uint8_t> encoded = encodePngRgba(path.string(), width, height, rgba);
    AtomicFileWriter out(path);
    out.write(encoded.data(), encoded.size());
    out.commit();
}

// The tone-mapped 8-bit pixels writeImage puts in a PNG.
std::vector<uint8_t> srgbRgba(const Image& image) {
    std::vector<uint8_t> rgba(image.pixels.size() * 4);
    for (size_t i = 0; i < image.pixels.size(); ++i) {
        for (int k = 0; k < 3; ++k) rgba[4 * i + size_t(k)] = encodeSrgb8(image.pixels[i][k]);
        rgba[4 * i + 3] = 255;
    }
    return rgba;
}

void writePng(const fs::path& path, const Image& image) {
    writePngRgba(path, image.width, image.height, srgbRgba(image).data());
}

void writePfm(const fs::path& path, const Image& image) {
    AtomicFileWriter out(path);
    const std::string header = strCat("PF\n", image.width, " ", image.height, "\n-1.0\n");
    out.write(header.data(), header.size());
    std::vector<float> row(size_t(image.width) * 3);
    for (int y = image.height - 1; y >= 0; --y) {
        for (int x = 0; x < image.width; ++x) {
            const glm::vec4& p = image.at(x, y);
            for (int k = 0; k < 3; ++k) row[size_t(x) * 3 + size_t(k)] = p[k];
        }
        out.writeSpan(std::span<const float>(row));
    }
    out.commit();
}

// tinyexr's error message (freed) on one line: its line breaks become "; ".
std::string takeExrError(const char* err) {
    std::string message;
    for (const char* c = err; c && *c; ++c) {
        if (*c != '\n') message += *c;
        else if (c[1]) message += "; ";
    }
    if (err) FreeEXRErrorMessage(err);
    return message.empty() ? "no details" : message;
}

// A parsed header and loaded image, freed on scope exit.
struct ExrFile {
    EXRHeader header;
    EXRImage image;
    ExrFile() {
        InitEXRHeader(&header);
        InitEXRImage(&image);
    }
    ~ExrFile() {
        FreeEXRImage(&image);
        FreeEXRHeader(&header);
    }
    ExrFile(const ExrFile&) = delete;
    ExrFile& operator=(const ExrFile&) = delete;
};

// Uncompressed FLOAT scanlines; channels in OpenEXR's alphabetical order B, G, R.
void writeExr(const fs::path& path, const Image& image) {
    const size_t count = image.pixels.size();
    std::vector<float> planes[3];  // B, G, R
    for (int c = 0; c < 3; ++c) {
        planes[c].resize(count);
        for (size_t i = 0; i < count; ++i) planes[c][i] = image.pixels[i][2 - c];
    }
    float* planePointers[3] = {planes[0].data(), planes[1].data(), planes[2].data()};
    EXRImage exr;
    InitEXRImage(&exr);
    exr.images = reinterpret_cast<unsigned char**>(planePointers);
    exr.width = image.width;
    exr.height = image.height;
    exr.num_channels = 3;

    EXRHeader header;
    InitEXRHeader(&header);
    EXRChannelInfo channels[3] = {};
    int pixelTypes[3], requestedTypes[3];
    const char* names[3] = {"B", "G", "R"};
    for (int c = 0; c < 3; ++c) {
        std::strcpy(channels[c].name, names[c]);
        pixelTypes[c] = requestedTypes[c] = TINYEXR_PIXELTYPE_FLOAT;
    }
    header.num_channels = 3;
    header.channels = channels;
    header.pixel_types = pixelTypes;
    header.requested_pixel_types = requestedTypes;
    header.compression_type = TINYEXR_COMPRESSIONTYPE_NONE;

    unsigned char* memory = nullptr;
    const char* err = nullptr;
    const size_t bytes = SaveEXRImageToMemory(&exr, &header, &memory, &err);
    const std::unique_ptr<unsigned char, decltype(&std::free)> owned(memory, &std::free);
    AMRVK_CHECK(bytes > 0 && memory, path.string(), ": OpenEXR encoding failed (", takeExrError(err), ")");
    AtomicFileWriter out(path);
    out.write(memory, bytes);
    out.commit();
}

std::vector<uint8_t> readAll(const fs::path& path) {
    BinaryReader in(path);
    std::vector<uint8_t> data;
    in.readArray(data, in.size());
    return data;
}

}  // namespace

Image scaledBilinear(const Image& src, int width, int height) {
    AMRVK_CHECK(width > 0 && height > 0 && src.width > 0 && src.height > 0, "internal: scaling a ", src.width, "x",
                src.height, " image to ", width, "x", height);
    auto at = [&](int x, int y) { return src.at(std::clamp(x, 0, src.width - 1), std::clamp(y, 0, src.height - 1)); };
    Image out(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const double sx = (x + 0.5) * src.width / width - 0.5, sy = (y + 0.5) * src.height / height - 0.5;
            const int x0 = int(std::floor(sx)), y0 = int(std::floor(sy));
            const float fx = float(sx - x0), fy = float(sy - y0);
            out.at(x, y) = glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), fx),
                                    glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), fx), fy);
        }
    return out;
}

uint8_t encodeSrgb8(float linear) {
    const double c = linear > 0.0f ? (linear < 1.0f ? double(linear) : 1.0) : 0.0;
    const double s = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
    return static_cast<uint8_t>(std::lround(std::clamp(s, 0.0, 1.0) * 255.0));
}

void writeImage(const fs::path& path, const Image& image) {
    const std::string ext = toLower(path.extension().string());
    AMRVK_CHECK(ext == ".png" || ext == ".pfm" || ext == ".exr", path.string(),
                ": unknown image extension '", ext, "' (expected .png, .pfm or .exr)");
    checkImage(path, image);
    if (ext == ".png") writePng(path, image);
    else if (ext == ".pfm") writePfm(path, image);
    else writeExr(path, image);
}

std::vector<uint8_t> pngBytes(const Image& image) {
    checkImage("the image", image);
    return encodePngRgba("the image", image.width, image.height, srgbRgba(image).data());
}

void writePng8(const fs::path& path, const Image8& image) {
    checkSize(path.string(), "image size", image.width, image.height);
    AMRVK_CHECK(image.rgba.size() == size_t(image.width) * size_t(image.height) * 4, path.string(),
                ": image ", image.width, "x", image.height, " has ", image.rgba.size(),
                " RGBA bytes");
    writePngRgba(path, image.width, image.height, image.rgba.data());
}

Image readPfm(const fs::path& path) {
    const std::string file = path.string();
    const std::vector<uint8_t> data = readAll(path);
    size_t pos = 0;
    auto token = [&](const char* what) {
        while (pos < data.size() && std::isspace(data[pos])) ++pos;
        size_t begin = pos;
        while (pos < data.size() && !std::isspace(data[pos])) ++pos;
        AMRVK_CHECK(pos > begin && pos - begin < 32, file, ": PFM header: missing ", what,
                    " at byte ", begin);
        return std::string(data.begin() + long(begin), data.begin() + long(pos));
    };
    const std::string magic = token("magic");
    AMRVK_CHECK(magic == "PF" || magic == "Pf", file, ": not a PFM file (magic '", magic,
                "', expected 'PF' or 'Pf')");
    const int channels = magic == "PF" ? 3 : 1;
    int width = 0, height = 0;
    double scale = 0;
    try {
        width = std::stoi(token("width"));
        height = std::stoi(token("height"));
        scale = std::stod(token("scale"));
    } catch (const std::logic_error&) {
        AMRVK_CHECK(false, file, ": PFM header: width, height or scale is not a number");
    }
    checkSize(file, "PFM size", width, height);
    AMRVK_CHECK(scale != 0.0 && std::isfinite(scale), file, ": PFM scale ", scale, " is 0 or not finite");
    AMRVK_CHECK(pos < data.size() && std::isspace(data[pos]), file,
                ": PFM header not followed by a whitespace byte at ", pos);
    ++pos;
    const uint64_t floats = uint64_t(width) * uint64_t(height) * uint64_t(channels);
    AMRVK_CHECK(data.size() - pos == floats * 4, file, ": PFM data has ", data.size() - pos,
                " bytes after the header, expected ", floats * 4, " for ", width, "x", height,
                (channels == 3 ? " RGB" : " grey"));
    Image image(width, height, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    const bool bigEndian = scale > 0;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            for (int k = 0; k < channels; ++k) {
                uint32_t bits;
                std::memcpy(&bits, &data[pos], 4);
                pos += 4;
                if (bigEndian) bits = __builtin_bswap32(bits);
                float v;
                std::memcpy(&v, &bits, 4);
                glm::vec4& p = image.at(x, height - 1 - y);
                if (channels == 1) p = glm::vec4(v, v, v, 1.0f);
                else p[k] = v;
            }
        }
    }
    return image;
}

Image readExr(const fs::path& path) {
    const std::string file = path.string();
    const std::vector<uint8_t> data = readAll(path);
    EXRVersion version;
    AMRVK_CHECK(ParseEXRVersionFromMemory(&version, data.data(), data.size()) == TINYEXR_SUCCESS, file,
                ": not an OpenEXR file (bad magic or version)");
    AMRVK_CHECK(!version.multipart && !version.non_image && !version.tiled, file,
                ": only single-part scanline OpenEXR files are read (not multi-part, deep or tiled)");
    ExrFile exr;
    const char* err = nullptr;
    AMRVK_CHECK(ParseEXRHeaderFromMemory(&exr.header, &version, data.data(), data.size(), &err) == TINYEXR_SUCCESS,
                file, ": bad OpenEXR header (", takeExrError(err), ")");
    for (int c = 0; c < exr.header.num_channels; ++c) {
        AMRVK_CHECK(exr.header.pixel_types[c] != TINYEXR_PIXELTYPE_UINT, file, ": channel '",
                    exr.header.channels[c].name, "' is UINT (only HALF and FLOAT channels are read)");
        exr.header.requested_pixel_types[c] = TINYEXR_PIXELTYPE_FLOAT;
    }
    // On failure tinyexr frees the image (FreeEXRImage) while num_channels is still ours, and sets it
    // only on success: preset it, or the per-channel buffers of a damaged file leak.
    exr.image.num_channels = exr.header.num_channels;
    if (LoadEXRImageFromMemory(&exr.image, &exr.header, data.data(), data.size(), &err) != TINYEXR_SUCCESS) {
        InitEXRImage(&exr.image);  // tinyexr has freed it, leaving dangling pointers
        AMRVK_CHECK(false, file, ": cannot read OpenEXR pixels (", takeExrError(err), ")");
    }
    const int width = exr.image.width, height = exr.image.height;
    checkSize(file, "OpenEXR size", width, height);
    Image image(width, height, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    for (int c = 0; c < exr.header.num_channels; ++c) {
        const std::string name = exr.header.channels[c].name;
        const int k = name == "R" ? 0 : name == "G" ? 1 : name == "B" ? 2 : name == "A" ? 3 : -1;
        if (k < 0) continue;
        const float* plane = reinterpret_cast<const float*>(exr.image.images[c]);
        for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i][k] = plane[i];
    }
    return image;
}

Image8 readPng(const fs::path& path) {
    const std::string file = path.string();
    fileSize(path);
    png_image png{.version = PNG_IMAGE_VERSION};
    bool ok = png_image_begin_read_from_file(&png, file.c_str()) != 0;
    Image8 image;
    if (ok) {
        png.format = PNG_FORMAT_RGBA;
        image.width = int(png.width);
        image.height = int(png.height);
        image.rgba.resize(PNG_IMAGE_SIZE(png));
        ok = png_image_finish_read(&png, nullptr, image.rgba.data(), 0, nullptr) != 0;
    }
    std::string message = png.message;
    png_image_free(&png);
    AMRVK_CHECK(ok, file, ": cannot read PNG (", message, ")");
    return image;
}

}  // namespace amrvk
