// The legend drawn into PNGs (session/legend_image.*), read back from the PNG file: its size, the
// picture kept, the colour bar against the TF evaluated here by hand, the opacity strip, text drawn
// by FreeType only where the layout says, the backdrop everywhere else; font errors.
#include "session/legend_image.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "core/font.h"
#include "core/image_io.h"
#include "scene/tf_presets.h"
#include "test_data.h"

using namespace amrvk;
namespace fs = std::filesystem;

namespace {

// sRGB of a linear value, written out here (not core/image_io's encodeSrgb8).
int srgb8(double linear) {
    const double c = std::clamp(linear, 0.0, 1.0);
    const double s = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
    return int(std::lround(s * 255));
}

// The test TF: colour and alpha linear between (0: red, alpha 0), (1: green-cyan, 0.5), (3: blue, 2).
struct Node {
    double x, r, g, b, a;
};
const Node kNodes[] = {{0, 1, 0, 0, 0}, {1, 0, 1, 0.5, 0.5}, {3, 0.2, 0.2, 1, 2}};

Node evalByHand(double v) {
    if (v <= kNodes[0].x) return kNodes[0];
    for (int i = 0; i < 2; ++i)
        if (v <= kNodes[i + 1].x) {
            const Node &p = kNodes[i], &q = kNodes[i + 1];
            const double t = (v - p.x) / (q.x - p.x);
            return {v, p.r + t * (q.r - p.r), p.g + t * (q.g - p.g), p.b + t * (q.b - p.b), p.a + t * (q.a - p.a)};
        }
    return kNodes[2];
}

session::LegendContent testContent(const std::string& title, bool logScale = false) {
    std::vector<float> xs;
    std::vector<glm::vec4> cs;
    for (const Node& n : kNodes) {
        xs.push_back(float(n.x));
        cs.emplace_back(float(n.r), float(n.g), float(n.b), float(n.a));
    }
    session::LegendContent c;
    c.tf = scene::TransferFunction(xs, cs);
    c.lo = 0;
    c.hi = 3;
    c.logScale = logScale;
    c.title = title;
    c.units = "g/cm³";
    return c;
}

// A picture with a gradient and one HDR pixel (above 1: the PNG clamps it).
Image testPicture(int w, int h) {
    Image p(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) p.at(x, y) = glm::vec4(float(x) / float(w), float(y) / float(h), 0.5f, 1.0f);
    p.at(3, 4) = glm::vec4(5.0f, 0.2f, 7.0f, 1.0f);
    return p;
}

struct Rgb {
    int r, g, b;
};
Rgb pixel(const Image8& png, int x, int y) {
    const size_t i = (size_t(y) * size_t(png.width) + size_t(x)) * 4;
    return {png.rgba[i], png.rgba[i + 1], png.rgba[i + 2]};
}
bool near(Rgb a, double r, double g, double b, int tol = 1) {
    return std::abs(a.r - srgb8(r)) <= tol && std::abs(a.g - srgb8(g)) <= tol && std::abs(a.b - srgb8(b)) <= tol;
}

// The legend of `content` over `picture` written as a PNG and read back.
Image8 legendPng(const Image& picture, const session::LegendContent& content, session::LegendPlace place,
                 const Font& font, const std::string& name) {
    const fs::path file = test::scratchDir() / name;
    writeImage(file, session::drawLegend(picture, content, place, font));
    return readPng(file);
}

// Outside the bars, tick marks and text the legend block is its backdrop: `backdrop(x, y)`.
template <typename Backdrop>
void expectOnlyBackdropOutsideElements(const Image8& png, const session::LegendLayout& L, Backdrop backdrop) {
    int checked = 0, wrong = 0;
    for (int y = L.block.y; y < L.block.y + L.block.height; ++y)
        for (int x = L.block.x; x < L.block.x + L.block.width; ++x) {
            bool element = L.colorBar.contains(x, y) || L.opacityBar.contains(x, y) || L.tickMarks.contains(x, y);
            for (const session::PixelRect& t : L.text) element = element || t.contains(x, y);
            if (element) continue;
            ++checked;
            if (!backdrop(pixel(png, x, y), x, y) && ++wrong <= 5)
                ADD_FAILURE() << "pixel " << x << "," << y << " is not backdrop";
        }
    EXPECT_GT(checked, 100);
    EXPECT_EQ(wrong, 0);
}

// Pixels of a text rectangle that are not backdrop, and how many are bright ink.
std::pair<int, int> textPixels(const Image8& png, const session::PixelRect& r, Rgb backdrop) {
    int drawn = 0, ink = 0;
    for (int y = r.y; y < r.y + r.height; ++y)
        for (int x = r.x; x < r.x + r.width; ++x) {
            const Rgb p = pixel(png, x, y);
            if (p.r != backdrop.r || p.g != backdrop.g || p.b != backdrop.b) ++drawn;
            if (p.r > 200 && p.g > 200 && p.b > 200) ++ink;
        }
    return {drawn, ink};
}

std::unique_ptr<Font> defaultFont() {
    if (!fontRenderingAvailable()) return nullptr;
    return session::openLegendFont({});
}

}  // namespace

