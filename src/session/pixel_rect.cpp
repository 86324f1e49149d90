#include "session/pixel_rect.h"

namespace amrvk::session {

bool PixelRect::contains(double px, double py) const {
    return !empty() && px >= double(x) && px < double(right()) && py >= double(y) && py < double(bottom());
}

bool overlaps(const PixelRect& a, const PixelRect& b) {
    if (a.empty() || b.empty()) return false;
    return a.x < b.right() && b.x < a.right() && a.y < b.bottom() && b.y < a.bottom();
}

bool inside(const PixelRect& inner, const PixelRect& outer) {
    if (inner.empty()) return true;
    return inner.x >= outer.x && inner.y >= outer.y && inner.right() <= outer.right() &&
           inner.bottom() <= outer.bottom();
}

}  // namespace amrvk::session
