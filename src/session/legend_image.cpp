#include "session/legend_image.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace amrvk::session {

namespace {

constexpr int kMinBarRows = 16;
constexpr int kMaxWidthEm = 40;        // the legend block's width, in font sizes
constexpr float kOverlayOpacity = 0.8f;

// Sizes that depend only on the font size.
struct Metrics {
    int fontPx, superscriptPx, lineHeight, baseline, pad, barWidth, tickLength, gap, raise;
};

Metrics metrics(int pictureHeight, const Font& font) {
    Metrics m{};
    m.fontPx = std::clamp(int(std::lround(pictureHeight / 22.0)), 9, 48);
    m.superscriptPx = std::max(6, int(std::lround(m.fontPx * 0.7)));
    const TextBitmap line = font.render("", m.fontPx);
    m.lineHeight = line.height;
    m.baseline = line.baseline;
    m.pad = std::max(3, m.fontPx / 2);
    m.barWidth = std::max(6, m.fontPx);
    m.tickLength = std::max(3, m.fontPx / 2);
    m.gap = std::max(2, m.fontPx / 4);
    m.raise = int(std::lround(m.fontPx * 0.45));  // superscript baseline above the label's
    return m;
}

// Top of a label's line box so that its digits are centred on row `row`.
int labelTop(const Metrics& m, int row) { return row - m.baseline + int(std::lround(m.fontPx * 0.36)); }

// Coverage of `text` blended as ink onto `image` at (x, y), clipped to `clip`.
void drawText(Image& image, const TextBitmap& text, int x, int y, const PixelRect& clip) {
    for (int ty = 0; ty < text.height; ++ty)
        for (int tx = 0; tx < text.width; ++tx) {
            const int px = x + tx, py = y + ty;
            const uint8_t c = text.at(tx, ty);
            if (c == 0 || !clip.contains(px, py)) continue;
            glm::vec4& p = image.at(px, py);
            p = glm::vec4(glm::mix(glm::vec3(p), kLegendInk, float(c) / 255.0f), 1.0f);
        }
}

int labelWidth(const Font& font, const Metrics& m, const LegendTick& t) {
    return font.width(t.label, m.fontPx) + (t.exponent.empty() ? 0 : font.width(t.exponent, m.superscriptPx));
}

}  // namespace

LegendContent legendContent(const Session& s, const std::string& fieldUnits) {
    LegendContent c;
    c.tf = scene::albedoOf(s.tf, s.tfColors);  // linear, as the picture: a PNG shows the map as given
    c.lo = c.tf.firstPosition();
    c.hi = c.tf.lastPosition();
    c.logScale = s.read.scale == amr::FieldScale::Log;
    c.title = legendTitle(s.legend, s.field, c.logScale);
    c.units = legendUnits(s.legend, fieldUnits);
    return c;
}

std::unique_ptr<Font> openLegendFont(const Legend& legend) {
    try {
        return std::make_unique<Font>(legend.font.empty() ? std::string(kDefaultFontFile) : legend.font);
    } catch (const Error& e) {
        throw Error(std::string("--legend: ") + e.what());
    }
}