TEST(LegendImage, SideStripKeepsThePictureAndShowsTheTfColoursAtTheBarsValues) {
    const auto font = defaultFont();
    if (!font) GTEST_SKIP() << "built without FreeType";
    const Image picture = testPicture(80, 120);
    const session::LegendContent c = testContent("Density");
    const session::LegendLayout L = session::legendLayout(80, 120, c, session::LegendPlace::Side, *font);
    const Image8 png = legendPng(picture, c, session::LegendPlace::Side, *font, "side.png");
    // Size: the picture and the strip beside it.
    ASSERT_EQ(png.height, 120);
    ASSERT_EQ(png.width, 80 + L.block.width);
    EXPECT_EQ(L.block.x, 80);
    EXPECT_GE(L.colorBar.height, 16);
    // The picture as it was (clamped by the PNG, as without a legend).
    for (int y = 0; y < 120; ++y)
        for (int x = 0; x < 80; ++x) {
            const glm::vec4& p = picture.at(x, y);
            ASSERT_TRUE(near(pixel(png, x, y), p.r, p.g, p.b, 0)) << x << "," << y;
        }
    // The colour bar: row y shows v = hi - (y + 0.5 - top) / rows (hi - lo), its TF colour opaque.
    const int rows = L.colorBar.height;
    for (int y = L.colorBar.y; y < L.colorBar.y + rows; ++y) {
        const double v = 3.0 - (double(y - L.colorBar.y) + 0.5) / rows * 3.0;
        const Node n = evalByHand(v);
        for (int x = L.colorBar.x; x < L.colorBar.x + L.colorBar.width; ++x)
            ASSERT_TRUE(near(pixel(png, x, y), n.r, n.g, n.b)) << "bar row " << y << " value " << v;
        // The opacity strip: the same colour at opacity alpha / 2 (the largest alpha) over one of two greys.
        const double o = n.a / 2.0;
        int light = 0, dark = 0;
        for (int x = L.opacityBar.x; x < L.opacityBar.x + L.opacityBar.width; ++x) {
            const Rgb p = pixel(png, x, y);
            const bool isLight = near(p, 0.6 * (1 - o) + n.r * o, 0.6 * (1 - o) + n.g * o, 0.6 * (1 - o) + n.b * o);
            const bool isDark = near(p, 0.25 * (1 - o) + n.r * o, 0.25 * (1 - o) + n.g * o, 0.25 * (1 - o) + n.b * o);
            ASSERT_TRUE(isLight || isDark) << "opacity strip " << x << "," << y;
            light += isLight;
            dark += isDark;
        }
        if (o < 0.5) {
            EXPECT_TRUE(light > 0 && dark > 0) << "no checkerboard in row " << y;
        }
    }
    // Every tick on its row, drawn in ink from the bar's edge.
    ASSERT_GE(L.ticks.size(), 2u);
    for (const session::LegendTick& t : L.ticks) {
        const int row = session::legendTickRow(L, c, t.position);
        EXPECT_TRUE(near(pixel(png, L.tickMarks.x, row), 1, 1, 1, 0)) << "tick " << t.position;
    }
    // Text in the title and label areas, backdrop everywhere else in the strip.
    const Rgb backdrop{srgb8(0.02), srgb8(0.02), srgb8(0.02)};
    ASSERT_EQ(L.text.size(), 2u);
    for (const session::PixelRect& r : L.text) {
        const auto [drawn, ink] = textPixels(png, r, backdrop);
        EXPECT_GT(drawn, 30);
        EXPECT_GT(ink, 5);
    }
    expectOnlyBackdropOutsideElements(
        png, L, [&](Rgb p, int, int) { return p.r == backdrop.r && p.g == backdrop.g && p.b == backdrop.b; });
}

