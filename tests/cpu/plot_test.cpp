// Benchmark plots: data lands where the frame's axis mapping puts it, log-log power laws are
// straight, bad points are skipped, text and legends draw, bars scale with their values, PNG
// output round-trips bit-exactly and failures leave no file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <tuple>

#include "bench/plot.h"
#include "core/error.h"
#include "core/image_io.h"
#include "test_data.h"

using namespace amrvk;
using bench::Rgb8;

namespace {

constexpr Rgb8 kRed{200, 30, 40};  // not in the palette, not grey
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

Rgb8 pixel(const Image8& im, int x, int y) {
    const size_t i = (size_t(x) + size_t(im.width) * size_t(y)) * 4;
    return {im.rgba[i], im.rgba[i + 1], im.rgba[i + 2]};
}

bool inside(const Image8& im, int x, int y) { return x >= 0 && y >= 0 && x < im.width && y < im.height; }

// Whether some pixel within `radius` (Chebyshev) of (x, y) has colour c.
bool colorNear(const Image8& im, int x, int y, Rgb8 c, int radius) {
    for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx)
            if (inside(im, x + dx, y + dy) && pixel(im, x + dx, y + dy) == c) return true;
    return false;
}

// Pixels of colour c in columns [x0, x1] and rows [y0, y1].
int countColor(const Image8& im, Rgb8 c, int x0, int y0, int x1, int y1) {
    int n = 0;
    for (int y = std::max(0, y0); y <= std::min(im.height - 1, y1); ++y)
        for (int x = std::max(0, x0); x <= std::min(im.width - 1, x1); ++x) n += pixel(im, x, y) == c;
    return n;
}

int countDark(const Image8& im, int x0, int y0, int x1, int y1) {
    int n = 0;
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
            const Rgb8 p = pixel(im, x, y);
            n += p.r < 128 && p.g < 128 && p.b < 128;
        }
    return n;
}

// Distance from p to the segment a-b.
double segmentDistance(double px, double py, double ax, double ay, double bx, double by) {
    const double dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy;
    const double t = len2 > 0 ? std::clamp(((px - ax) * dx + (py - ay) * dy) / len2, 0.0, 1.0) : 0.0;
    return std::hypot(px - (ax + t * dx), py - (ay + t * dy));
}

bench::PlotSeries series(std::vector<double> x, std::vector<double> y, Rgb8 color, std::string label = {}) {
    bench::PlotSeries s;
    s.label = std::move(label);
    s.x = std::move(x);
    s.y = std::move(y);
    s.color = color;
    return s;
}

void expectValidImage(const Image8& im, int w, int h) {
    ASSERT_EQ(im.width, w);
    ASSERT_EQ(im.height, h);
    ASSERT_EQ(im.rgba.size(), size_t(w) * size_t(h) * 4);
    for (size_t i = 3; i < im.rgba.size(); i += 4) ASSERT_EQ(im.rgba[i], 255) << "pixel " << i / 4;
}

}  // namespace