LegendLayout legendLayout(int pictureWidth, int pictureHeight, const LegendContent& c, LegendPlace place,
                          const Font& font) {
    AMRVK_CHECK(pictureWidth > 0 && pictureHeight > 0, "legend: empty picture ", pictureWidth, "x", pictureHeight);
    for (const std::string* text : {&c.title, &c.units})
        AMRVK_CHECK(text->size() <= kMaxLegendTextBytes, "legend: the ", text == &c.title ? "title" : "units",
                    " text has ", text->size(), " bytes (at most ", kMaxLegendTextBytes, ")");
    const Metrics m = metrics(pictureHeight, font);
    LegendLayout L;
    L.fontPx = m.fontPx;
    L.superscriptPx = m.superscriptPx;
    L.lineHeight = m.lineHeight;
    const int headerLines = c.units.empty() ? 1 : 2;
    const int header = m.pad + headerLines * m.lineHeight;
    // Half a label line (and a superscript's raise) above the top tick and below the bottom one.
    const int barTop = header + m.lineHeight / 2 + m.raise;
    const int below = m.lineHeight / 2 + m.pad;
    const int needed = barTop + kMinBarRows + below;
    const int blockHeight =
        place == LegendPlace::Side ? pictureHeight : std::max(needed, int(std::lround(pictureHeight * 0.6)));
    const int margin = place == LegendPlace::Side ? 0 : m.pad;
    AMRVK_CHECK(blockHeight >= needed && blockHeight + 2 * margin <= pictureHeight, "legend: the picture ",
                pictureWidth, "x", pictureHeight, " is too small for a legend (it needs a height of at least ",
                needed + 2 * margin, " pixels)");
    const int rows = blockHeight - barTop - below;
    L.ticks = legendTicks(c.lo, c.hi, c.logScale, std::clamp(rows / (2 * m.lineHeight), 2, 8));

    int labels = 0;
    for (const LegendTick& t : L.ticks)
        if (t.major) labels = std::max(labels, labelWidth(font, m, t));
    const int headerWidth = std::max(font.width(c.title, m.fontPx), font.width(c.units, m.fontPx));
    const int labelX = m.pad + 2 * m.barWidth + m.tickLength + m.gap;
    const int blockWidth = std::max(labelX + labels + m.pad, m.pad + headerWidth + m.pad);
    AMRVK_CHECK(blockWidth <= kMaxWidthEm * m.fontPx, "legend: '", c.title, "' / '", c.units,
                "' would make the legend ", blockWidth, " pixels wide (at most ", kMaxWidthEm, " times the font's ",
                m.fontPx, " px): shorten the title or units");

    if (place == LegendPlace::Side) {
        L.width = pictureWidth + blockWidth;
        L.height = pictureHeight;
        L.block = {pictureWidth, 0, blockWidth, pictureHeight};
    } else {
        AMRVK_CHECK(blockWidth + 2 * margin <= pictureWidth, "legend: the picture ", pictureWidth, "x", pictureHeight,
                    " is too narrow for the legend over it (", blockWidth + 2 * margin,
                    " pixels needed; --legend-place side puts it beside the picture)");
        L.width = pictureWidth;
        L.height = pictureHeight;
        L.block = {pictureWidth - margin - blockWidth, pictureHeight - margin - blockHeight, blockWidth, blockHeight};
    }
    L.picture = {0, 0, pictureWidth, pictureHeight};
    const int bx = L.block.x, by = L.block.y;
    L.opacityBar = {bx + m.pad, by + barTop, m.barWidth, rows};
    L.colorBar = {bx + m.pad + m.barWidth, by + barTop, m.barWidth, rows};
    L.tickMarks = {bx + m.pad + 2 * m.barWidth, by + barTop, m.tickLength, rows};
    L.text.push_back({bx + m.pad, by + m.pad, blockWidth - 2 * m.pad, headerLines * m.lineHeight});
    const int labelsTop = std::min(labelTop(m, by + barTop), labelTop(m, by + barTop) + m.baseline - m.raise -
                                                                 font.render("", m.superscriptPx).baseline);
    const int labelsBottom = labelTop(m, by + barTop + rows - 1) + m.lineHeight;
    L.text.push_back({bx + labelX, labelsTop, labels, labelsBottom - labelsTop});
    return L;
}

double legendRowValue(const LegendContent& c, int row, int rows) {
    if (!(c.hi > c.lo)) return c.lo;
    return c.hi - (double(row) + 0.5) / double(rows) * (c.hi - c.lo);
}

int legendRowOfTick(const LegendContent& c, double position, int rows) {
    if (!(c.hi > c.lo)) return rows / 2;
    const double f = std::clamp((c.hi - position) / (c.hi - c.lo), 0.0, 1.0);
    return int(std::lround(f * (rows - 1)));
}

double legendBarValue(const LegendLayout& L, const LegendContent& c, int y) {
    return legendRowValue(c, y - L.colorBar.y, L.colorBar.height);
}

int legendTickRow(const LegendLayout& L, const LegendContent& c, double position) {
    return L.colorBar.y + legendRowOfTick(c, position, L.colorBar.height);
}