TEST(LegendImage, TheFontReallyDrawsTheTitle) {
    const auto font = defaultFont();
    if (!font) GTEST_SKIP() << "built without FreeType";
    // Width grows with the text; two titles draw different pixels in the title area.
    EXPECT_GT(font->width("Temperature", 12), font->width("Te", 12));
    const TextBitmap one = font->render("1", 20), l = font->render("l", 20);
    EXPECT_EQ(one.height, l.height);
    EXPECT_NE(one.coverage, l.coverage);
    const Image picture = testPicture(64, 128);
    const session::LegendContent a = testContent("Density"), b = testContent("Temperature");
    const Image8 pa = legendPng(picture, a, session::LegendPlace::Side, *font, "a.png");
    const Image8 pb = legendPng(picture, b, session::LegendPlace::Side, *font, "b.png");
    const session::LegendLayout la = session::legendLayout(64, 128, a, session::LegendPlace::Side, *font);
    const Rgb backdrop{srgb8(0.02), srgb8(0.02), srgb8(0.02)};
    const auto [drawnA, inkA] = textPixels(pa, la.text[0], backdrop);
    EXPECT_GT(drawnA, 30);
    EXPECT_GT(inkA, 5);
    int differ = 0;
    for (int y = la.text[0].y; y < la.text[0].y + la.text[0].height; ++y)
        for (int x = la.text[0].x; x < la.text[0].x + std::min(la.text[0].width, 40); ++x) {
            const Rgb p = pixel(pa, x, y), q = pixel(pb, x, y);
            differ += p.r != q.r || p.g != q.g || p.b != q.b;
        }
    EXPECT_GT(differ, 10);
}

TEST(LegendImage, LogScaleLabelsWithSuperscriptsStayInTheirArea) {
    const auto font = defaultFont();
    if (!font) GTEST_SKIP() << "built without FreeType";
    session::LegendContent c = testContent("Density (log10 scale)", true);  // the axis [0, 3]: 10^0 .. 10^3
    const Image picture = testPicture(96, 160);
    const session::LegendLayout L = session::legendLayout(96, 160, c, session::LegendPlace::Side, *font);
    int decades = 0;
    for (const session::LegendTick& t : L.ticks) decades += t.major && t.label == "10" && !t.exponent.empty();
    EXPECT_GE(decades, 2);
    const Image8 png = legendPng(picture, c, session::LegendPlace::Side, *font, "log.png");
    const Rgb backdrop{srgb8(0.02), srgb8(0.02), srgb8(0.02)};
    EXPECT_GT(textPixels(png, L.text[1], backdrop).first, 30);
    expectOnlyBackdropOutsideElements(
        png, L, [&](Rgb p, int, int) { return p.r == backdrop.r && p.g == backdrop.g && p.b == backdrop.b; });
}

TEST(LegendImage, OverlaySitsInTheLowerRightCornerOnATranslucentBackdrop) {
    const auto font = defaultFont();
    if (!font) GTEST_SKIP() << "built without FreeType";
    const Image picture = testPicture(160, 128);
    const session::LegendContent c = testContent("Density");
    const session::LegendLayout L = session::legendLayout(160, 128, c, session::LegendPlace::Overlay, *font);
    const Image8 png = legendPng(picture, c, session::LegendPlace::Overlay, *font, "overlay.png");
    ASSERT_EQ(png.width, 160);
    ASSERT_EQ(png.height, 128);
    EXPECT_GT(L.block.x + L.block.width / 2, 80);
    EXPECT_GT(L.block.y + L.block.height / 2, 64);
    EXPECT_LE(L.block.x + L.block.width, 160);
    EXPECT_LE(L.block.y + L.block.height, 128);
    for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 160; ++x) {
            if (L.block.contains(x, y)) continue;
            const glm::vec4& p = picture.at(x, y);
            ASSERT_TRUE(near(pixel(png, x, y), p.r, p.g, p.b, 0)) << x << "," << y;
        }
    // The backdrop: 80% of 0.02 over the picture (clamped to [0, 1] as shown).
    expectOnlyBackdropOutsideElements(png, L, [&](Rgb p, int x, int y) {
        const glm::vec4& q = picture.at(x, y);
        auto over = [](double v) { return 0.2 * std::clamp(v, 0.0, 1.0) + 0.8 * 0.02; };
        return near(p, over(q.r), over(q.g), over(q.b));
    });
}

TEST(LegendImage, ContentComesFromTheSession) {
    session::Session s;
    s.field = "Density";
    s.read.scale = amr::FieldScale::Log;
    s.legend.units = "g/cm^3";
    s.tf = scene::TfChannels::split(scene::makePreset("ramp", -1.5f, 2.5f));
    const session::LegendContent c = session::legendContent(s, "code units (1 = 2.4967e-29 g/cm^3)");
    EXPECT_EQ(c.title, "Density (log10 scale)");
    EXPECT_EQ(c.units, "g/cm^3");  // --legend-units overrides the field's own
    EXPECT_TRUE(c.logScale);
    EXPECT_FLOAT_EQ(float(c.lo), -1.5f);
    EXPECT_FLOAT_EQ(float(c.hi), 2.5f);
}

