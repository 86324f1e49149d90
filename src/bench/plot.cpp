#include "bench/plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <optional>
#include <string_view>
#include <utility>

#include "core/error.h"

namespace amrvk::bench {
namespace {

constexpr int kMinSize = 64, kMaxSize = 8192;
constexpr Rgb8 kWhite{255, 255, 255}, kBlack{0, 0, 0}, kGrid{225, 225, 225}, kLegendBorder{150, 150, 150},
    kZeroLine{120, 120, 120};

// ---- Bitmap font ----------------------------------------------------------------------------
// One 5x8 cell per printable ASCII character 32..126 (this project's own design): byte r of the
// entry is row r (0 = top; rows 0..6 above the baseline, row 7 the descender), bit 4 = left column.
// At scale 1 a character advances 6 px; capitals are 7 px tall.
constexpr int kAdvance = 6;
constexpr int kCapHeight = 7;
constexpr int kCellHeight = 8;
constexpr uint64_t kFont[95] = {
    0x00000000000000, 0x04000404040404, 0x00000000000a0a, 0x0a0a1f0a1f0a0a, 0x041e050e140f04,  //   ! " # $
    0x03130804021918, 0x0d12150814120c, 0x00000000080404, 0x02040808080402, 0x08040202020408,  // % & ' ( )
    0x0004150e150400, 0x0004041f040400, 0x8040c0000000000, 0x0000001f000000, 0x0c0c0000000000,  // * + , - .
    0x00100804020100, 0x0e11191513110e, 0x0e040404040c04, 0x1f08040201110e, 0x0e11010204021f,  // / 0 1 2 3
    0x02021f120a0602, 0x0e1101011e101f, 0x0e11111e100806, 0x0808080402011f, 0x0e11110e11110e,  // 4 5 6 7 8
    0x0c02010f11110e, 0x000c0c000c0c00, 0x8040c0c000c0c00, 0x02040810080402, 0x00001f001f0000,  // 9 : ; < =
    0x08040201020408, 0x0400040201110e, 0x0e15150d01110e, 0x1111111f11110e, 0x1e11111e11111e,  // > ? @ A B
    0x0e11101010110e, 0x1c12111111121c, 0x1f10101e10101f, 0x1010101e10101f, 0x0f11111710110e,  // C D E F G
    0x1111111f111111, 0x0e04040404040e, 0x0c120202020207, 0x11121418141211, 0x1f101010101010,  // H I J K L
    0x11111115151b11, 0x11111315191111, 0x0e11111111110e, 0x1010101e11111e, 0x0d12151111110e,  // M N O P Q
    0x1112141e11111e, 0x1e01010e10100f, 0x0404040404041f, 0x0e111111111111, 0x040a1111111111,  // R S T U V
    0x0a151515111111, 0x11110a040a1111, 0x040404040a1111, 0x1f10080402011f, 0x0e08080808080e,  // W X Y Z [
    0x00010204081000, 0x0e02020202020e, 0x00000000110a04, 0x1f00000000000000, 0x00000000000408,  // \ ] ^ _ `
    0x0f110f010e0000, 0x1e111119161010, 0x0e1110100e0000, 0x0f1111130d0101, 0x0e101f110e0000,  // a b c d e
    0x0808081c080906, 0xe010f11110f0000, 0x11111119161010, 0x0e0404040c0004, 0xc12020202060002,  // f g h i j
    0x12141814121010, 0x0e04040404040c, 0x111115151a0000, 0x11111119160000, 0x0e1111110e0000,  // k l m n o
    0x10101e11111e0000, 0x1010f11110f0000, 0x10101019160000, 0x1e010e100f0000, 0x060908081c0808,  // p q r s t
    0x0d131111110000, 0x040a1111110000, 0x0a151511110000, 0x110a040a110000, 0xe010f1111110000,  // u v w x y
    0x1f0804021f0000, 0x02040408040402, 0x04040404040404, 0x08040402040408, 0x00000215080000,  // z { | } ~
};

uint64_t glyphBits(char ch) {
    const auto u = static_cast<unsigned char>(ch);
    return kFont[(u < 32 || u > 126 ? unsigned('?') : unsigned(u)) - 32];
}

// Width in pixels of a text run at `scale` (no trailing spacing); 0 for "".
int textWidth(std::string_view text, int scale) {
    const size_t n = std::min<size_t>(text.size(), 4096);
    return n == 0 ? 0 : (int(n) * kAdvance - 1) * scale;
}

// Shortens text to at most maxWidth pixels at `scale`, marking a cut with "..".
std::string fitText(std::string_view text, int maxWidth, int scale) {
    if (textWidth(text, scale) <= maxWidth) return std::string(text);
    const int chars = (maxWidth / scale + 1) / kAdvance;
    if (chars <= 0) return {};
    if (chars < 4) return std::string(text.substr(0, size_t(chars)));
    return std::string(text.substr(0, size_t(chars - 2))) + "..";
}

// ---- Canvas ---------------------------------------------------------------------------------

struct Rect {
    int x0 = 0, y0 = 0, x1 = -1, y1 = -1;  // inclusive pixel bounds; empty when x1 < x0 or y1 < y0
    bool empty() const { return x1 < x0 || y1 < y0; }
    int width() const { return x1 - x0 + 1; }
    int height() const { return y1 - y0 + 1; }
    Rect grown(int d) const { return {x0 - d, y0 - d, x1 + d, y1 + d}; }
    Rect clipped(const Rect& o) const {
        return {std::max(x0, o.x0), std::max(y0, o.y0), std::min(x1, o.x1), std::min(y1, o.y1)};
    }
    bool intersects(const Rect& o) const { return !clipped(o).empty(); }
};

// Floor of a pixel coordinate, clamped to +-1e7 (NaN -> -1e7) so the int conversion is defined.
int toPixel(double v) {
    if (!(v > -1e7)) return -10000000;
    if (v > 1e7) return 10000000;
    return int(std::floor(v));
}

// An RGBA8 image with a clip rectangle; every write outside the clip is dropped.
class Canvas {
public:
    Canvas(int width, int height) {
        mImage.width = width;
        mImage.height = height;
        mImage.rgba.assign(size_t(width) * size_t(height) * 4, 255);
        mClip = bounds();
    }
    Rect bounds() const { return {0, 0, mImage.width - 1, mImage.height - 1}; }
    void setClip(const Rect& r) { mClip = r.clipped(bounds()); }
    void resetClip() { mClip = bounds(); }
    void fill(const Rect& r, Rgb8 c) {
        const Rect in = r.clipped(mClip);
        for (int y = in.y0; y <= in.y1; ++y) {
            uint8_t* p = &mImage.rgba[(size_t(in.x0) + size_t(mImage.width) * size_t(y)) * 4];
            for (int x = in.x0; x <= in.x1; ++x, p += 4) {
                p[0] = c.r;
                p[1] = c.g;
                p[2] = c.b;
                p[3] = 255;
            }
        }
    }
    void outline(const Rect& r, Rgb8 c) {
        fill({r.x0, r.y0, r.x1, r.y0}, c);
        fill({r.x0, r.y1, r.x1, r.y1}, c);
        fill({r.x0, r.y0, r.x0, r.y1}, c);
        fill({r.x1, r.y0, r.x1, r.y1}, c);
    }
    Image8 take() { return std::move(mImage); }

private:
    Image8 mImage;
    Rect mClip;
};

// Draws text with its top-left corner at (x, y). up: rotated 90 degrees counter-clockwise, reading
// bottom to top, with (x, y) the bottom-left corner of the rotated run.
void drawText(Canvas& cv, int x, int y, std::string_view text, int scale, Rgb8 color, bool up = false) {
    const size_t n = std::min<size_t>(text.size(), 4096);
    for (size_t i = 0; i < n; ++i) {
        const uint64_t bits = glyphBits(text[i]);
        for (int row = 0; row < kCellHeight; ++row) {
            for (int col = 0; col < 5; ++col) {
                if (((bits >> (8 * row + 4 - col)) & 1u) == 0) continue;
                const int u = (int(i) * kAdvance + col) * scale, v = row * scale;
                if (up) cv.fill({x + v, y - u - scale + 1, x + v + scale - 1, y - u}, color);
                else cv.fill({x + u, y + v, x + u + scale - 1, y + v + scale - 1}, color);
            }
        }
    }
}

// ---- Lines ----------------------------------------------------------------------------------

// Clips p(t) = a + t * d, t in [t0, t1], to the box [xmin, xmax] x [ymin, ymax] (Liang-Barsky);
// false when no part is inside.
bool clipSegment(double ax, double ay, double dx, double dy, double xmin, double ymin, double xmax,
                 double ymax, double& t0, double& t1) {
    const double p[4] = {-dx, dx, -dy, dy};
    const double q[4] = {ax - xmin, xmax - ax, ay - ymin, ymax - ay};
    for (int k = 0; k < 4; ++k) {
        if (p[k] == 0.0) {
            if (q[k] < 0.0) return false;
        } else if (p[k] < 0.0) {
            t0 = std::max(t0, q[k] / p[k]);
        } else {
            t1 = std::min(t1, q[k] / p[k]);
        }
    }
    return t0 <= t1;
}

// A 2 px wide pen; a dashed pen carries its phase (pixels travelled) from segment to segment.
struct Pen {
    Rgb8 color;
    bool dashed = false;
    double dashOn = 10, dashPeriod = 16;  // pixels
    double travelled = 0;
};

// Draws the segment between continuous pixel positions a and b (pixel (i, j) covers
// [i, i+1) x [j, j+1)), restricted to `box` (with a 2 px allowance for the pen).
void drawSegment(Canvas& cv, const Rect& box, double ax, double ay, double bx, double by, Pen& pen) {
    const double dx = bx - ax, dy = by - ay;
    const double length = std::hypot(dx, dy);
    if (!std::isfinite(length)) return;
    double t0 = 0.0, t1 = 1.0;
    if (clipSegment(ax, ay, dx, dy, box.x0 - 2.0, box.y0 - 2.0, box.x1 + 3.0, box.y1 + 3.0, t0, t1)) {
        const int steps = std::max(1, int(std::ceil(std::max(std::fabs(dx), std::fabs(dy)) * (t1 - t0))));
        for (int i = 0; i <= steps; ++i) {
            const double t = t0 + (t1 - t0) * double(i) / double(steps);
            if (pen.dashed && std::fmod(pen.travelled + t * length, pen.dashPeriod) >= pen.dashOn) continue;
            const int x = toPixel(ax + t * dx - 0.5), y = toPixel(ay + t * dy - 0.5);
            cv.fill({x, y, x + 1, y + 1}, pen.color);
        }
    }
    pen.travelled += length;
}

void drawMarker(Canvas& cv, double x, double y, int half, Rgb8 color) {
    const int px = toPixel(x), py = toPixel(y);
    cv.fill({px - half, py - half, px + half, py + half}, color);
}

// ---- Axes -----------------------------------------------------------------------------------

enum class TickKind { Major, Minor, LabelOnly };  // major: grid line, long mark, label

struct Tick {
    double value = 0;
    TickKind kind = TickKind::Major;
    std::string label;
};

// Position in [0, 1] of v on an axis from lo to hi; halves keep the linear case finite for any
// finite range.
double axisFraction(double v, double lo, double hi, bool log) {
    if (log) return (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo));
    return (v / 2 - lo / 2) / (hi / 2 - lo / 2);
}

struct AxisRange {
    double lo = 0, hi = 1;
    bool log = false;
};

// Data extent of the finite values added.
struct Extent {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -std::numeric_limits<double>::infinity();
    void add(double v) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    bool empty() const { return !(lo <= hi); }
};

// Linear range: the data plus 4% of its span on each side (bars: the range includes 0 and gets no
// margin on the zero side); a zero span grows by 10% of the value (or 1); no data -> [0, 1].
AxisRange linearRange(const Extent& e, bool bars) {
    constexpr double kMax = std::numeric_limits<double>::max();
    if (e.empty()) return {0.0, 1.0, false};
    double lo = e.lo, hi = e.hi;
    if (bars) {
        lo = std::min(lo, 0.0);
        hi = std::max(hi, 0.0);
        if (lo == hi) return {0.0, 1.0, false};
    }
    if (lo == hi) {
        const double pad = lo != 0.0 ? std::fabs(lo) * 0.1 : 1.0;
        lo -= pad;
        hi += pad;
    } else {
        const double pad = (hi / 2 - lo / 2) * 0.08;
        if (!bars || lo < 0.0) lo -= pad;
        if (!bars || hi > 0.0) hi += pad;
    }
    lo = std::max(lo, -kMax);
    hi = std::min(hi, kMax);
    if (!(hi / 2 - lo / 2 > 0.0)) {  // a span of a few denormals
        lo -= 1.0;
        hi += 1.0;
    }
    return {lo, hi, false};
}

// Log range: the positive data snapped out to whole decades (a single decade value v gets
// [v/10, 10v]; bars: the lower decade lies strictly below the smallest value, so every bar has a
// height); no data -> [1, 10]. Decades are kept within [1e-323, 1e308].
AxisRange logRange(const Extent& e, bool bars) {
    if (e.empty()) return {1.0, 10.0, true};
    const double la = std::log10(e.lo);
    double a = bars ? std::ceil(la) - 1.0 : std::floor(la), b = std::ceil(std::log10(e.hi));
    if (a == b) {
        a -= 1.0;
        b += 1.0;
    }
    a = std::clamp(a, -323.0, 307.0);
    b = std::clamp(b, a + 1.0, 308.0);
    return {std::pow(10.0, a), std::pow(10.0, b), true};
}

// The smallest 1, 2 or 5 times a power of ten that is >= raw.
double niceStep(double raw) {
    if (!(raw > 0.0) || !std::isfinite(raw)) return 1.0;
    const double base = std::pow(10.0, std::floor(std::log10(raw)));
    for (double m : {1.0, 2.0, 5.0})
        if (m * base >= raw * (1.0 - 1e-9)) return m * base;
    return 10.0 * base;
}

// Drops a '+' and leading zeros from a printf exponent: "1.5e+06" -> "1.5e6", "1e-05" -> "1e-5".
std::string tidyExponent(std::string s) {
    const size_t e = s.find('e');
    if (e == std::string::npos) return s;
    std::string mantissa = s.substr(0, e), exponent = s.substr(e + 1);
    bool negative = false;
    if (!exponent.empty() && (exponent[0] == '+' || exponent[0] == '-')) {
        negative = exponent[0] == '-';
        exponent.erase(0, 1);
    }
    const size_t nz = exponent.find_first_not_of('0');
    exponent = nz == std::string::npos ? "0" : exponent.substr(nz);
    return mantissa + "e" + (negative ? "-" : "") + exponent;
}

// A tick label with as many digits as the step needs: fixed notation for moderate magnitudes
// (|v| < 1e6, step >= 1e-4), otherwise the shortest exponent form ("2.5e6", "1e-5").
std::string linearLabel(double v, double step, double maxMagnitude) {
    if (std::fabs(v) < step * 1e-6) v = 0.0;
    char buf[64];
    if (maxMagnitude < 1e6 && step >= 1e-4) {
        const int decimals = std::clamp(int(std::ceil(-std::log10(step) - 1e-9)), 0, 10);
        std::snprintf(buf, sizeof(buf), "%.*f", decimals, v);
        return buf;
    }
    const int digits = std::clamp(
        int(std::floor(std::log10(maxMagnitude)) - std::floor(std::log10(step))) + 1, 1, 17);
    std::snprintf(buf, sizeof(buf), "%.*g", digits, v);
    return tidyExponent(buf);
}

// 10^k as "0.01", "0.1", "1", "10", "100" for |k| <= 2, else "1e-3", "1e3".
std::string decadeLabel(int k) {
    static const char* const kNear[] = {"0.01", "0.1", "1", "10", "100"};
    if (k >= -2 && k <= 2) return kNear[k + 2];
    return "1e" + std::to_string(k);
}

// Pixels a tick label needs along the axis (width plus a gap across x; twice the text height on y).
int labelRoom(const std::vector<Tick>& ticks, bool horizontal, int scale) {
    if (!horizontal) return 2 * kCellHeight * scale;
    int widest = 0;
    for (const Tick& t : ticks) widest = std::max(widest, textWidth(t.label, scale));
    return widest + 2 * kAdvance * scale;
}

// Major ticks at nice 1/2/5 steps, about one per 50 (x) or 30 (y) text-scale pixels, widened
// until the labels do not collide.
std::vector<Tick> linearTicks(const AxisRange& r, double lengthPx, bool horizontal, int scale) {
    const double span = r.hi / 2 - r.lo / 2;  // half the range, finite
    const double maxMagnitude = std::max(std::fabs(r.lo), std::fabs(r.hi));
    const double target = std::max(2.0, lengthPx / ((horizontal ? 50.0 : 30.0) * scale));
    double step = niceStep(span / target * 2);
    std::vector<Tick> previous;
    for (int attempt = 0; attempt < 64; ++attempt) {
        std::vector<Tick> ticks;
        const double i0 = std::ceil(r.lo / step - 1e-9), i1 = std::floor(r.hi / step + 1e-9);
        if (i1 - i0 < 500.0) {
            for (int k = 0; k <= int(i1 - i0); ++k) {
                const double v = (i0 + k) * step;
                ticks.push_back({v, TickKind::Major, linearLabel(v, step, maxMagnitude)});
            }
        }
        if (ticks.size() < 2 && !previous.empty()) return previous;
        const double pixelsPerStep = lengthPx * (step / 2) / span;
        if (!ticks.empty() && pixelsPerStep >= labelRoom(ticks, horizontal, scale)) return ticks;
        previous = std::move(ticks);
        step = niceStep(step * 1.01);
    }
    return previous;
}

// Decade ticks: labelled every `stride` decades (1, 2, 3, 5, 10, 20, ...) so labels do not collide,
// other decades as minor marks, and minor marks at 2..9 when a decade spans >= 40 px.
std::vector<Tick> logTicks(const AxisRange& r, double lengthPx, bool horizontal, int scale) {
    const int a = int(std::lround(std::log10(r.lo))), b = int(std::lround(std::log10(r.hi)));
    const double perDecade = lengthPx / std::max(1, b - a);
    int widest = 0;
    for (int k = a; k <= b; ++k) widest = std::max(widest, textWidth(decadeLabel(k), scale));
    const int room = horizontal ? widest + 2 * kAdvance * scale : 2 * kCellHeight * scale;
    int stride = 1;
    for (int mult = 1; stride * perDecade < room && mult < 1000; mult *= 10)
        for (int s : {1, 2, 3, 5})
            if ((stride = s * mult) * perDecade >= room) break;
    std::vector<Tick> ticks;
    for (int k = a; k <= b; ++k) {
        const bool major = ((k % stride) + stride) % stride == 0;
        if (major) ticks.push_back({std::pow(10.0, k), TickKind::Major, decadeLabel(k)});
        else if (perDecade >= 3.0) ticks.push_back({std::pow(10.0, k), TickKind::Minor, {}});
        if (perDecade >= 40.0 && k < b)
            for (int m = 2; m <= 9; ++m) ticks.push_back({m * std::pow(10.0, k), TickKind::Minor, {}});
    }
    return ticks;
}

// ---- Legend ---------------------------------------------------------------------------------

struct LegendItem {
    std::string label;
    Rgb8 color;
    LineStyle style = LineStyle::Solid;
    bool markers = false;
    bool bar = false;      // filled square swatch
    bool swatch = true;    // false for the "+N more" entry
};

// A measured legend: items in column-major order, box placed by the layout.
struct Legend {
    std::vector<LegendItem> items;
    Rect box;
    int scale = 1, cols = 1, rows = 0, colWidth = 0;
    int inner() const { return 3 * scale; }
    int rowHeight() const { return 10 * scale; }
    int swatchWidth() const { return 12 * scale; }
    int gap() const { return 3 * scale; }
    int colGap() const { return 6 * scale; }
    bool complete = true;  // every item shown with its full label
};

// Shortens text to at most maxWidth pixels at `scale` by cutting out its middle ("struc..ant 12"),
// which keeps the distinguishing ends of labels such as "variant 1" .. "variant 12".
std::string fitMiddle(std::string_view text, int maxWidth, int scale) {
    if (textWidth(text, scale) <= maxWidth) return std::string(text);
    const int chars = (maxWidth / scale + 1) / kAdvance;
    if (chars < 6) return fitText(text, maxWidth, scale);
    const size_t head = size_t(chars - 1) / 2, tail = size_t(chars - 2) - head;
    return std::string(text.substr(0, head)) + ".." + std::string(text.substr(text.size() - tail));
}

// The legend at text scale s in at most maxWidth x maxHeight pixels, in as many columns as needed;
// labels over 40 characters are shortened. cut: labels may be shortened further (to >= 4
// characters), and if even that does not fit, the first items and a final "+N more" are shown.
// Without cut, nothing when the full labels do not fit.
std::optional<Legend> tryLegend(const std::vector<LegendItem>& all, int maxWidth, int maxHeight, int s, bool cut) {
    Legend legend;
    legend.scale = s;
    const size_t n = all.size();
    const int maxRows = std::max(1, (maxHeight - 2 * legend.inner() + 2 * s) / legend.rowHeight());
    const size_t colsNeeded = (n + size_t(maxRows) - 1) / size_t(maxRows);
    int widest = 0;
    for (const LegendItem& it : all) widest = std::max(widest, textWidth(std::string_view(it.label).substr(0, 40), s));
    const int minLabel = std::min(widest, textWidth("abcd", s));
    const int fixed = legend.swatchWidth() + legend.gap();
    int cols = 0, labelWidth = 0;
    if (colsNeeded <= 64) {
        cols = int(colsNeeded);
        const int room = (maxWidth - 2 * legend.inner() + legend.colGap()) / cols - legend.colGap() - fixed;
        labelWidth = std::min(widest, room);
        if (labelWidth < (cut ? minLabel : widest)) cols = 0;
    }
    if (cols == 0 && !cut) return std::nullopt;
    size_t shown = n;
    if (cols == 0) {  // too many even with short labels: fixed narrow columns, then "+N more"
        labelWidth = minLabel;
        cols = std::max(1, (maxWidth - 2 * legend.inner() + legend.colGap()) / (fixed + labelWidth + legend.colGap()));
        const size_t capacity = size_t(cols) * size_t(maxRows);
        if (n > capacity) shown = capacity - 1;
    }
    legend.complete = shown == n && labelWidth >= widest;
    for (size_t i = 0; i < shown; ++i) {
        LegendItem it = all[i];
        it.label = fitMiddle(it.label, labelWidth, s);
        legend.items.push_back(std::move(it));
    }
    if (shown < n) {
        LegendItem more;
        more.swatch = false;
        more.label = fitText(strCat("+", n - shown, " more"), fixed + labelWidth, s);
        legend.items.push_back(std::move(more));
    }
    legend.cols = cols;
    legend.rows = int((legend.items.size() + size_t(cols) - 1) / size_t(cols));
    legend.colWidth = fixed + labelWidth;
    legend.box = {0, 0, 2 * legend.inner() + cols * legend.colWidth + (cols - 1) * legend.colGap() - 1,
                  2 * legend.inner() + legend.rows * legend.rowHeight() - 2 * s - 1};
    return legend;
}

// Fits the labelled items into at most maxWidth x maxHeight pixels: full labels at text scale
// `scale`, else full labels at scale 1, else shortened labels (and "+N more") at scale 1.
Legend measureLegend(const std::vector<LegendItem>& all, int maxWidth, int maxHeight, int scale) {
    if (all.empty()) return {};
    for (int s = scale; s >= 1; --s)
        if (std::optional<Legend> full = tryLegend(all, maxWidth, maxHeight, s, false)) return *full;
    return *tryLegend(all, maxWidth, maxHeight, 1, true);
}

void drawLegend(Canvas& cv, const Legend& legend) {
    if (legend.items.empty()) return;
    const int s = legend.scale;
    cv.fill(legend.box, kWhite);
    cv.outline(legend.box, kLegendBorder);
    for (size_t i = 0; i < legend.items.size(); ++i) {
        const LegendItem& it = legend.items[i];
        const int col = int(i) / legend.rows, row = int(i) % legend.rows;
        const int x = legend.box.x0 + legend.inner() + col * (legend.colWidth + legend.colGap());
        const int y = legend.box.y0 + legend.inner() + row * legend.rowHeight();
        int textX = x;
        if (it.swatch) {
            const int w = legend.swatchWidth();
            if (it.bar) {
                cv.fill({x + s, y, x + w - s - 1, y + kCapHeight * s - 1}, it.color);
            } else {
                Pen pen{it.color, it.style == LineStyle::Dashed, 3.0 * s, 5.0 * s, 0.0};
                const double mid = y + kCapHeight * s / 2.0;
                drawSegment(cv, cv.bounds(), x, mid, x + w, mid, pen);
                if (it.markers) drawMarker(cv, x + w / 2.0, mid, s, it.color);
            }
            textX += w + legend.gap();
        }
        drawText(cv, textX, y, it.label, s, kBlack);
    }
}

// ---- Layout ---------------------------------------------------------------------------------

struct ChartText {
    std::string_view title, xLabel, yLabel;
    int width = 0, height = 0;
};

struct Layout {
    int scale = 1, pad = 4, tickLength = 3;
    PlotFrame frame;
    std::vector<Tick> xTicks, yTicks;
    Legend legend;
    Rect plotRect() const { return {frame.left, frame.top, frame.right, frame.bottom}; }
};

// Whether data drawn with `frame` would lie under a legend box at `box`.
using Occupied = std::function<bool(const PlotFrame& frame, const Rect& box)>;

// Shrinks the margins a (first b) so that at least `inside` pixels of `total` remain between them.
void keepInside(int total, int inside, int& a, int& b) {
    int excess = a + b + inside - total;
    if (excess <= 0) return;
    const int fromB = std::min(b, excess);
    b -= fromB;
    excess -= fromB;
    a -= std::min(a, excess);
}

// Margins, frame, ticks and legend placement. The legend goes inside the plot area (first free
// corner of top-right, top-left, bottom-right, bottom-left) when it is small and some corner holds
// no data, else to the right of the plot area. xTicks: numeric unless the caller replaces them.
Layout layoutChart(const ChartText& text, const AxisRange& xr, const AxisRange& yr,
                   const std::vector<LegendItem>& items, const Occupied& occupied) {
    Layout L;
    const int w = text.width, h = text.height;
    const int s = std::min(w, h) >= 400 ? 2 : 1;
    L.scale = s;
    L.pad = 4 * s;
    L.tickLength = 3 * s;
    const int textHeight = kCellHeight * s;
    int top = 2 * L.pad + (text.title.empty() ? 0 : textHeight + L.pad / 2);
    int bottom = L.tickLength + L.pad / 2 + textHeight + (text.xLabel.empty() ? 0 : L.pad + textHeight) + L.pad;
    keepInside(h, std::max(8, h / 3), top, bottom);
    L.frame.top = top;
    L.frame.bottom = h - 1 - bottom;
    L.frame.x0 = xr.lo, L.frame.x1 = xr.hi, L.frame.logX = xr.log;
    L.frame.y0 = yr.lo, L.frame.y1 = yr.hi, L.frame.logY = yr.log;
    const double plotHeight = L.frame.bottom - L.frame.top;
    L.yTicks = yr.log ? logTicks(yr, plotHeight, false, s) : linearTicks(yr, plotHeight, false, s);
    int yLabelWidth = 0;
    for (const Tick& t : L.yTicks) yLabelWidth = std::max(yLabelWidth, textWidth(t.label, s));
    const int left0 = L.pad + (text.yLabel.empty() ? 0 : textHeight + L.pad) + yLabelWidth + L.pad / 2 + L.tickLength;

    auto place = [&](int rightMargin) {
        int left = left0, right = rightMargin;
        keepInside(w, std::max(8, w / 3), right, left);
        L.frame.left = left;
        L.frame.right = w - 1 - right;
    };
    place(3 * L.pad);
    bool inside = false;
    if (!items.empty() && items.size() <= 10) {
        L.legend = measureLegend(items, (L.frame.right - L.frame.left) * 45 / 100,
                                 (L.frame.bottom - L.frame.top) / 2, s);
        if (L.legend.complete && L.legend.cols == 1 && L.legend.scale == s) {
            const Rect area = L.plotRect().grown(-L.pad);
            const int bw = L.legend.box.width(), bh = L.legend.box.height();
            const Rect corners[4] = {{area.x1 - bw + 1, area.y0, area.x1, area.y0 + bh - 1},
                                     {area.x0, area.y0, area.x0 + bw - 1, area.y0 + bh - 1},
                                     {area.x1 - bw + 1, area.y1 - bh + 1, area.x1, area.y1},
                                     {area.x0, area.y1 - bh + 1, area.x0 + bw - 1, area.y1}};
            for (const Rect& c : corners) {
                if (!occupied(L.frame, c.grown(2))) {
                    L.legend.box = c;
                    inside = true;
                    break;
                }
            }
        }
    }
    if (!items.empty() && !inside) {
        L.legend = measureLegend(items, w * 2 / 5, L.frame.bottom - L.frame.top + 1, s);
        place(L.legend.box.width() + 3 * L.pad);
        const int x0 = L.frame.right + 2 * L.pad;
        L.legend.box = {x0, L.frame.top, x0 + L.legend.box.width() - 1, L.frame.top + L.legend.box.height() - 1};
    }
    const double plotWidth = L.frame.right - L.frame.left;
    L.xTicks = xr.log ? logTicks(xr, plotWidth, true, s) : linearTicks(xr, plotWidth, true, s);
    return L;
}

void drawGrid(Canvas& cv, const Layout& L) {
    const PlotFrame& f = L.frame;
    for (const Tick& t : L.xTicks) {
        if (t.kind != TickKind::Major) continue;
        const int x = toPixel(f.pixelX(t.value));
        if (x > f.left && x < f.right) cv.fill({x, f.top + 1, x, f.bottom - 1}, kGrid);
    }
    for (const Tick& t : L.yTicks) {
        if (t.kind != TickKind::Major) continue;
        const int y = toPixel(f.pixelY(t.value));
        if (y > f.top && y < f.bottom) cv.fill({f.left + 1, y, f.right - 1, y}, kGrid);
    }
}

// Frame, tick marks and labels, axis labels, title and legend.
void drawDecorations(Canvas& cv, const Layout& L, const ChartText& text) {
    const PlotFrame& f = L.frame;
    const int s = L.scale, w = text.width, h = text.height;
    const int textHeight = kCellHeight * s;
    cv.outline(L.plotRect(), kBlack);
    const int minorLength = (L.tickLength + 1) / 2;
    const int xLabelTop = f.bottom + L.tickLength + L.pad / 2 + 1;
    for (const Tick& t : L.xTicks) {
        const int x = toPixel(f.pixelX(t.value));
        if (x < f.left || x > f.right) continue;
        if (t.kind != TickKind::LabelOnly)
            cv.fill({x, f.bottom + 1, x, f.bottom + (t.kind == TickKind::Major ? L.tickLength : minorLength)}, kBlack);
        if (t.label.empty()) continue;
        const int tw = textWidth(t.label, s);
        drawText(cv, std::clamp(x - tw / 2, 0, std::max(0, w - tw)), xLabelTop, t.label, s, kBlack);
    }
    for (const Tick& t : L.yTicks) {
        const int y = toPixel(f.pixelY(t.value));
        if (y < f.top || y > f.bottom) continue;
        cv.fill({f.left - (t.kind == TickKind::Major ? L.tickLength : minorLength), y, f.left - 1, y}, kBlack);
        if (t.label.empty()) continue;
        const int tw = textWidth(t.label, s);
        const int ty = std::clamp(y - kCapHeight * s / 2, 0, std::max(0, h - textHeight));
        drawText(cv, f.left - L.tickLength - L.pad / 2 - tw, ty, t.label, s, kBlack);
    }
    if (!text.xLabel.empty()) {
        const std::string label = fitText(text.xLabel, w - 2 * L.pad, s);
        const int tw = textWidth(label, s);
        const int cx = (f.left + f.right) / 2;
        drawText(cv, std::clamp(cx - tw / 2, 0, std::max(0, w - tw)), xLabelTop + textHeight + L.pad, label, s,
                 kBlack);
    }
    if (!text.yLabel.empty()) {
        const std::string label = fitText(text.yLabel, h - 2 * L.pad, s);
        const int tw = textWidth(label, s);
        const int cy = (f.top + f.bottom) / 2;
        drawText(cv, L.pad, std::clamp(cy + tw / 2, tw - 1, h - 1), label, s, kBlack, true);
    }
    if (!text.title.empty()) {  // bold: drawn twice, 1 px apart
        const std::string title = fitText(text.title, w - 2 * L.pad - 1, s);
        const int tw = textWidth(title, s) + 1;
        const int x = std::max(0, (w - tw) / 2);
        drawText(cv, x, L.pad, title, s, kBlack);
        drawText(cv, x + 1, L.pad, title, s, kBlack);
    }
    drawLegend(cv, L.legend);
}

void checkSize(int width, int height) {
    AMRVK_CHECK(width >= kMinSize && width <= kMaxSize, "plot width ", width, " is not in [", kMinSize, ", ",
                kMaxSize, "] pixels");
    AMRVK_CHECK(height >= kMinSize && height <= kMaxSize, "plot height ", height, " is not in [", kMinSize,
                ", ", kMaxSize, "] pixels");
}

// ---- Line plots -----------------------------------------------------------------------------

bool pointValid(const LinePlot& plot, double x, double y) {
    return std::isfinite(x) && std::isfinite(y) && (!plot.logX || x > 0.0) && (!plot.logY || y > 0.0);
}

size_t pointCount(const PlotSeries& s) { return std::min(s.x.size(), s.y.size()); }

Rgb8 seriesColor(const LinePlot& plot, size_t i) { return plot.series[i].color.value_or(paletteColor(i)); }

int markerHalf(int scale) { return scale; }

Layout layoutLinePlot(const LinePlot& plot) {
    checkSize(plot.width, plot.height);
    Extent ex, ey;
    for (const PlotSeries& s : plot.series) {
        for (size_t i = 0; i < pointCount(s); ++i) {
            if (!pointValid(plot, s.x[i], s.y[i])) continue;
            ex.add(s.x[i]);
            ey.add(s.y[i]);
        }
    }
    const AxisRange xr = plot.logX ? logRange(ex, false) : linearRange(ex, false);
    const AxisRange yr = plot.logY ? logRange(ey, false) : linearRange(ey, false);
    std::vector<LegendItem> items;
    for (size_t i = 0; i < plot.series.size(); ++i) {
        const PlotSeries& s = plot.series[i];
        if (s.label.empty()) continue;
        items.push_back({s.label, seriesColor(plot, i), s.style, s.markers, false, true});
    }
    const int s = std::min(plot.width, plot.height) >= 400 ? 2 : 1;
    // Occupied: some segment or point, widened by pen and marker, touches the box.
    const Occupied occupied = [&plot, s](const PlotFrame& f, const Rect& box) {
        const Rect b = box.grown(markerHalf(s) + 1);
        for (const PlotSeries& ser : plot.series) {
            bool havePrev = false;
            double px = 0, py = 0;
            for (size_t i = 0; i < pointCount(ser); ++i) {
                if (!pointValid(plot, ser.x[i], ser.y[i])) {
                    havePrev = false;
                    continue;
                }
                const double x = f.pixelX(ser.x[i]), y = f.pixelY(ser.y[i]);
                double t0 = 0.0, t1 = 1.0;
                const double ax = havePrev ? px : x, ay = havePrev ? py : y;
                if (clipSegment(ax, ay, x - ax, y - ay, b.x0, b.y0, b.x1 + 1.0, b.y1 + 1.0, t0, t1)) return true;
                px = x, py = y, havePrev = true;
            }
        }
        return false;
    };
    return layoutChart({plot.title, plot.xLabel, plot.yLabel, plot.width, plot.height}, xr, yr, items, occupied);
}

// Consecutive valid points are joined; an invalid point breaks the line. Markers at every valid
// point when requested, and at isolated points always (they would be invisible otherwise).
void drawSeries(Canvas& cv, const Layout& L, const LinePlot& plot, size_t index) {
    const PlotSeries& ser = plot.series[index];
    const Rgb8 color = seriesColor(plot, index);
    const Rect box = L.plotRect();
    Pen pen{color, ser.style == LineStyle::Dashed, 5.0 * L.scale, 8.0 * L.scale, 0.0};
    const size_t n = pointCount(ser);
    auto valid = [&](size_t i) { return i < n && pointValid(plot, ser.x[i], ser.y[i]); };
    bool havePrev = false;
    double px = 0, py = 0;
    for (size_t i = 0; i < n; ++i) {
        if (!valid(i)) {
            havePrev = false;
            continue;
        }
        const double x = L.frame.pixelX(ser.x[i]), y = L.frame.pixelY(ser.y[i]);
        if (havePrev) drawSegment(cv, box, px, py, x, y, pen);
        const bool isolated = !havePrev && !valid(i + 1);
        if (ser.markers || isolated) drawMarker(cv, x, y, markerHalf(L.scale), color);
        px = x, py = y, havePrev = true;
    }
}

// ---- Bar charts -----------------------------------------------------------------------------

bool barValid(const BarChart& chart, double v) { return std::isfinite(v) && (!chart.logY || v > 0.0); }

// Calls fn(rect, color) for every bar: group g spans [g, g+1) on x, its bars share the middle 80%.
void forEachBar(const BarChart& chart, const PlotFrame& f, const std::function<void(const Rect&, Rgb8)>& fn) {
    size_t slots = chart.categories.size();
    for (const BarGroup& g : chart.groups) slots = std::max(slots, g.values.size());
    if (slots == 0) return;
    const double base = chart.logY ? f.pixelY(f.y0) : f.pixelY(std::clamp(0.0, f.y0, f.y1));
    for (size_t g = 0; g < chart.groups.size(); ++g) {
        const std::vector<double>& values = chart.groups[g].values;
        for (size_t c = 0; c < values.size(); ++c) {
            if (!barValid(chart, values[c])) continue;
            const double xa = f.pixelX(double(g) + 0.1 + 0.8 * double(c) / double(slots));
            const double xb = f.pixelX(double(g) + 0.1 + 0.8 * double(c + 1) / double(slots));
            const int x0 = toPixel(xa);
            const int x1 = std::max(x0, toPixel(xb) - 1 - (xb - xa >= 4.0 ? 1 : 0));
            const int ya = toPixel(base), yb = toPixel(f.pixelY(values[c]));
            fn({x0, std::min(ya, yb), x1, std::max(ya, yb)}, paletteColor(c));
        }
    }
}

Layout layoutBarChart(const BarChart& chart) {
    checkSize(chart.width, chart.height);
    Extent ey;
    for (const BarGroup& g : chart.groups)
        for (double v : g.values)
            if (barValid(chart, v)) ey.add(v);
    const AxisRange xr{0.0, double(std::max<size_t>(1, chart.groups.size())), false};
    const AxisRange yr = chart.logY ? logRange(ey, true) : linearRange(ey, true);
    std::vector<LegendItem> items;
    for (size_t c = 0; c < chart.categories.size(); ++c)
        if (!chart.categories[c].empty()) items.push_back({chart.categories[c], paletteColor(c), {}, false, true, true});
    const Occupied occupied = [&chart](const PlotFrame& f, const Rect& box) {
        bool hit = false;
        forEachBar(chart, f, [&](const Rect& r, Rgb8) { hit = hit || r.intersects(box); });
        return hit;
    };
    Layout L = layoutChart({chart.title, {}, chart.yLabel, chart.width, chart.height}, xr, yr, items, occupied);
    // x axis: marks at group boundaries, group labels centred (every k-th group when narrow).
    L.xTicks.clear();
    const size_t groups = chart.groups.size();
    const double groupPx = (L.frame.right - L.frame.left) / double(std::max<size_t>(1, groups));
    if (groupPx >= 4.0)
        for (size_t g = 0; g <= groups; ++g) L.xTicks.push_back({double(g), TickKind::Minor, {}});
    int widest = 0;
    for (const BarGroup& g : chart.groups) widest = std::max(widest, textWidth(g.label, L.scale));
    const int needed = std::min(widest, textWidth("abc", L.scale));
    size_t stride = 1;
    while (stride < groups && double(stride) * groupPx - 2.0 * L.scale < needed) stride = stride < 10 ? stride + 1 : stride * 2;
    const int room = int(std::min(double(stride) * groupPx - 2.0 * L.scale, 1e6));
    for (size_t g = 0; g < groups; g += stride)
        if (!chart.groups[g].label.empty())
            L.xTicks.push_back({double(g) + 0.5, TickKind::LabelOnly, fitText(chart.groups[g].label, room, L.scale)});
    return L;
}

}  // namespace