Image drawLegend(const Image& picture, const LegendContent& c, LegendPlace place, const Font& font) {
    const LegendLayout L = legendLayout(picture.width, picture.height, c, place, font);
    const Metrics m = metrics(picture.height, font);
    Image out(L.width, L.height, glm::vec4(kLegendBackdrop, 1.0f));
    for (int y = 0; y < picture.height; ++y)
        for (int x = 0; x < picture.width; ++x) out.at(x, y) = picture.at(x, y);
    // The backdrop: opaque beside the picture, translucent over it (over the picture as the PNG shows it).
    for (int y = L.block.y; y < L.block.y + L.block.height; ++y)
        for (int x = L.block.x; x < L.block.x + L.block.width; ++x) {
            glm::vec4& p = out.at(x, y);
            const glm::vec3 shown = glm::clamp(glm::vec3(p), 0.0f, 1.0f);
            const glm::vec3 under = glm::all(glm::equal(shown, shown)) ? shown : glm::vec3(0.0f);  // NaN as 0
            p = place == LegendPlace::Side ? glm::vec4(kLegendBackdrop, 1.0f)
                                           : glm::vec4(glm::mix(under, kLegendBackdrop, kOverlayOpacity), 1.0f);
        }
    // The bars.
    const float maxAlpha = c.tf.maxAlpha(c.tf.firstPosition(), c.tf.lastPosition());  // of every node
    const int cell = std::max(2, m.barWidth / 2);
    for (int y = L.colorBar.y; y < L.colorBar.y + L.colorBar.height; ++y) {
        const glm::vec4 tf = c.tf.evaluate(float(legendBarValue(L, c, y)));
        const float opacity = maxAlpha > 0 ? std::clamp(tf.a / maxAlpha, 0.0f, 1.0f) : 0.0f;
        for (int i = 0; i < L.colorBar.width; ++i) out.at(L.colorBar.x + i, y) = glm::vec4(glm::vec3(tf), 1.0f);
        for (int i = 0; i < L.opacityBar.width; ++i) {
            const bool light = ((i / cell) + ((y - L.opacityBar.y) / cell)) % 2 == 1;
            const glm::vec3 checker(light ? kCheckerLight : kCheckerDark);
            out.at(L.opacityBar.x + i, y) = glm::vec4(glm::mix(checker, glm::vec3(tf), opacity), 1.0f);
        }
    }
    // Ticks and their labels.
    const PixelRect& labels = L.text[1];
    for (const LegendTick& t : L.ticks) {
        const int row = legendTickRow(L, c, t.position);
        const int length = t.major ? L.tickMarks.width : std::max(2, L.tickMarks.width / 2);
        for (int i = 0; i < length; ++i) out.at(L.tickMarks.x + i, row) = glm::vec4(kLegendInk, 1.0f);
        if (!t.major) continue;
        const int top = labelTop(m, row);
        drawText(out, font.render(t.label, m.fontPx), labels.x, top, labels);
        if (!t.exponent.empty()) {
            const TextBitmap sup = font.render(t.exponent, m.superscriptPx);
            drawText(out, sup, labels.x + font.width(t.label, m.fontPx), top + m.baseline - m.raise - sup.baseline,
                     labels);
        }
    }
    // Title and units.
    const PixelRect& header = L.text[0];
    drawText(out, font.render(c.title, m.fontPx), header.x, header.y, header);
    if (!c.units.empty()) drawText(out, font.render(c.units, m.fontPx), header.x, header.y + m.lineHeight, header);
    return out;
}

void checkLegendFits(const Session& s, const std::string& fieldUnits, const Font& font) {
    legendLayout(s.settings.width, s.settings.height, legendContent(s, fieldUnits), s.legend.place, font);
}

void writePicture(const std::filesystem::path& path, const Image& picture, const Session& s,
                  const std::string& fieldUnits, const Font* font) {
    if (font) writeImage(path, drawLegend(picture, legendContent(s, fieldUnits), s.legend.place, *font));
    else writeImage(path, picture);
}

}  // namespace amrvk::session