TEST(PlotLine, LinearSeriesLandsWhereTheAxisMapsIt) {
    bench::LinePlot plot;
    plot.title = "linear";
    plot.xLabel = "x";
    plot.yLabel = "y";
    const std::vector<double> xs = {0, 1, 2, 4}, ys = {0, 3, 1, 2};
    plot.series.push_back(series(xs, ys, kRed));
    const Image8 im = bench::renderLinePlot(plot);
    expectValidImage(im, 960, 640);
    const bench::PlotFrame f = bench::linePlotFrame(plot);
    // The axis ranges hold the data with a small margin on every side.
    EXPECT_LT(f.x0, 0.0);
    EXPECT_GT(f.x0, -0.5);
    EXPECT_GT(f.x1, 4.0);
    EXPECT_LT(f.x1, 4.5);
    EXPECT_LT(f.y0, 0.0);
    EXPECT_GT(f.y1, 3.0);
    EXPECT_GT(f.left, 0);
    EXPECT_LT(f.right, im.width - 1);
    EXPECT_GT(f.top, 0);
    EXPECT_LT(f.bottom, im.height - 1);

    std::vector<std::pair<double, double>> pts;
    for (size_t i = 0; i < xs.size(); ++i) {
        const double px = f.pixelX(xs[i]), py = f.pixelY(ys[i]);
        pts.emplace_back(px, py);
        EXPECT_TRUE(colorNear(im, int(px), int(py), kRed, 2)) << "point " << i << " at " << px << ", " << py;
    }
    // Every series pixel lies on the polyline (pen width and marker included).
    int seriesPixels = 0;
    for (int y = 0; y < im.height; ++y) {
        for (int x = 0; x < im.width; ++x) {
            if (!(pixel(im, x, y) == kRed)) continue;
            ++seriesPixels;
            double d = 1e9;
            for (size_t i = 0; i + 1 < pts.size(); ++i)
                d = std::min(d, segmentDistance(x + 0.5, y + 0.5, pts[i].first, pts[i].second, pts[i + 1].first,
                                                pts[i + 1].second));
            ASSERT_LE(d, 4.5) << "stray series pixel at " << x << ", " << y;
        }
    }
    EXPECT_GT(seriesPixels, 200);
    // The far corner of the plot area (top right, away from every point) stays free of the series.
    EXPECT_EQ(countColor(im, kRed, f.right - 40, f.top + 1, f.right - 1, f.top + 40), 0);
    EXPECT_TRUE(pixel(im, 0, 0) == (Rgb8{255, 255, 255}));
    EXPECT_TRUE(pixel(im, im.width - 1, im.height - 1) == (Rgb8{255, 255, 255}));
    EXPECT_TRUE(pixel(im, f.left, (f.top + f.bottom) / 2) == (Rgb8{0, 0, 0}));  // frame
}

TEST(PlotLine, LogLogPowerLawIsStraight) {
    bench::LinePlot plot;
    plot.logX = plot.logY = true;
    std::vector<double> xs, ys;
    for (int i = 0; i <= 30; ++i) {
        xs.push_back(std::pow(10.0, 3.0 * i / 30));
        ys.push_back(std::pow(xs.back(), -0.5));
    }
    plot.series.push_back(series(xs, ys, kRed));
    plot.series[0].markers = false;
    const Image8 im = bench::renderLinePlot(plot);
    const bench::PlotFrame f = bench::linePlotFrame(plot);
    // Snapped to decades.
    EXPECT_DOUBLE_EQ(f.x0, 1.0);
    EXPECT_DOUBLE_EQ(f.x1, 1000.0);
    EXPECT_NEAR(f.y0, 0.01, 1e-15);
    EXPECT_DOUBLE_EQ(f.y1, 1.0);
    const double ax = f.pixelX(xs.front()), ay = f.pixelY(ys.front());
    const double bx = f.pixelX(xs.back()), by = f.pixelY(ys.back());
    EXPECT_NEAR(ay, f.top + 0.5, 1e-9);  // y = 1 at the top
    // Down the middle of the plot, the series pixels of each column centre on the straight segment.
    int columns = 0;
    for (double u = 0.1; u <= 0.9; u += 0.1) {
        const int x = int(ax + u * (bx - ax));
        double sum = 0;
        int n = 0;
        for (int y = f.top + 1; y < f.bottom; ++y)
            if (pixel(im, x, y) == kRed) sum += y + 0.5, ++n;
        ASSERT_GT(n, 0) << "no series pixel in column " << x;
        const double expected = ay + (x + 0.5 - ax) / (bx - ax) * (by - ay);
        EXPECT_NEAR(sum / n, expected, 2.0) << "column " << x;
        ++columns;
    }
    EXPECT_EQ(columns, 9);
}

