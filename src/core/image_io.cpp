#include "core/image_io.h"

#include <png.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <string>

#include "core/error.h"
#include "core/file_io.h"

namespace fs = std::filesystem;

namespace amrvk {

// PFM and EXR are little-endian; values are written and read with memcpy of native floats.
static_assert(std::endian::native == std::endian::little, "image_io assumes a little-endian host");

namespace {

constexpr uint32_t kExrMagic = 20000630;  // bytes 76 2f 31 01
constexpr int32_t kExrFloat = 2;          // pixel type FLOAT
constexpr int kMaxDimension = 1 << 20;

std::string lowerExtension(const fs::path& path) {
    std::string ext = path.extension().string();
    for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return ext;
}

void checkImage(const fs::path& path, const Image& image) {
    AMRVK_CHECK(image.width > 0 && image.height > 0 && image.width <= kMaxDimension &&
                    image.height <= kMaxDimension,
                path.string(), ": image size ", image.width, "x", image.height,
                " is not in [1, ", kMaxDimension, "] per axis");
    AMRVK_CHECK(image.pixels.size() == size_t(image.width) * size_t(image.height), path.string(),
                ": image ", image.width, "x", image.height, " has ", image.pixels.size(), " pixels");
}

// Little-endian byte appender for headers.
class Bytes {
public:
    template <typename T>
    void put(T v) {
        const size_t at = mData.size();
        mData.resize(at + sizeof(T));
        std::memcpy(mData.data() + at, &v, sizeof(T));
    }
    void putString(const char* s) { mData.insert(mData.end(), s, s + std::strlen(s) + 1); }
    // EXR attribute: name, type, int32 size, then the value appended by the caller.
    void attribute(const char* name, const char* type, int32_t size) {
        putString(name);
        putString(type);
        put(size);
    }
    const std::vector<uint8_t>& data() const { return mData; }

private:
    std::vector<uint8_t> mData;
};

// Encodes 8-bit RGBA pixels (row 0 = top) as PNG and writes them through AtomicFileWriter.
void writePngRgba(const fs::path& path, int width, int height, const uint8_t* rgba) {
    png_image png;
    std::memset(&png, 0, sizeof(png));
    png.version = PNG_IMAGE_VERSION;
    png.width = static_cast<png_uint_32>(width);
    png.height = static_cast<png_uint_32>(height);
    png.format = PNG_FORMAT_RGBA;
    png_alloc_size_t bytes = 0;
    bool ok = png_image_write_to_memory(&png, nullptr, &bytes, 0, rgba, 0, nullptr) != 0;
    std::vector<uint8_t> encoded(ok ? bytes : 0);
    if (ok) ok = png_image_write_to_memory(&png, encoded.data(), &bytes, 0, rgba, 0, nullptr) != 0;
    std::string message = png.message;
    png_image_free(&png);
    AMRVK_CHECK(ok, path.string(), ": PNG encoding failed (", message, ")");
    AtomicFileWriter out(path);
    out.write(encoded.data(), bytes);
    out.commit();
}

void writePng(const fs::path& path, const Image& image) {
    std::vector<uint8_t> rgba(image.pixels.size() * 4);
    for (size_t i = 0; i < image.pixels.size(); ++i) {
        for (int k = 0; k < 3; ++k) rgba[4 * i + size_t(k)] = encodeSrgb8(image.pixels[i][k]);
        rgba[4 * i + 3] = 255;
    }
    writePngRgba(path, image.width, image.height, rgba.data());
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

void writeExr(const fs::path& path, const Image& image) {
    const int32_t w = image.width, h = image.height;
    Bytes header;
    header.put(kExrMagic);
    header.put(int32_t(2));  // version 2, single-part scanline, short names
    const char* channels[] = {"B", "G", "R"};
    header.attribute("channels", "chlist", 3 * (2 + 16) + 1);
    for (const char* c : channels) {
        header.putString(c);
        header.put(kExrFloat);
        header.put(uint32_t(0));  // pLinear 0, three reserved bytes
        header.put(int32_t(1));   // xSampling
        header.put(int32_t(1));   // ySampling
    }
    header.put(uint8_t(0));
    header.attribute("compression", "compression", 1);
    header.put(uint8_t(0));  // NO_COMPRESSION
    for (const char* window : {"dataWindow", "displayWindow"}) {
        header.attribute(window, "box2i", 16);
        header.put(int32_t(0));
        header.put(int32_t(0));
        header.put(w - 1);
        header.put(h - 1);
    }
    header.attribute("lineOrder", "lineOrder", 1);
    header.put(uint8_t(0));  // INCREASING_Y
    header.attribute("pixelAspectRatio", "float", 4);
    header.put(1.0f);
    header.attribute("screenWindowCenter", "v2f", 8);
    header.put(0.0f);
    header.put(0.0f);
    header.attribute("screenWindowWidth", "float", 4);
    header.put(1.0f);
    header.put(uint8_t(0));  // end of header

    const uint64_t rowBytes = uint64_t(w) * 3 * sizeof(float);
    const uint64_t firstChunk = header.data().size() + uint64_t(h) * sizeof(uint64_t);
    for (int32_t y = 0; y < h; ++y) header.put(uint64_t(firstChunk + uint64_t(y) * (8 + rowBytes)));

    AtomicFileWriter out(path);
    out.write(header.data().data(), header.data().size());
    std::vector<float> row(size_t(w) * 3);
    for (int32_t y = 0; y < h; ++y) {
        for (int c = 0; c < 3; ++c)  // channel order B, G, R
            for (int x = 0; x < w; ++x) row[size_t(c * w + x)] = image.at(x, y)[2 - c];
        const int32_t chunkHead[2] = {y, static_cast<int32_t>(rowBytes)};
        out.write(chunkHead, sizeof(chunkHead));
        out.writeSpan(std::span<const float>(row));
    }
    out.commit();
}

std::vector<uint8_t> readAll(const fs::path& path) {
    BinaryReader in(path);
    std::vector<uint8_t> data;
    in.readArray(data, in.size());
    return data;
}

// Bounds-checked little-endian cursor over a file's bytes; errors name file and offset.
class Cursor {
public:
    Cursor(const fs::path& path, const std::vector<uint8_t>& data) : mPath(path), mData(data) {}
    template <typename T>
    T get() {
        need(sizeof(T));
        T v;
        std::memcpy(&v, mData.data() + mOffset, sizeof(T));
        mOffset += sizeof(T);
        return v;
    }
    std::string getString() {
        const auto* begin = mData.data() + mOffset;
        const auto* end = std::find(begin, mData.data() + mData.size(), uint8_t(0));
        AMRVK_CHECK(end != mData.data() + mData.size(), mPath.string(),
                    ": unterminated string at byte ", mOffset);
        std::string s(begin, end);
        mOffset += s.size() + 1;
        return s;
    }
    void need(uint64_t bytes) const {
        AMRVK_CHECK(mOffset + bytes <= mData.size(), mPath.string(), ": truncated at byte ",
                    mData.size(), " (needed ", bytes, " bytes at offset ", mOffset, ")");
    }
    void seek(uint64_t offset) {
        AMRVK_CHECK(offset <= mData.size(), mPath.string(), ": offset ", offset,
                    " is past the end (size ", mData.size(), " bytes)");
        mOffset = offset;
    }
    uint64_t offset() const { return mOffset; }

private:
    const fs::path& mPath;
    const std::vector<uint8_t>& mData;
    uint64_t mOffset = 0;
};

}  // namespace

uint8_t encodeSrgb8(float linear) {
    const double c = linear > 0.0f ? (linear < 1.0f ? double(linear) : 1.0) : 0.0;
    const double s = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
    return static_cast<uint8_t>(std::lround(std::clamp(s, 0.0, 1.0) * 255.0));
}

void writeImage(const fs::path& path, const Image& image) {
    const std::string ext = lowerExtension(path);
    AMRVK_CHECK(ext == ".png" || ext == ".pfm" || ext == ".exr", path.string(),
                ": unknown image extension '", ext, "' (expected .png, .pfm or .exr)");
    checkImage(path, image);
    if (ext == ".png") writePng(path, image);
    else if (ext == ".pfm") writePfm(path, image);
    else writeExr(path, image);
}

void writePng8(const fs::path& path, const Image8& image) {
    AMRVK_CHECK(image.width > 0 && image.height > 0 && image.width <= kMaxDimension &&
                    image.height <= kMaxDimension,
                path.string(), ": image size ", image.width, "x", image.height,
                " is not in [1, ", kMaxDimension, "] per axis");
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
    AMRVK_CHECK(width > 0 && height > 0 && width <= kMaxDimension && height <= kMaxDimension, file,
                ": PFM size ", width, "x", height, " is not in [1, ", kMaxDimension, "] per axis");
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
    Cursor in(path, data);
    AMRVK_CHECK(in.get<uint32_t>() == kExrMagic, file, ": not an OpenEXR file (bad magic)");
    const uint32_t version = in.get<uint32_t>();
    AMRVK_CHECK((version & 0xff) == 2 && (version & 0x1a00) == 0, file, ": OpenEXR version field 0x",
                std::hex, version, std::dec, " is not a single-part scanline version 2 file");
    struct Channel {
        std::string name;
        int32_t type;
    };
    std::vector<Channel> channels;
    int32_t window[4] = {0, 0, -1, -1};
    bool haveWindow = false;
    for (;;) {
        const std::string name = in.getString();
        if (name.empty()) break;
        const std::string type = in.getString();
        const int32_t size = in.get<int32_t>();
        AMRVK_CHECK(size >= 0, file, ": attribute '", name, "' has negative size ", size);
        in.need(uint64_t(size));
        const uint64_t next = in.offset() + uint64_t(size);
        if (name == "channels") {
            for (;;) {
                std::string channel = in.getString();
                if (channel.empty()) break;
                const int32_t pixelType = in.get<int32_t>();
                in.get<uint32_t>();
                const int32_t xs = in.get<int32_t>(), ys = in.get<int32_t>();
                AMRVK_CHECK(pixelType == kExrFloat && xs == 1 && ys == 1, file, ": channel '",
                            channel, "' is not an unsampled FLOAT channel (only those are read)");
                channels.push_back({channel, pixelType});
            }
        } else if (name == "compression") {
            const auto compression = in.get<uint8_t>();
            AMRVK_CHECK(compression == 0, file, ": compression ", int(compression),
                        " is not supported (only NONE)");
        } else if (name == "dataWindow") {
            for (int32_t& v : window) v = in.get<int32_t>();
            haveWindow = true;
        }
        in.seek(next);
    }
    AMRVK_CHECK(haveWindow && !channels.empty(), file, ": missing dataWindow or channels attribute");
    const int64_t width = int64_t(window[2]) - window[0] + 1, height = int64_t(window[3]) - window[1] + 1;
    AMRVK_CHECK(width > 0 && height > 0 && width <= kMaxDimension && height <= kMaxDimension, file,
                ": dataWindow size ", width, "x", height, " is not in [1, ", kMaxDimension, "] per axis");
    Image image(int(width), int(height), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    const uint64_t rowBytes = uint64_t(width) * channels.size() * sizeof(float);
    std::vector<uint64_t> offsets(static_cast<size_t>(height));
    for (uint64_t& o : offsets) o = in.get<uint64_t>();
    for (uint64_t chunkOffset : offsets) {
        in.seek(chunkOffset);
        const int64_t y = int64_t(in.get<int32_t>()) - window[1];
        const int32_t bytes = in.get<int32_t>();
        AMRVK_CHECK(y >= 0 && y < height && uint64_t(bytes) == rowBytes, file, ": scanline chunk at byte ",
                    chunkOffset, " has y ", y + window[1], " and ", bytes, " bytes (expected ", rowBytes, ")");
        for (const Channel& c : channels) {
            int k = c.name == "R" ? 0 : c.name == "G" ? 1 : c.name == "B" ? 2 : c.name == "A" ? 3 : -1;
            for (int64_t x = 0; x < width; ++x) {
                const float v = in.get<float>();
                if (k >= 0) image.at(int(x), int(y))[k] = v;
            }
        }
    }
    return image;
}

Image8 readPng(const fs::path& path) {
    const std::string file = path.string();
    fileSize(path);
    png_image png;
    std::memset(&png, 0, sizeof(png));
    png.version = PNG_IMAGE_VERSION;
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
