#pragma once
// The colour legend: its settings (a part of the session, so `render --session` and the viewer
// agree) and what it shows: the title and the ticks of the TF's value axis. Vulkan-free; drawn into
// PNGs by session/legend_image.* and in the viewer by viewer/legend_overlay.*.
//
// The axis is the TF's: field units, or log10 of the field for a log scale (`--scale log`: the TF
// is laid over log10 of each cell's value, docs/formats.md "Log-scaled fields").
//  - linear: "nice" ticks, steps of 1, 2 or 5 x 10^k, at most `maxMajor` labelled, minor ticks
//    between them (5 per step of 1 or 5 x 10^k, 4 per step of 2 x 10^k);
//  - log: a tick at every decade 10^k inside the range, labelled "10" with the superscript k
//    (every 2nd, 5th, 10th, ... decade labelled when more than maxMajor fit), minor ticks at
//    m x 10^k, m = 2..9, when every decade is labelled; a range inside less than two decades gets
//    nice linear ticks of the value itself, placed at their log10;
//  - a degenerate range (lo == hi) has one labelled tick at lo; non-finite or reversed ends throw.
#include <string>
#include <string_view>
#include <vector>

namespace amrvk::session {

// Where the legend goes in a PNG: a strip to the right of the picture (the image gets wider, no
// data hidden), or over the picture's lower right corner on a translucent backdrop.
enum class LegendPlace { Side, Overlay };
LegendPlace parseLegendPlace(std::string_view text);  // "side" | "overlay"; throws otherwise
const char* legendPlaceName(LegendPlace place);

struct Legend {
    bool show = false;                      // PNGs of render and of viewer screenshots; the viewer's overlay
    LegendPlace place = LegendPlace::Side;  // PNGs only (the viewer draws it over the picture)
    std::string title;                      // empty: the field's name
    std::string units;                      // overrides the field's units (amr::Field::units); empty: those
    std::string font;                       // empty: Debian's DejaVu Sans (core/font.h kDefaultFontFile)
    bool operator==(const Legend&) const = default;
};

struct LegendTick {
    double position = 0;   // on the TF axis: field units, or log10 of the value for a log scale
    bool major = false;    // labelled
    std::string label;     // e.g. "0.25", "-3", "1.5e7"; a decade: "10"
    std::string exponent;  // a decade 10^k: "k" (drawn as a superscript); else empty
};

// Ticks over the TF axis [lo, hi], ascending by position, every one inside [lo, hi].
std::vector<LegendTick> legendTicks(double lo, double hi, bool logScale, int maxMajor = 6);

// The step of nice linear ticks: the smallest 1, 2 or 5 x 10^k that is at least span / maxTicks.
double niceStep(double span, int maxTicks);
// A tick value as text with as many digits as the step needs: fixed point ("0.25", "-40") while
// |value| and `magnitude` (the axis's largest, so one legend keeps one form) are < 1e5 and
// step >= 1e-4, else scientific ("1.5e7", "2.50e-9"); 0 is "0".
std::string tickLabel(double value, double step, double magnitude = 0);

// The longest title or units text a legend takes, in bytes.
inline constexpr size_t kMaxLegendTextBytes = 256;
// "" when `text` fits a title or units (at most kMaxLegendTextBytes), else why not ("300 bytes (at
// most 256)"): the words of every front end (session/setting_table.cpp's rows).
std::string legendTextError(const std::string& text);
// Throws one line naming --legend-title or --legend-units (Python: legend_title, legend_units) when
// either is longer than kMaxLegendTextBytes: said where it is set, not when a picture is drawn.
void checkLegendText(const Legend& legend);

// The legend's title: the settings' title or the field's name, with " (log10 scale)" for a log scale.
std::string legendTitle(const Legend& legend, const std::string& field, bool logScale);
// The legend's units line: the settings' units (--legend-units) or else the field's own
// (amr::Field::units, e.g. "code units (1 = 2.4967e-29 g/cm^3)"); empty: no units line.
std::string legendUnits(const Legend& legend, const std::string& fieldUnits);

}  // namespace amrvk::session