TEST(PlotLine, InvalidPointsAreSkipped) {
    bench::LinePlot plot;
    plot.logX = plot.logY = true;
    plot.series.push_back(series({1, 0, -3, 10, kNaN, 5, kInf, 2}, {1, 5, 5, 100, 7, -1, 3, kNaN}, kRed, "s"));
    bench::PlotFrame f;
    ASSERT_NO_THROW(f = bench::linePlotFrame(plot));
    // Only (1, 1) and (10, 100) count.
    EXPECT_DOUBLE_EQ(f.x0, 1.0);
    EXPECT_DOUBLE_EQ(f.x1, 10.0);
    EXPECT_DOUBLE_EQ(f.y0, 1.0);
    EXPECT_DOUBLE_EQ(f.y1, 100.0);
    Image8 im;
    ASSERT_NO_THROW(im = bench::renderLinePlot(plot));
    expectValidImage(im, 960, 640);
    EXPECT_TRUE(colorNear(im, int(f.pixelX(10)), int(f.pixelY(100)), kRed, 2));

    // Nothing valid at all, and a mismatched x/y length.
    bench::LinePlot none;
    none.logY = true;
    none.series.push_back(series({1, 2, 3}, {0, -1, kNaN, 4}, kRed, "none"));
    ASSERT_NO_THROW(im = bench::renderLinePlot(none));
    expectValidImage(im, 960, 640);
}

TEST(PlotLine, DegenerateInputsRender) {
    // No series at all: frame, ticks and white background.
    const bench::LinePlot empty;
    Image8 im = bench::renderLinePlot(empty);
    expectValidImage(im, 960, 640);
    const bench::PlotFrame f = bench::linePlotFrame(empty);
    EXPECT_TRUE(pixel(im, f.left, f.top) == (Rgb8{0, 0, 0}));
    EXPECT_TRUE(pixel(im, (f.left + f.right) / 2 + 3, (f.top + f.bottom) / 2 + 3) == (Rgb8{255, 255, 255}) ||
                pixel(im, (f.left + f.right) / 2 + 3, (f.top + f.bottom) / 2 + 3) == (Rgb8{225, 225, 225}));

    // One point (equal min and max on both axes): the range grows around it, the point shows.
    bench::LinePlot single;
    single.series.push_back(series({5}, {5}, kRed));
    single.series[0].markers = false;  // an isolated point is marked anyway
    im = bench::renderLinePlot(single);
    const bench::PlotFrame fs = bench::linePlotFrame(single);
    EXPECT_LT(fs.x0, 5.0);
    EXPECT_GT(fs.x1, 5.0);
    EXPECT_LT(fs.y0, 5.0);
    EXPECT_GT(fs.y1, 5.0);
    EXPECT_TRUE(colorNear(im, int(fs.pixelX(5)), int(fs.pixelY(5)), kRed, 1));

    // Equal values on a log axis, zero, huge and tiny magnitudes.
    for (auto [x, y, logY] : {std::tuple{1.0, 10.0, true}, std::tuple{0.0, 0.0, false},
                              std::tuple{1e300, -1e300, false}, std::tuple{1e-310, 1e-310, true}}) {
        bench::LinePlot p;
        p.logY = logY;
        p.series.push_back(series({x, x}, {y, y}, kRed, "flat"));
        ASSERT_NO_THROW(im = bench::renderLinePlot(p)) << x << " " << y;
        const bench::PlotFrame fp = bench::linePlotFrame(p);
        EXPECT_LT(fp.x0, fp.x1);
        EXPECT_LT(fp.y0, fp.y1);
        EXPECT_GT(countColor(im, kRed, fp.left, fp.top, fp.right, fp.bottom), 0) << x << " " << y;
    }
    bench::LinePlot extremes;
    extremes.series.push_back(series({-std::numeric_limits<double>::max(), std::numeric_limits<double>::max()},
                                     {std::numeric_limits<double>::max(), -std::numeric_limits<double>::max()},
                                     kRed));
    ASSERT_NO_THROW(im = bench::renderLinePlot(extremes));
    expectValidImage(im, 960, 640);

    // A million points, smallest size.
    bench::LinePlot big;
    big.width = big.height = 64;
    bench::PlotSeries s = series({}, {}, kRed, "sine");
    for (int i = 0; i < 1000000; ++i) {
        s.x.push_back(i);
        s.y.push_back(std::sin(i * 1e-4));
    }
    big.series.push_back(std::move(s));
    big.title = "a title far too long to fit into sixty-four pixels";
    big.xLabel = big.yLabel = "long axis label that cannot fit";
    im = bench::renderLinePlot(big);
    expectValidImage(im, 64, 64);
    EXPECT_GT(countColor(im, kRed, 0, 0, 63, 63), 0);
}

