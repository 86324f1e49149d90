#pragma once
// Dependency-free charts for benchmark reports: line plots (linear or log axes) and grouped bar
// charts, rasterised on the CPU into 8-bit RGBA images and written as PNG.
// Coordinates: pixel (x, y) with row 0 = top, x fastest (Image8). Text uses a built-in
// 5x7 bitmap font with descenders (printable ASCII 32..126; other bytes draw as '?') at scale 2
// when both sides are >= 400 px, else 1. The legend sits in a data-free corner inside the plot
// area (top-right first) when small, else right of it (smaller text, columns, shortened labels).
// Guarantees: rendering is deterministic (same input -> identical pixels), every pixel is opaque
// (alpha 255), nothing is drawn outside the image, and degenerate data (no series, no finite
// points, a single point, zero range, millions of points) renders an image instead of throwing.
// Only a width or height outside [64, 8192] pixels throws amrvk::Error.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/image_io.h"

namespace amrvk::bench {

struct Rgb8 {
    uint8_t r = 0, g = 0, b = 0;
    bool operator==(const Rgb8&) const = default;
};

// Okabe-Ito colour-blind-friendly categorical palette (7 colours, no black or yellow-on-white),
// then the same hues darkened for indices 7..13, lightened for 14..20, and so on, cyclically.
Rgb8 paletteColor(size_t i);

enum class LineStyle { Solid, Dashed };

struct PlotSeries {
    std::string label;           // legend text; an empty label leaves the series out of the legend
    std::vector<double> x, y;    // same length (extra entries of the longer one are ignored); points
                                 // with non-finite values, or <= 0 on a log axis, are skipped
    LineStyle style = LineStyle::Solid;
    bool markers = true;         // small square marker at each point
    std::optional<Rgb8> color;   // default paletteColor(series index)
};

struct LinePlot {
    std::string title, xLabel, yLabel;
    bool logX = false, logY = false;
    std::vector<PlotSeries> series;
    int width = 960, height = 640;  // pixels, each in [64, 8192]
};

struct BarGroup {
    std::string label;           // x-axis label of the group
    std::vector<double> values;  // one bar per category; missing, non-finite (or <= 0 on log) -> no bar
};

struct BarChart {
    std::string title, yLabel;
    bool logY = false;
    std::vector<std::string> categories;  // legend entries, one colour each (paletteColor(i))
    std::vector<BarGroup> groups;         // x-axis groups
    int width = 960, height = 640;        // pixels, each in [64, 8192]
};

// The plot area (inside the black frame) and the data-to-pixel mapping a render used, so callers
// and tests can locate data points. Pixel coordinates are continuous: pixel (i, j) covers
// [i, i+1) x [j, j+1); row 0 = top.
struct PlotFrame {
    int left = 0, top = 0, right = 0, bottom = 0;  // frame lines, pixels (inclusive)
    double x0 = 0, x1 = 1, y0 = 0, y1 = 1;         // axis ranges (data units, also on log axes)
    bool logX = false, logY = false;
    double pixelX(double x) const;  // data x -> pixel column (x0 -> left, x1 -> right)
    double pixelY(double y) const;  // data y -> pixel row (y0 -> bottom, y1 -> top)
};

// The frame renderLinePlot / renderBarChart use for this input (bar charts: x0 = 0, x1 = number
// of groups, group g spans [g, g+1)). Throws like the renderers for an invalid size.
PlotFrame linePlotFrame(const LinePlot& plot);
PlotFrame barChartFrame(const BarChart& chart);

Image8 renderLinePlot(const LinePlot& plot);
Image8 renderBarChart(const BarChart& chart);

// Renders and writes a PNG (writePng8): throws on a write failure, leaving no file.
void writeLinePlot(const std::filesystem::path& png, const LinePlot& plot);
void writeBarChart(const std::filesystem::path& png, const BarChart& chart);

}  // namespace amrvk::bench
