#include "viewer/cut_overlay.h"

#include "viewer/logic/cut_handles.h"

namespace amrvk::viewer {

void drawCutOverlay(const session::Session& s, ImVec2 pictureMin, ImVec2 pictureMax, int activeFace) {
    const auto& crop = s.settings.cut.crop;
    if (!crop) return;
    const scene::Camera& cam = s.settings.camera;
    const int w = s.settings.width, h = s.settings.height;
    const float sx = (pictureMax.x - pictureMin.x) / float(w), sy = (pictureMax.y - pictureMin.y) / float(h);
    auto toScreen = [&](glm::dvec2 p) { return ImVec2(pictureMin.x + float(p.x) * sx, pictureMin.y + float(p.y) * sy); };
    ImDrawList* dl = ImGui::GetBackgroundDrawList();
    dl->PushClipRect(pictureMin, pictureMax, true);
    for (const auto& e : CutHandles::edges(*crop)) {
        const auto a = CutHandles::project(cam, w, h, e[0]), b = CutHandles::project(cam, w, h, e[1]);
        if (a && b) dl->AddLine(toScreen(*a), toScreen(*b), IM_COL32(255, 255, 255, 140), 1.0f);
    }
    for (int f = 0; f < 6; ++f) {
        const auto p = CutHandles::project(cam, w, h, CutHandles::faceCentre(*crop, f));
        if (!p) continue;
        const ImVec2 c = toScreen(*p);
        const ImU32 fill = f == activeFace ? IM_COL32(255, 210, 60, 255) : IM_COL32(240, 240, 240, 200);
        dl->AddCircleFilled(c, float(kCutHandleRadius) * 0.7f, fill);
        dl->AddCircle(c, float(kCutHandleRadius) * 0.7f, IM_COL32(20, 20, 20, 220), 0, 1.5f);
    }
    dl->PopClipRect();
}

}  // namespace amrvk::viewer