TEST(PlotLine, DashedLineHasGaps) {
    auto coverage = [](bench::LineStyle style) {
        bench::LinePlot plot;
        plot.series.push_back(series({0, 10}, {1, 1}, kRed));
        plot.series.push_back(series({0, 10}, {0, 2}, Rgb8{0, 0, 255}));  // gives the y axis a range
        plot.series[0].style = style;
        plot.series[0].markers = false;
        const Image8 im = bench::renderLinePlot(plot);
        const bench::PlotFrame f = bench::linePlotFrame(plot);
        const int y = int(f.pixelY(1));
        const int x0 = int(f.pixelX(1)), x1 = int(f.pixelX(4));  // left of the crossing at x = 5
        int hit = 0;
        for (int x = x0; x <= x1; ++x) hit += countColor(im, kRed, x, y - 2, x, y + 2) > 0;
        return double(hit) / double(x1 - x0 + 1);
    };
    EXPECT_GT(coverage(bench::LineStyle::Solid), 0.99);
    const double dashed = coverage(bench::LineStyle::Dashed);
    EXPECT_GT(dashed, 0.4);
    EXPECT_LT(dashed, 0.8);
}

TEST(PlotText, TitleAndLabelsDrawPixels) {
    bench::LinePlot plot;
    plot.series.push_back(series({0, 1}, {0, 1}, kRed));
    const Image8 plain = bench::renderLinePlot(plot);
    plot.title = "Convergence";
    const Image8 titled = bench::renderLinePlot(plot);
    // Title band: above the untitled frame, middle half of the width (tick labels sit at the left).
    const int band = bench::linePlotFrame(bench::LinePlot{}).top - 2;
    EXPECT_EQ(countDark(plain, 240, 0, 720, band), 0);
    EXPECT_GT(countDark(titled, 240, 0, 720, band), 100);
    // Different text gives different pixels.
    plot.title = "Convergencf";
    EXPECT_NE(bench::renderLinePlot(plot).rgba, titled.rgba);

    // Axis labels: below the plot area, and left of it.
    plot.title.clear();
    plot.xLabel = "samples per pixel";
    plot.yLabel = "RMSE";
    const Image8 labelled = bench::renderLinePlot(plot);
    const bench::PlotFrame f = bench::linePlotFrame(plot);
    const bench::PlotFrame fp = bench::linePlotFrame({});
    EXPECT_GT(countDark(labelled, f.left, f.bottom + 30, f.right, labelled.height - 1), 100);
    EXPECT_GT(f.left, fp.left);  // room made for the rotated y label
    EXPECT_GT(countDark(labelled, 0, f.top, 20, f.bottom), 30);
}

