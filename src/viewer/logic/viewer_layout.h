#pragma once
// Where the viewer's window puts things (window-free, unit-tested): a side panel docked at the
// right edge, full height, and the picture in the area left of it, as large as fits with the
// image's own aspect (the camera's: width/height of the session's image size), centred. The panel
// and the picture never overlap, at any window size. All rectangles are in framebuffer pixels,
// origin at the window's top-left, y down, half-open: [x, x + width) x [y, y + height).
// The viewer takes the picture rectangle from here for the display pass, mouse control and any
// overlay drawn over the picture (e.g. a colour legend).
#include "session/pixel_rect.h"

namespace amrvk::viewer {

// Panel widths in pixels: the default, the narrowest a user may drag it to (its labels still fit),
// and the least width the picture area keeps beside it.
constexpr int kPanelDefaultWidth = 440;
constexpr int kPanelMinWidth = 300;
constexpr int kPictureMinWidth = 160;

struct ViewerLayout {
    session::PixelRect window;   // the whole framebuffer
    session::PixelRect panel;    // the docked side panel: right edge, full height
    session::PixelRect area;     // what the panel leaves: left of it, full height
    session::PixelRect picture;  // the image shown: inside area, the image's aspect, centred
};

// The layout of a window of windowWidth x windowHeight pixels with a panel asked to be
// panelWidth wide, showing an image of imageWidth x imageHeight pixels. The panel width is
// clamped to [kPanelMinWidth, window - kPictureMinWidth]; a window too narrow for both splits
// in half. A window of no pixels (minimised) gives empty rectangles. Throws for image sizes < 1.
ViewerLayout viewerLayout(int windowWidth, int windowHeight, int panelWidth, int imageWidth, int imageHeight);

// The window size whose picture area is imageWidth x imageHeight beside a default panel: the
// viewer's window when --window is not given (the image then shows pixel for pixel).
void defaultWindowSize(int imageWidth, int imageHeight, int& windowWidth, int& windowHeight);

}  // namespace amrvk::viewer
