#pragma once
// A rectangle of pixels (window-free, unit-tested with the viewer's layout): framebuffer or image
// pixels, origin at the top-left, y down, half-open: [x, x + width) x [y, y + height). The viewer's
// layout (viewer/logic/viewer_layout.h) and the colour legend's (session/legend_image.h) are made
// of them; it lives here, below both, because the legend is drawn by `render --legend` and Python
// too, without the viewer.
namespace amrvk::session {

struct PixelRect {
    int x = 0, y = 0, width = 0, height = 0;
    bool empty() const { return width <= 0 || height <= 0; }
    int right() const { return x + width; }    // one past the last column
    int bottom() const { return y + height; }  // one past the last row
    // Whether pixel (px, py) (a cursor position in pixels: floor of it) lies inside.
    bool contains(double px, double py) const;
    bool operator==(const PixelRect&) const = default;
};
// Whether a and b share a pixel (empty rectangles share none).
bool overlaps(const PixelRect& a, const PixelRect& b);
// Whether `inner` lies in `outer` (an empty inner lies anywhere).
bool inside(const PixelRect& inner, const PixelRect& outer);

}  // namespace amrvk::session