TEST(PlotLegend, ListsSeriesAndStaysReadableWithThirty) {
    // A labelled series adds its swatch (series colour) away from its line, plus dark text.
    bench::LinePlot plot;
    plot.series.push_back(series({0, 1}, {1, 0}, kRed));
    const Image8 unlabelled = bench::renderLinePlot(plot);
    plot.series[0].label = "reference";
    const Image8 labelled = bench::renderLinePlot(plot);
    EXPECT_GT(countColor(labelled, kRed, 0, 0, 959, 639), countColor(unlabelled, kRed, 0, 0, 959, 639) + 10);
    EXPECT_GT(countDark(labelled, 0, 0, 959, 639), countDark(unlabelled, 0, 0, 959, 639) + 50);

    // Thirty series with long labels: the legend moves right of the plot area, every colour shows.
    bench::LinePlot many;
    for (int i = 0; i < 30; ++i) {
        bench::PlotSeries s;
        s.label = "structure variant number " + std::to_string(i);
        s.x = {1, 2, 3};
        s.y = {double(i), double(i) + 1, double(i) + 0.5};
        s.style = i % 2 ? bench::LineStyle::Dashed : bench::LineStyle::Solid;
        many.series.push_back(std::move(s));
    }
    const Image8 im = bench::renderLinePlot(many);
    const bench::PlotFrame f = bench::linePlotFrame(many);
    EXPECT_GT(f.right - f.left, im.width / 2);
    for (size_t i = 0; i < 30; ++i)
        EXPECT_GT(countColor(im, bench::paletteColor(i), f.right + 1, f.top, im.width - 1, f.bottom), 0)
            << "series " << i;
}

TEST(PlotPalette, ColoursAreDistinctAndVisible) {
    std::set<std::tuple<int, int, int>> seen;
    for (size_t i = 0; i < 21; ++i) {
        const Rgb8 c = bench::paletteColor(i);
        seen.insert({c.r, c.g, c.b});
        EXPECT_LT(int(c.r) + c.g + c.b, 3 * 215) << "colour " << i << " too close to white";
    }
    EXPECT_EQ(seen.size(), 21u);
    EXPECT_TRUE(bench::paletteColor(21) == bench::paletteColor(0));
}

TEST(PlotBar, LargerValuesAreTaller) {
    bench::BarChart chart;
    chart.title = "time per frame";
    chart.yLabel = "ms";
    chart.categories = {"kd-tree", "bvh"};
    chart.groups = {{"small", {1.0, 3.0}}, {"large", {2.0, 0.5}}};
    const Image8 im = bench::renderBarChart(chart);
    expectValidImage(im, 960, 640);
    const bench::PlotFrame f = bench::barChartFrame(chart);
    EXPECT_DOUBLE_EQ(f.y0, 0.0);  // bars start at zero
    EXPECT_GT(f.y1, 3.0);
    // Height of bar (g, c): the run of its colour up its centre column from the baseline.
    auto height = [&](int g, int c) {
        const int x = int(f.pixelX(g + 0.1 + 0.8 * (c + 0.5) / 2));
        const Rgb8 color = bench::paletteColor(size_t(c));
        int y = f.bottom - 1, n = 0;
        while (y > f.top && pixel(im, x, y) == color) --y, ++n;
        return n;
    };
    const int h1 = height(0, 0), h3 = height(0, 1), h2 = height(1, 0), h05 = height(1, 1);
    EXPECT_GT(h3, h2);
    EXPECT_GT(h2, h1);
    EXPECT_GT(h1, h05);
    EXPECT_GT(h05, 0);
    EXPECT_NEAR(double(h3) / h1, 3.0, 0.05);
    EXPECT_NEAR(double(h2) / h05, 4.0, 0.1);
    // Group labels are drawn under the plot area.
    EXPECT_GT(countDark(im, f.left + 1, f.bottom + 2, f.right - 1, im.height - 1), 50);
}

