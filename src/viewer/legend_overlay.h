#pragma once
// The colour legend in the viewer window: drawn with ImGui's draw list and font over the picture's
// lower right corner (under the panels), the same content as the PNG legend (session/legend_image.h:
// the TF's colour bar, its opacity over a checkerboard, ticks, title, units). Window pixels are sRGB
// (B8G8R8A8_UNORM), so the TF's colours are encoded as the PNG's are.
#include <imgui.h>

#include <string>

#include "session/session.h"

namespace amrvk::viewer {

// Draws `s`'s legend when s.legend.show, inside the picture's rectangle [pictureMin, pictureMax)
// (window pixels); nothing when the rectangle is too small to hold one. `fieldUnits`: the shown
// field's own units (session::legendContent). Call between ImGui's NewFrame and Render.
void drawLegendOverlay(const session::Session& s, const std::string& fieldUnits, ImVec2 pictureMin,
                       ImVec2 pictureMax);

}  // namespace amrvk::viewer