TEST(LegendImage, UnitsLineIsTheFieldsOwnUnlessTheSessionGivesOne) {
    session::Session s;
    s.field = "Density";
    s.tf = scene::TfChannels::split(scene::makePreset("ramp", 0.0f, 1.0f));
    EXPECT_EQ(session::legendContent(s, "code units (1 = 2.4967e-29 g/cm^3)").units,
              "code units (1 = 2.4967e-29 g/cm^3)");
    EXPECT_EQ(session::legendContent(s, "").units, "");  // not known: no units line
    s.legend.units = "cm^-3";
    EXPECT_EQ(session::legendContent(s, "code units (1 = 2.4967e-29 g/cm^3)").units, "cm^-3");
    EXPECT_EQ(session::legendContent(s, "").units, "cm^-3");
}

TEST(LegendImage, TooSmallPicturesAndBadFontsAreOneLineErrors) {
    if (!fontRenderingAvailable()) {
        test::expectContains(test::errorOf([] { session::openLegendFont({}); }),
                             "--legend: cannot draw text: this amrvk was built without FreeType");
        GTEST_SKIP() << "built without FreeType";
    }
    test::expectContains(test::errorOf([] { session::openLegendFont({.font = "/nonexistent/font.ttf"}); }),
                         "--legend: /nonexistent/font.ttf: no such file");
    const fs::path notFont = test::scratchDir() / "font.ttf";
    std::ofstream(notFont) << "not a font at all\n";
    test::expectContains(test::errorOf([&] { session::openLegendFont({.font = notFont.string()}); }),
                         "not a font FreeType can read");
    const auto font = defaultFont();
    const session::LegendContent c = testContent("Density");
    test::expectContains(
        test::errorOf([&] { session::drawLegend(testPicture(40, 30), c, session::LegendPlace::Side, *font); }),
        "is too small for a legend");
    session::LegendContent longTitle = testContent(std::string(120, 'W'));
    test::expectContains(
        test::errorOf([&] { session::drawLegend(testPicture(64, 128), longTitle, session::LegendPlace::Side, *font); }),
        "shorten the title or units");
    longTitle.title = std::string(300, 'x');
    test::expectContains(
        test::errorOf([&] { session::drawLegend(testPicture(64, 128), longTitle, session::LegendPlace::Side, *font); }),
        "legend: the title text has 300 bytes (at most 256)");
    test::expectContains(
        test::errorOf([&] { session::drawLegend(testPicture(30, 128), c, session::LegendPlace::Overlay, *font); }),
        "too narrow for the legend over it");
}

// Issue 35: a session's legend in a PNG shows its colour map as given (display colours, 8 bits,
// within one step) for srgb TF colours, and for linear ones the colour the picture shows, encoded.
TEST(LegendImage, TheSessionsColourBarShowsTheMapAsGiven) {
    const auto font = defaultFont();
    if (!font) GTEST_SKIP() << "built without FreeType";
    session::Session s;
    s.field = "Density";
    s.tf = scene::TfChannels::split(scene::TransferFunction(
        {0.0f, 1.0f}, {glm::vec4(0.2f, 0.4f, 0.6f, 1.0f), glm::vec4(0.9f, 0.5f, 0.0f, 1.0f)}));
    for (const scene::TfColors colors : {scene::TfColors::Srgb, scene::TfColors::Linear}) {
        s.tfColors = colors;
        const session::LegendContent c = session::legendContent(s, "");
        const session::LegendLayout L = session::legendLayout(80, 120, c, session::LegendPlace::Side, *font);
        const Image8 png = legendPng(testPicture(80, 120), c, session::LegendPlace::Side, *font, "bar.png");
        for (int y = L.colorBar.y; y < L.colorBar.y + L.colorBar.height; ++y) {
            const glm::vec4 given = s.tf.merged().evaluate(float(session::legendBarValue(L, c, y)));
            const Rgb p = pixel(png, L.colorBar.x + 1, y);
            const Rgb want = colors == scene::TfColors::Srgb
                                 ? Rgb{int(std::lround(given.r * 255)), int(std::lround(given.g * 255)),
                                       int(std::lround(given.b * 255))}
                                 : Rgb{srgb8(given.r), srgb8(given.g), srgb8(given.b)};
            ASSERT_TRUE(std::abs(p.r - want.r) <= 1 && std::abs(p.g - want.g) <= 1 && std::abs(p.b - want.b) <= 1)
                << scene::tfColorsName(colors) << " row " << y << ": " << p.r << " " << p.g << " " << p.b
                << ", expected " << want.r << " " << want.g << " " << want.b;
        }
    }
}