TEST(PlotBar, LogAxisAndDegenerateCharts) {
    bench::BarChart chart;
    chart.logY = true;
    chart.categories = {"a", "b", "c"};
    chart.groups = {{"g", {10.0, 0.0, -1.0}}, {"h", {1000.0, kNaN}}};
    Image8 im;
    ASSERT_NO_THROW(im = bench::renderBarChart(chart));
    expectValidImage(im, 960, 640);
    const bench::PlotFrame f = bench::barChartFrame(chart);
    // Decades around the positive values 10 and 1000, the floor below the smallest bar.
    EXPECT_DOUBLE_EQ(f.y0, 1.0);
    EXPECT_DOUBLE_EQ(f.y1, 1000.0);
    // Bar heights from the baseline: 10 reaches a third of the way up, 0 and -1 draw nothing.
    auto height = [&](int g, int c) {
        const int x = int(f.pixelX(g + 0.1 + 0.8 * (c + 0.5) / 3));
        int y = f.bottom - 1, n = 0;
        while (y > f.top && pixel(im, x, y) == bench::paletteColor(size_t(c))) --y, ++n;
        return n;
    };
    EXPECT_NEAR(height(0, 0), (f.bottom - f.top) / 3.0, 2.0);
    EXPECT_NEAR(height(1, 0), f.bottom - f.top, 2.0);
    EXPECT_EQ(height(0, 1), 0);
    EXPECT_EQ(height(0, 2), 0);

    ASSERT_NO_THROW(im = bench::renderBarChart({}));
    expectValidImage(im, 960, 640);
    bench::BarChart many;
    many.width = 200;
    many.height = 100;
    for (int g = 0; g < 500; ++g) many.groups.push_back({"group " + std::to_string(g), {double(g), -double(g)}});
    ASSERT_NO_THROW(im = bench::renderBarChart(many));
    expectValidImage(im, 200, 100);
}

TEST(PlotIo, WrittenPngMatchesTheRenderAndFailuresLeaveNoFile) {
    const auto dir = test::scratchDir();
    bench::LinePlot plot;
    plot.title = "round trip";
    plot.logY = true;
    plot.series.push_back(series({1, 2, 3}, {1, 10, 100}, kRed, "s"));
    bench::writeLinePlot(dir / "line.png", plot);
    const Image8 back = readPng(dir / "line.png");
    const Image8 rendered = bench::renderLinePlot(plot);
    EXPECT_EQ(back.width, plot.width);
    EXPECT_EQ(back.height, plot.height);
    EXPECT_EQ(back.rgba, rendered.rgba);

    bench::BarChart chart;
    chart.categories = {"a"};
    chart.groups = {{"g", {1.0}}};
    chart.width = 300;
    chart.height = 200;
    bench::writeBarChart(dir / "bar.png", chart);
    EXPECT_EQ(readPng(dir / "bar.png").rgba, bench::renderBarChart(chart).rgba);

    test::expectError([&] { bench::writeLinePlot(dir / "missing" / "x.png", plot); }, {"x.png", "cannot write"});
    test::expectError([&] { bench::writeBarChart(dir / "missing" / "y.png", chart); }, {"y.png", "cannot write"});
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"bar.png", "line.png"}));
}

TEST(PlotSize, InvalidSizeThrows) {
    const auto dir = test::scratchDir();
    for (auto [w, h, what] : {std::tuple{63, 640, "plot width 63 "}, std::tuple{8193, 640, "plot width 8193 "},
                              std::tuple{960, 0, "plot height 0 "}, std::tuple{960, -5, "plot height -5 "}}) {
        bench::LinePlot plot;
        plot.width = w;
        plot.height = h;
        test::expectError([&] { bench::renderLinePlot(plot); }, {what, "[64, 8192]"});
        test::expectError([&] { bench::writeLinePlot(dir / "p.png", plot); }, {what});
        bench::BarChart chart;
        chart.width = w;
        chart.height = h;
        test::expectError([&] { bench::renderBarChart(chart); }, {what});
    }
    EXPECT_TRUE(std::filesystem::is_empty(dir));
    bench::LinePlot edge;
    edge.width = 8192;
    edge.height = 64;
    expectValidImage(bench::renderLinePlot(edge), 8192, 64);
}
