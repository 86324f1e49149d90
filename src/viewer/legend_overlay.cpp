#include "viewer/legend_overlay.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "core/image_io.h"
#include "session/legend_image.h"

namespace amrvk::viewer {

namespace {

ImU32 srgb(glm::vec3 linear, float alpha = 1.0f) {
    return IM_COL32(encodeSrgb8(linear.r), encodeSrgb8(linear.g), encodeSrgb8(linear.b), int(std::lround(alpha * 255)));
}

}  // namespace

void drawLegendOverlay(const session::Session& s, const std::string& fieldUnits, ImVec2 pictureMin,
                       ImVec2 pictureMax) {
    if (!s.legend.show) return;
    const session::LegendContent c = session::legendContent(s, fieldUnits);
    ImFont* font = ImGui::GetFont();
    const float px = ImGui::GetFontSize(), sup = std::round(px * 0.7f);
    const float pad = std::round(px * 0.5f), bar = px, tick = std::round(px * 0.5f), gap = std::round(px * 0.3f);
    const float line = px * 1.2f, raise = std::round(px * 0.45f);
    auto width = [&](const std::string& text, float size) {
        return font->CalcTextSizeA(size, FLT_MAX, 0, text.c_str()).x;
    };

    const int headerLines = c.units.empty() ? 1 : 2;
    const float header = pad + float(headerLines) * line;
    const float barTop = header + line * 0.5f + raise, below = line * 0.5f + pad;
    const float pictureHeight = pictureMax.y - pictureMin.y, pictureWidth = pictureMax.x - pictureMin.x;
    const float blockHeight = std::max(barTop + 16 + below, std::round(pictureHeight * 0.45f));
    const float rows = std::floor(blockHeight - barTop - below);
    if (blockHeight + 2 * pad > pictureHeight) return;
    const std::vector<session::LegendTick> ticks =
        session::legendTicks(c.lo, c.hi, c.logScale, std::clamp(int(rows / (2 * line)), 2, 8));
    float labels = 0;
    for (const session::LegendTick& t : ticks)
        if (t.major) labels = std::max(labels, width(t.label, px) + (t.exponent.empty() ? 0 : width(t.exponent, sup)));
    const float labelX = pad + 2 * bar + tick + gap;
    const float blockWidth =
        std::max(labelX + labels + pad, 2 * pad + std::max(width(c.title, px), width(c.units, px)));
    if (blockWidth + 2 * pad > pictureWidth) return;

    ImDrawList* dl = ImGui::GetBackgroundDrawList();  // over the picture, under the panels
    const ImVec2 o(std::floor(pictureMax.x - pad - blockWidth), std::floor(pictureMax.y - pad - blockHeight));
    dl->AddRectFilled(o, ImVec2(o.x + blockWidth, o.y + blockHeight), srgb(session::kLegendBackdrop, 0.8f));
    const float maxAlpha = c.tf.maxAlpha(c.tf.firstPosition(), c.tf.lastPosition());  // of every node
    const float cell = std::max(2.0f, std::floor(bar / 2));
    const float y0 = o.y + barTop, xo = o.x + pad, xc = xo + bar;
    for (int r = 0; r < int(rows); ++r) {
        const glm::vec4 tf = c.tf.evaluate(float(session::legendRowValue(c, r, int(rows))));
        const float opacity = maxAlpha > 0 ? std::clamp(tf.a / maxAlpha, 0.0f, 1.0f) : 0.0f;
        const float y = y0 + float(r);
        dl->AddRectFilled(ImVec2(xc, y), ImVec2(xc + bar, y + 1), srgb(glm::vec3(tf)));
        for (int k = 0; float(k) * cell < bar; ++k) {
            const bool light = (k + int(float(r) / cell)) % 2 == 1;
            const glm::vec3 checker(light ? session::kCheckerLight : session::kCheckerDark);
            dl->AddRectFilled(ImVec2(xo + float(k) * cell, y), ImVec2(std::min(xo + float(k + 1) * cell, xc), y + 1),
                              srgb(glm::mix(checker, glm::vec3(tf), opacity)));
        }
    }
    const ImU32 ink = srgb(session::kLegendInk);
    const float xt = xc + bar;
    for (const session::LegendTick& t : ticks) {
        const float y = y0 + float(session::legendRowOfTick(c, t.position, int(rows))) + 0.5f;
        dl->AddLine(ImVec2(xt, y), ImVec2(xt + (t.major ? tick : tick / 2), y), ink);
        if (!t.major) continue;
        const float top = y - px * 0.5f;
        dl->AddText(font, px, ImVec2(o.x + labelX, top), ink, t.label.c_str());
        if (!t.exponent.empty())
            dl->AddText(font, sup, ImVec2(o.x + labelX + width(t.label, px), top - raise + px - sup), ink,
                        t.exponent.c_str());
    }
    dl->AddText(font, px, ImVec2(o.x + pad, o.y + pad), ink, c.title.c_str());
    if (!c.units.empty()) dl->AddText(font, px, ImVec2(o.x + pad, o.y + pad + line), ink, c.units.c_str());
}

}  // namespace amrvk::viewer
