#pragma once
// The colour legend drawn into a picture, for PNG files (`render --legend`, the viewer's
// screenshots with the legend on): a vertical colour bar of the TF's colours (highest value at
// the top) with, on its left, a strip of the same colours at their opacity over a checkerboard,
// tick marks and labels on its right (session/legend.h), the title (the field, "(log10 scale)"
// for a log scale) and the units above. Text is drawn by FreeType (core/font.h). Vulkan-free.
//
// Placement (LegendPlace): Side puts the legend in a strip right of the picture (the image gets
// wider by the strip; every picture pixel is kept as it is); Overlay puts it over the picture's
// lower right corner on a backdrop of opacity 0.8 (the image keeps its size).
// Sizes follow the picture's height: the font is H / 22 pixels (9 to 48).
#include <filesystem>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

#include "core/font.h"
#include "core/image_io.h"
#include "scene/transfer_function.h"
#include "session/legend.h"
#include "session/pixel_rect.h"
#include "session/session.h"

namespace amrvk::session {

// What the legend shows.
struct LegendContent {
    std::string title;      // legendTitle(): the title or field, "(log10 scale)" noted
    std::string units;      // empty: no units line
    double lo = 0, hi = 0;  // the TF axis shown: the TF's first and last node (log10 of the field for a log scale)
    bool logScale = false;
    scene::TransferFunction tf;  // the picture's albedo (scene::albedoOf: linear), shown sRGB encoded
};
// A session's legend: its TF, field, scale and legend settings; `fieldUnits` is the shown field's
// own units (scene::Volume::field().units), what the units line says unless legend.units is set.
LegendContent legendContent(const Session& s, const std::string& fieldUnits);

// The font a legend draws with (legend.font, else core/font.h's kDefaultFontFile); errors are one
// line starting "--legend: " (a missing or unreadable font, a build without FreeType).
std::unique_ptr<Font> openLegendFont(const Legend& legend);

// Where everything goes, in the pixels of the image drawLegend returns.
struct LegendLayout {
    int width = 0, height = 0;    // the whole image
    PixelRect picture;            // the picture, copied unchanged (Overlay: under the block)
    PixelRect block;              // the legend's backdrop (Side: the whole strip)
    PixelRect opacityBar;         // TF colour at opacity alpha / (the TF's largest alpha) over a checkerboard
    PixelRect colorBar;           // TF colour, opaque: row y shows legendBarValue(y)
    PixelRect tickMarks;          // the tick lines, right of the colour bar
    std::vector<PixelRect> text;  // the only places text is drawn: title and units, tick labels
    int fontPx = 0, superscriptPx = 0, lineHeight = 0;
    std::vector<LegendTick> ticks;  // legendTicks() with as many labels as the bar's height holds
};
LegendLayout legendLayout(int pictureWidth, int pictureHeight, const LegendContent& content, LegendPlace place,
                          const Font& font);
// The value on the TF axis row r (0 at the top) of a `rows`-row colour bar shows: hi at the top, lo
// at the bottom, at row centres (hi - (r + 0.5) / rows * (hi - lo)); lo for a degenerate range.
// The PNG legend and the viewer's overlay both lay their bars out with these two.
double legendRowValue(const LegendContent& content, int row, int rows);
// The row (0 at the top) of a `rows`-row bar a tick at `position` is drawn on.
int legendRowOfTick(const LegendContent& content, double position, int rows);
// The same in the pixels of the image drawLegend returns.
double legendBarValue(const LegendLayout& layout, const LegendContent& content, int y);
int legendTickRow(const LegendLayout& layout, const LegendContent& content, double position);

// Linear colours of the legend: backdrop, text and tick marks, the checkerboard's two greys.
inline constexpr glm::vec3 kLegendBackdrop{0.02f, 0.02f, 0.02f};
inline constexpr glm::vec3 kLegendInk{1.0f, 1.0f, 1.0f};
inline constexpr float kCheckerDark = 0.25f, kCheckerLight = 0.6f;

// The picture with its legend (linear RGB, like the picture; PNG writing tone-maps both). Throws one
// line when the picture is too small to hold one (the size it needs), or the title or units are
// longer than 256 bytes or would make the legend wider than 40 font sizes.
Image drawLegend(const Image& picture, const LegendContent& content, LegendPlace place, const Font& font);

// What `render` and its series frames do with a session's legend: before the render, throw the
// size it needs when s's picture cannot hold it; after, write the picture to `path` with the legend
// drawn, or as it is when `font` is null (no legend, or not a PNG).
void checkLegendFits(const Session& s, const std::string& fieldUnits, const Font& font);
void writePicture(const std::filesystem::path& path, const Image& picture, const Session& s,
                  const std::string& fieldUnits, const Font* font);

}  // namespace amrvk::session
