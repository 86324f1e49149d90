#include "core/font.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/file_io.h"

#if AMRVK_FREETYPE
#include <ft2build.h>
#include FT_FREETYPE_H
#endif

namespace fs = std::filesystem;

namespace amrvk {

namespace {
constexpr uint64_t kMaxFontBytes = uint64_t(64) << 20;
constexpr char32_t kReplacement = 0xFFFD;
}  // namespace

std::vector<char32_t> decodeUtf8(std::string_view text) {
    std::vector<char32_t> out;
    size_t i = 0;
    while (i < text.size()) {
        const auto b = uint8_t(text[i]);
        int extra = b < 0x80 ? 0 : (b >> 5) == 6 ? 1 : (b >> 4) == 14 ? 2 : (b >> 3) == 30 ? 3 : -1;
        char32_t cp = extra == 0 ? b : extra == 1 ? (b & 0x1F) : extra == 2 ? (b & 0x0F) : (b & 0x07);
        bool ok = extra >= 0 && i + size_t(extra) < text.size();
        for (int k = 1; ok && k <= extra; ++k) {
            const auto c = uint8_t(text[i + size_t(k)]);
            ok = (c >> 6) == 2;
            cp = (cp << 6) | (c & 0x3F);
        }
        // Overlong forms, surrogates and values past U+10FFFF are not UTF-8.
        static constexpr char32_t kMin[4] = {0, 0x80, 0x800, 0x10000};
        if (ok && (cp < kMin[extra] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF))) ok = false;
        if (ok) {
            out.push_back(cp);
            i += size_t(extra) + 1;
        } else {
            out.push_back(kReplacement);
            ++i;
        }
    }
    return out;
}

#if AMRVK_FREETYPE

bool fontRenderingAvailable() { return true; }

struct Font::Impl {
    FT_Library library = nullptr;
    FT_Face face = nullptr;
    std::vector<uint8_t> bytes;  // FreeType reads the face from here while it lives
    std::string file;
    ~Impl() {
        if (face) FT_Done_Face(face);
        if (library) FT_Done_FreeType(library);
    }
    void setSize(int pixelSize) const {
        AMRVK_CHECK(pixelSize >= 4 && pixelSize <= 512, "font size ", pixelSize, " px is outside [4, 512]");
        const FT_Error e = FT_Set_Pixel_Sizes(face, 0, FT_UInt(pixelSize));
        AMRVK_CHECK(e == 0, file, ": cannot scale the font to ", pixelSize, " px (FreeType error ", int(e), ")");
    }
    // Calls glyph(slot, penX) for every character, pen in pixels; returns the advance width.
    template <typename Draw>
    int layout(std::string_view utf8, Draw draw) const {
        FT_Pos pen = 0;  // 26.6 fixed point
        FT_UInt previous = 0;
        int right = 0;
        const bool kerning = FT_HAS_KERNING(face);
        for (char32_t cp : decodeUtf8(utf8)) {
            const FT_UInt index = FT_Get_Char_Index(face, FT_ULong(cp));
            if (kerning && previous && index) {
                FT_Vector delta{};
                if (FT_Get_Kerning(face, previous, index, FT_KERNING_DEFAULT, &delta) == 0) pen += delta.x;
            }
            const FT_Error e = FT_Load_Glyph(face, index, FT_LOAD_RENDER);
            AMRVK_CHECK(e == 0, file, ": cannot draw character U+", std::hex, uint32_t(cp), " (FreeType error ",
                        std::dec, int(e), ")");
            const int penX = int((pen + 32) >> 6);
            draw(face->glyph, penX);
            right = std::max(right, penX + face->glyph->bitmap_left + int(face->glyph->bitmap.width));
            pen += face->glyph->advance.x;
            previous = index;
        }
        return std::max(right, int((pen + 63) >> 6));
    }
};

Font::Font(const fs::path& path) : mImpl(std::make_unique<Impl>()) {
    Impl& f = *mImpl;
    f.file = path.string();
    const uint64_t size = fileSize(path);
    AMRVK_CHECK(size > 0 && size <= kMaxFontBytes, f.file, ": ", size, " bytes is not a font size amrvk reads (1 to ",
                kMaxFontBytes, ")");
    BinaryReader in(path);
    in.readArray(f.bytes, size);
    FT_Error e = FT_Init_FreeType(&f.library);
    AMRVK_CHECK(e == 0, "cannot start FreeType (error ", int(e), ")");
    e = FT_New_Memory_Face(f.library, f.bytes.data(), FT_Long(f.bytes.size()), 0, &f.face);
    if (e) f.face = nullptr;
    AMRVK_CHECK(e == 0, f.file, ": not a font FreeType can read (error ", int(e), ")");
    AMRVK_CHECK(FT_IS_SCALABLE(f.face), f.file, ": not a scalable font (amrvk draws text at any size)");
}

Font::~Font() = default;

int Font::width(std::string_view utf8, int pixelSize) const {
    mImpl->setSize(pixelSize);
    return mImpl->layout(utf8, [](FT_GlyphSlot, int) {});
}

TextBitmap Font::render(std::string_view utf8, int pixelSize) const {
    const Impl& f = *mImpl;
    f.setSize(pixelSize);
    const FT_Size_Metrics& m = f.face->size->metrics;
    TextBitmap out;
    out.baseline = int((m.ascender + 63) >> 6);
    out.height = out.baseline + int((-m.descender + 63) >> 6);
    out.width = f.layout(utf8, [](FT_GlyphSlot, int) {});
    out.coverage.assign(size_t(std::max(out.width, 0)) * size_t(out.height), 0);
    f.layout(utf8, [&](FT_GlyphSlot g, int penX) {
        const FT_Bitmap& b = g->bitmap;
        AMRVK_CHECK(b.pixel_mode == FT_PIXEL_MODE_GRAY || b.rows == 0, f.file, ": glyph bitmap mode ",
                    int(b.pixel_mode), " (expected 8-bit grey)");
        for (int r = 0; r < int(b.rows); ++r) {
            const int y = out.baseline - g->bitmap_top + r;
            if (y < 0 || y >= out.height) continue;
            for (int c = 0; c < int(b.width); ++c) {
                const int x = penX + g->bitmap_left + c;
                if (x < 0 || x >= out.width) continue;
                uint8_t& dst = out.coverage[size_t(x) + size_t(out.width) * size_t(y)];
                dst = uint8_t(std::min(255, int(dst) + int(b.buffer[r * b.pitch + c])));
            }
        }
    });
    return out;
}

#else  // built without FreeType

bool fontRenderingAvailable() { return false; }

struct Font::Impl {};

Font::Font(const fs::path&) {
    AMRVK_CHECK(false,
                "cannot draw text: this amrvk was built without FreeType (install libfreetype-dev and "
                "rebuild)");
}
Font::~Font() = default;
int Font::width(std::string_view, int) const { return 0; }
TextBitmap Font::render(std::string_view, int) const { return {}; }

#endif

}  // namespace amrvk
