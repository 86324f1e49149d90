#pragma once
// Text as coverage bitmaps, rasterised by FreeType from a font file (Debian's DejaVu Sans by
// default): the legend's labels (session/legend_image.*). amrvk builds without FreeType (CMake
// option AMRVK_FREETYPE, on where libfreetype-dev is found); then constructing a Font throws one
// line saying why.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string_view>
#include <vector>

namespace amrvk {

// Debian's fonts-dejavu-core.
inline constexpr const char* kDefaultFontFile = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

// True when this amrvk was built with FreeType.
bool fontRenderingAvailable();

// 8-bit coverage of a line of text (0 = none, 255 = full), row 0 = top, x fastest. `height` is the
// font's line box at its pixel size (ascender - descender), `baseline` the row of the baseline in it.
struct TextBitmap {
    int width = 0, height = 0, baseline = 0;
    std::vector<uint8_t> coverage;
    uint8_t at(int x, int y) const { return coverage[size_t(x) + size_t(width) * size_t(y)]; }
};

class Font {
public:
    // Reads the whole file (a regular file of at most 64 MiB) and opens its first face. Throws one
    // line: "FILE: no such file", "FILE: not a font FreeType can read (error N)", or, built without
    // FreeType, "cannot draw text: this amrvk was built without FreeType (libfreetype-dev)".
    explicit Font(const std::filesystem::path& file);
    ~Font();
    Font(const Font&) = delete;
    Font& operator=(const Font&) = delete;

    // `utf8` at `pixelSize` (em height in pixels, 4..512): glyphs antialiased, advanced with kerning,
    // coverage of overlapping glyphs added (saturating). Bytes that are not UTF-8 draw U+FFFD;
    // characters the font lacks draw its missing-glyph box. Not thread-safe.
    TextBitmap render(std::string_view utf8, int pixelSize) const;
    // Width render() would give, without drawing.
    int width(std::string_view utf8, int pixelSize) const;

private:
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

// Code points of UTF-8 text; each byte of an invalid sequence becomes U+FFFD.
std::vector<char32_t> decodeUtf8(std::string_view text);

}  // namespace amrvk
