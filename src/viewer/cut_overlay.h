#pragma once
// The crop box over the picture (docs/cut-aways.md): its 12 edges and a handle at the centre of each
// face, projected with the renderer's camera rays (viewer/logic/cut_handles.h), drawn with ImGui's
// background draw list (over the picture, under the panels). Dragging a handle (ViewerApp's
// input) moves that face along its normal.
#include <imgui.h>

#include "session/session.h"

namespace amrvk::viewer {

constexpr double kCutHandleRadius = 7.0;  // picture pixels: what a press must come within to take a handle

// Draws the crop box of `s` (nothing without one) in the picture rectangle [pictureMin, pictureMax)
// (ImGui coordinates), which shows the s.settings.width x height image; `activeFace` (or -1) is
// drawn highlighted. Call between ImGui's NewFrame and Render.
void drawCutOverlay(const session::Session& s, ImVec2 pictureMin, ImVec2 pictureMax, int activeFace);

}  // namespace amrvk::viewer
