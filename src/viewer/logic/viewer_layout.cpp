#include "viewer/logic/viewer_layout.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace amrvk::viewer {

namespace {

// The least window height of the default window: the panel's sections need room.
constexpr int kDefaultMinHeight = 600;

}  // namespace

ViewerLayout viewerLayout(int windowWidth, int windowHeight, int panelWidth, int imageWidth, int imageHeight) {
    AMRVK_CHECK(imageWidth >= 1 && imageHeight >= 1, "internal: image size ", imageWidth, "x", imageHeight,
                " has no pixels");
    ViewerLayout l;
    l.window = {0, 0, std::max(windowWidth, 0), std::max(windowHeight, 0)};
    if (l.window.empty()) return l;
    const int w = l.window.width, h = l.window.height;
    const int panel = w >= kPanelMinWidth + kPictureMinWidth
                          ? std::clamp(panelWidth, kPanelMinWidth, w - kPictureMinWidth)
                          : w / 2;  // too narrow for both: half each (a 1-pixel window keeps its picture)
    l.panel = {w - panel, 0, panel, h};
    l.area = {0, 0, w - panel, h};
    // The largest rectangle of the image's aspect inside the area (at least one pixel), centred.
    const double scale = std::min(double(l.area.width) / imageWidth, double(l.area.height) / imageHeight);
    const int pw = std::clamp(int(std::lround(imageWidth * scale)), 1, l.area.width);
    const int ph = std::clamp(int(std::lround(imageHeight * scale)), 1, l.area.height);
    l.picture = {l.area.x + (l.area.width - pw) / 2, l.area.y + (l.area.height - ph) / 2, pw, ph};
    return l;
}

void defaultWindowSize(int imageWidth, int imageHeight, int& windowWidth, int& windowHeight) {
    windowWidth = std::max(imageWidth, kPictureMinWidth) + kPanelDefaultWidth;
    windowHeight = std::max(imageHeight, kDefaultMinHeight);
}

}  // namespace amrvk::viewer