double PlotFrame::pixelX(double x) const {
    return left + 0.5 + (right - left) * axisFraction(x, x0, x1, logX);
}

double PlotFrame::pixelY(double y) const {
    return bottom + 0.5 - (bottom - top) * axisFraction(y, y0, y1, logY);
}

Rgb8 paletteColor(size_t i) {
    // Okabe-Ito: blue, vermillion, bluish green, reddish purple, orange, sky blue, black.
    static constexpr Rgb8 kBase[7] = {{0, 114, 178},   {213, 94, 0},    {0, 158, 115}, {204, 121, 167},
                                      {230, 159, 0},   {86, 180, 233},  {0, 0, 0}};
    const Rgb8 c = kBase[i % 7];
    const size_t variant = (i / 7) % 3;
    if (variant == 0) return c;
    if (c == Rgb8{0, 0, 0}) return variant == 1 ? Rgb8{96, 96, 96} : Rgb8{160, 160, 160};
    auto mix = [&](uint8_t v) {
        return variant == 1 ? uint8_t(v * 6 / 10) : uint8_t(v + (255 - v) / 2);  // darker / lighter
    };
    return {mix(c.r), mix(c.g), mix(c.b)};
}

PlotFrame linePlotFrame(const LinePlot& plot) { return layoutLinePlot(plot).frame; }

