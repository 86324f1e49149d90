#pragma once
// Image files: PNG (8-bit sRGB, tone mapped), PFM and OpenEXR (linear float RGB). Every writer
// goes through AtomicFileWriter, so a failed write leaves no file behind.
#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <vector>

namespace amrvk {

// Linear RGB(A) pixels, row 0 = top, x fastest: pixels[x + width * y].
struct Image {
    int width = 0;
    int height = 0;
    std::vector<glm::vec4> pixels;

    Image() = default;
    Image(int w, int h, glm::vec4 fill = glm::vec4(0.0f))
        : width(w), height(h), pixels(size_t(w > 0 ? w : 0) * size_t(h > 0 ? h : 0), fill) {}
    glm::vec4& at(int x, int y) { return pixels[size_t(x) + size_t(width) * size_t(y)]; }
    const glm::vec4& at(int x, int y) const { return pixels[size_t(x) + size_t(width) * size_t(y)]; }
};

// 8-bit RGBA pixels as stored in a PNG, row 0 = top.
struct Image8 {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgba;  // 4 bytes per pixel
};

// sRGB encoding of a linear value clamped to [0, 1] (NaN -> 0), rounded to 8 bits.
uint8_t encodeSrgb8(float linear);

// `src` scaled to width x height (> 0) bilinearly, pixel centres mapped onto pixel centres and
// edges clamped: what the viewer's display pass shows of a smaller preview (passes/display.comp).
Image scaledBilinear(const Image& src, int width, int height);

// Writes by extension (case-insensitive):
//   .png  8-bit sRGB RGBA: each linear channel clamped to [0, 1], sRGB curve, alpha 255;
//   .pfm  linear float RGB, little-endian (scale -1), rows bottom to top as the format requires;
//   .exr  linear float RGB (tinyexr): single-part, uncompressed scanlines, channels B, G, R as FLOAT.
// The alpha channel is written only to PNG (as 255). Throws for an unknown extension, an image
// whose size does not match its pixels, or a write failure (leaving no file).
void writeImage(const std::filesystem::path& path, const Image& image);

// The PNG file writeImage would write for `image`, as bytes (a notebook's inline picture).
std::vector<uint8_t> pngBytes(const Image& image);

// Writes 8-bit RGBA pixels to a PNG as they are (no tone mapping, alpha kept). Throws for a size
// outside [1, 2^20] per axis, rgba.size() != 4 * width * height, or a write failure (leaving no file).
void writePng8(const std::filesystem::path& path, const Image8& image);

// Readers for tests and reference images: PFM (RGB or grey, either byte order), OpenEXR
// (tinyexr: single-part scanline, any compression it supports, HALF or FLOAT channels; R, G, B, A
// by name, missing colour channels 0, missing A 1), PNG (raw 8-bit RGBA). Alpha of PFM is 1.
Image readPfm(const std::filesystem::path& path);
Image readExr(const std::filesystem::path& path);
Image8 readPng(const std::filesystem::path& path);

}  // namespace amrvk