PlotFrame barChartFrame(const BarChart& chart) { return layoutBarChart(chart).frame; }

Image8 renderLinePlot(const LinePlot& plot) {
    const Layout L = layoutLinePlot(plot);
    Canvas cv(plot.width, plot.height);
    drawGrid(cv, L);
    cv.setClip(L.plotRect());
    for (size_t i = 0; i < plot.series.size(); ++i) drawSeries(cv, L, plot, i);
    cv.resetClip();
    drawDecorations(cv, L, {plot.title, plot.xLabel, plot.yLabel, plot.width, plot.height});
    return cv.take();
}

Image8 renderBarChart(const BarChart& chart) {
    const Layout L = layoutBarChart(chart);
    Canvas cv(chart.width, chart.height);
    drawGrid(cv, L);
    cv.setClip(L.plotRect());
    if (!chart.logY && L.frame.y0 < 0.0 && L.frame.y1 > 0.0) {
        const int y = toPixel(L.frame.pixelY(0.0));
        cv.fill({L.frame.left, y, L.frame.right, y}, kZeroLine);
    }
    forEachBar(chart, L.frame, [&](const Rect& r, Rgb8 c) { cv.fill(r, c); });
    cv.resetClip();
    drawDecorations(cv, L, {chart.title, {}, chart.yLabel, chart.width, chart.height});
    return cv.take();
}

void writeLinePlot(const std::filesystem::path& png, const LinePlot& plot) {
    writePng8(png, renderLinePlot(plot));
}

void writeBarChart(const std::filesystem::path& png, const BarChart& chart) {
    writePng8(png, renderBarChart(chart));
}

}  // namespace amrvk::bench
