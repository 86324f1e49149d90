#include "viewer/panels.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.h"
#include "core/strings.h"
#include "scene/limits.h"

namespace amrvk::viewer {

std::string g3(double v) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.3g", v);
    return text;
}

namespace {

const ImVec4 kRed(1.0f, 0.35f, 0.3f, 1.0f);

// Framebuffer pixels per ImGui unit, per axis (1 but on HiDPI screens).
ImVec2 framebufferScale() {
    const ImGuiIO& io = ImGui::GetIO();
    return {io.DisplayFramebufferScale.x > 0 ? io.DisplayFramebufferScale.x : 1.0f,
            io.DisplayFramebufferScale.y > 0 ? io.DisplayFramebufferScale.y : 1.0f};
}

// The last widget's rectangle under `name` in PanelState::widgets, when it is on screen.
void noteWidget(PanelState& p, const std::string& name) {
    if (!ImGui::IsItemVisible()) return;
    const ImVec2 s = framebufferScale(), lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
    const int x0 = int(std::lround(lo.x * s.x)), y0 = int(std::lround(lo.y * s.y));
    p.widgets.push_back({name, {x0, y0, int(std::lround(hi.x * s.x)) - x0, int(std::lround(hi.y * s.y)) - y0}});
}

// A collapsing section header, noted as "NAME header"; true when the section is open.
bool section(PanelState& p, const char* name, ImGuiTreeNodeFlags flags = 0) {
    const bool open = ImGui::CollapsingHeader(name, flags);
    noteWidget(p, std::string(name) + " header");
    return open;
}

// Combo over a fixed list of names; true when the choice changed.
bool namedCombo(const char* label, std::string& value, const std::vector<std::string>& names) {
    bool changed = false;
    if (ImGui::BeginCombo(label, value.c_str())) {
        for (const std::string& n : names) {
            if (ImGui::Selectable(n.c_str(), n == value) && n != value) {
                value = n;
                changed = true;
            }
        }
        ImGui::EndCombo();
    }
    return changed;
}

// namedCombo over an enum's names (parse and name convert); true when the choice changed.
template <typename E>
bool enumCombo(const char* label, E& value, const std::vector<std::string>& names, E (*parse)(const std::string&),
               const char* (*name)(E)) {
    std::string text = name(value);
    if (!namedCombo(label, text, names)) return false;
    value = parse(text);
    return true;
}

bool vec3Edit(const char* label, glm::dvec3& v, float speed) {
    float f[3] = {float(v.x), float(v.y), float(v.z)};
    if (!ImGui::DragFloat3(label, f, speed)) return false;
    v = glm::dvec3(f[0], f[1], f[2]);
    return true;
}

bool colorEdit(const char* label, glm::dvec3& v) {
    // HDR colours: the value can exceed 1 (radiance), so a float editor without clamping.
    float f[3] = {float(v.x), float(v.y), float(v.z)};
    if (!ImGui::ColorEdit3(label, f, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR)) return false;
    v = glm::max(glm::dvec3(f[0], f[1], f[2]), glm::dvec3(0.0));
    return true;
}

// Text that wraps at the panel's edge (long device names, combinations, errors).
void wrapped(const ImVec4* color, const std::string& text) {
    ImGui::PushTextWrapPos(0.0f);
    if (color)
        ImGui::TextColored(*color, "%s", text.c_str());
    else
        ImGui::TextUnformatted(text.c_str());
    ImGui::PopTextWrapPos();
}

void statisticsPanel(const Statistics& s) {
    wrapped(nullptr, s.device);
    wrapped(nullptr, s.combination);
    ImGui::Text("%.1f frames/s (%.1f ms)", s.framesPerSecond, s.frameMilliseconds);
    // Every line here is always drawn, one line each: a line that came and went would move the
    // headers below it between a frame and the next (a click aimed at one would hit another).
    if (s.firstPictureSeconds >= 0)
        ImGui::Text("first picture after %.2f s", s.firstPictureSeconds);
    else
        ImGui::TextUnformatted("first picture: not yet");
    if (s.ranks > 1) ImGui::Text("%d ranks, each a share of every pass", s.ranks);
    ImGui::Text("%.3f M paths/s", s.mPathsPerSecond);
    if (s.previewScale > 1) {
        ImGui::Text("preview 1/%d", s.previewScale);
    } else if (s.sppLimit > 0) {
        ImGui::Text("%u / %u spp", s.spp, s.sppLimit);
    } else {
        ImGui::Text("%u spp", s.spp);
    }
    if (s.rowsDone > 0 && s.previewScale == 1) {
        ImGui::SameLine();
        ImGui::ProgressBar(float(s.rowsDone) / float(std::max(1u, s.height)), ImVec2(120, 0));
    }
    // The kept preview is on screen until the estimate is as clean (scene/preview_hold.h).
    if (s.previewScale == 1 && s.shown == scene::Shown::Preview && s.previewNoise >= 0) {
        const std::string estimate = s.estimateNoise >= 0 ? g3(s.estimateNoise) : "-";
        ImGui::Text("shown: preview, noise %s (estimate %s > %s)", g3(s.previewNoise).c_str(), estimate.c_str(),
                    g3(s.noiseToReach).c_str());
    } else {
        ImGui::Text("shown: %s", s.previewScale > 1 || s.shown == scene::Shown::Preview ? "preview" : "estimate");
    }
    ImGui::Text("%.2f lookups/path, %.2f null/real", s.lookupsPerPath, s.nullPerReal);
    if (s.violations > 0)
        ImGui::TextColored(kRed, "%llu majorant violations", (unsigned long long)s.violations);
    else
        ImGui::Text("0 majorant violations");
    if (s.trackingCapHits > 0)
        wrapped(&kRed, std::to_string(s.trackingCapHits) + " paths stopped at the tracking cap (biased)");
    if (s.nanSamples > 0) ImGui::TextColored(kRed, "%llu NaN samples", (unsigned long long)s.nanSamples);
    ImGui::Text("device memory %.1f MiB", double(s.deviceBytes) / double(1 << 20));
    ImGui::Text("last TF edit %.1f ms", s.tfEditSeconds * 1e3);
    ImGui::Text("last structure build %.2f s", s.structureSeconds);
}

// The opacity curve over the histogram and the colour map; nodes are dragged (left), added
// (double click) and removed (right click).
void tfCanvas(PanelState& p, PanelRequests& r) {
    TfEditor tf(p.edit.tf);
    const float width = std::max(120.0f, ImGui::GetContentRegionAvail().x);
    const ImVec2 size(width, 150.0f);
    const ImVec2 o = ImGui::GetCursorScreenPos();
    ImGui::InvisibleButton("opacity", size, ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->AddRectFilled(o, ImVec2(o.x + size.x, o.y + size.y), IM_COL32(30, 30, 34, 255));
    const float top = std::max(p.alphaDisplayMax, 1e-6f);
    auto toScreen = [&](float x, float a) {
        return ImVec2(o.x + x * size.x, o.y + size.y - std::min(a / top, 1.0f) * (size.y - 4.0f) - 2.0f);
    };
    if (p.histogram && !p.histogram->counts.empty()) {
        const auto& c = p.histogram->counts;
        const double m = std::max(p.histogram->maxCount(), 1e-300);
        const float bw = size.x / float(c.size());
        for (size_t i = 0; i < c.size(); ++i) {
            const double h = p.logHistogram ? std::log1p(c[i]) / std::log1p(m) : c[i] / m;
            if (!(h > 0)) continue;
            dl->AddRectFilled(ImVec2(o.x + float(i) * bw, o.y + size.y - float(h) * size.y),
                              ImVec2(o.x + float(i + 1) * bw, o.y + size.y), IM_COL32(90, 90, 100, 255));
        }
    }
    const std::vector<OpacityNode> nodes = tf.opacity();
    for (size_t i = 0; i + 1 < nodes.size(); ++i)
        dl->AddLine(toScreen(nodes[i].x, nodes[i].alpha), toScreen(nodes[i + 1].x, nodes[i + 1].alpha),
                    IM_COL32(255, 255, 255, 255), 2.0f);
    for (size_t i = 0; i < nodes.size(); ++i)
        dl->AddCircleFilled(toScreen(nodes[i].x, nodes[i].alpha), int(i) == p.draggingNode ? 6.0f : 4.5f,
                            IM_COL32(255, 200, 60, 255));

    const ImVec2 mouse = ImGui::GetMousePos();
    const float mx = std::clamp((mouse.x - o.x) / size.x, 0.0f, 1.0f);
    const float ma = std::max(0.0f, (o.y + size.y - 2.0f - mouse.y) / (size.y - 4.0f) * top);
    const float tolX = 7.0f / size.x, tolA = 7.0f / (size.y - 4.0f) * top;
    if (ImGui::IsItemHovered()) {
        const std::optional<size_t> hit = tf.nodeNear(mx, ma, tolX, tolA);
        if (ImGui::IsMouseClicked(ImGuiMouseButton_Left) && hit) p.draggingNode = int(*hit);
        if (ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left) && !hit) {
            p.draggingNode = int(tf.addNode(mx, ma));
            r.tfChanged = true;
        }
        if (ImGui::IsMouseClicked(ImGuiMouseButton_Right) && hit && *hit > 0 && *hit + 1 < nodes.size()) {
            tf.removeNode(*hit);
            r.tfChanged = r.tfCommitted = true;
        }
        const float value = tf.lo() + mx * (tf.hi() - tf.lo());
        ImGui::SetTooltip("value %.4g   alpha %.4g\ndrag a node; double-click adds one, right-click removes it", value,
                          ma);
    }
    if (p.draggingNode >= 0) {
        if (ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
            const OpacityNode n = tf.opacity()[size_t(p.draggingNode)];
            if (n.x != mx || n.alpha != ma) {
                tf.moveNode(size_t(p.draggingNode), mx, ma);
                r.tfChanged = true;
            }
        } else {
            p.draggingNode = -1;
            r.tfCommitted = true;
        }
    }
    // The colour map under the curve.
    const ImVec2 bar = ImGui::GetCursorScreenPos();
    const std::vector<float> xs = tf.colorPositions();
    const std::vector<glm::vec3>& cs = tf.colors();
    auto col = [](glm::vec3 c) { return ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, 1.0f)); };
    for (size_t i = 0; i + 1 < xs.size(); ++i)
        dl->AddRectFilledMultiColor(ImVec2(bar.x + xs[i] * size.x, bar.y),
                                    ImVec2(bar.x + xs[i + 1] * size.x, bar.y + 14), col(cs[i]), col(cs[i + 1]),
                                    col(cs[i + 1]), col(cs[i]));
    if (xs.size() == 1) dl->AddRectFilled(bar, ImVec2(bar.x + size.x, bar.y + 14), col(cs[0]));
    ImGui::Dummy(ImVec2(size.x, 16));
}

void transferFunctionPanel(PanelState& p, PanelRequests& r) {
    TfEditor tf(p.edit.tf);
    if (!p.colorMapNames.empty()) {
        std::string name = p.colorMapNames[size_t(std::clamp(p.colorMapChoice, 0, int(p.colorMapNames.size()) - 1))];
        if (namedCombo("colour map", name, p.colorMapNames)) {
            p.colorMapChoice =
                int(std::find(p.colorMapNames.begin(), p.colorMapNames.end(), name) - p.colorMapNames.begin());
            r.applyColorMap = true;
        }
    }
    tfCanvas(p, r);
    ImGui::SliderFloat("alpha axis", &p.alphaDisplayMax, 1e-3f, 100.0f, "%.3g", ImGuiSliderFlags_Logarithmic);
    ImGui::Checkbox("log histogram", &p.logHistogram);
    ImGui::SameLine();
    // What the colours mean (scene/tf_colors.h); the colour bar above shows them as given either way.
    bool srgbColours = p.edit.tfColors == scene::TfColors::Srgb;
    if (ImGui::Checkbox("sRGB colours", &srgbColours))
        p.edit.tfColors = srgbColours ? scene::TfColors::Srgb : scene::TfColors::Linear;
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("on: the colour map's colours are display colours, as in ParaView and matplotlib "
                          "(decoded to linear albedo); off: linear albedo as given (--tf-colors linear)");
    ImGui::SameLine();
    // The field's scale: the data is read again (docs/viewer.md), the TF fitted again or moved onto
    // the new range (tfOnNewScale).
    bool logScale = p.edit.read.scale == amr::FieldScale::Log;
    if (ImGui::Checkbox("log scale", &logScale))
        p.edit.read.scale = logScale ? amr::FieldScale::Log : amr::FieldScale::Linear;
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("log10 of each cell's value (read again; the TF keeps its shape on the new range)");
    if (p.edit.read.scale == amr::FieldScale::Log) {
        double floor = p.edit.read.logFloor;
        if (ImGui::InputDouble("log floor", &floor, 0.0, 0.0, "%.6g", ImGuiInputTextFlags_EnterReturnsTrue))
            p.edit.read.logFloor = floor;  // checked by the viewer (>= 0)
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip(
                "values below it (and every value <= 0) become log10 of it; 0: the field's smallest "
                "positive value (Enter applies)");
    }
    ImGui::Checkbox("legend", &p.edit.legend.show);
    float range[2] = {tf.lo(), tf.hi()};
    if (ImGui::InputFloat2("value range", range, "%.5g", ImGuiInputTextFlags_EnterReturnsTrue)) {
        try {
            tf.setRange(range[0], range[1]);
            r.tfChanged = r.tfCommitted = true;
        } catch (const Error& e) {
            p.message = e.what();
        }
    }
    if (ImGui::Button("data range")) r.resetRange = true;
    float density = float(p.edit.settings.densityScale);
    if (ImGui::SliderFloat("density scale", &density, 1e-4f, 1e4f, "%.4g", ImGuiSliderFlags_Logarithmic))
        p.edit.settings.densityScale = std::max(0.0f, density);
    ImGui::BeginDisabled(!p.canUndo);
    if (ImGui::Button("undo")) r.undo = true;
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::BeginDisabled(!p.canRedo);
    if (ImGui::Button("redo")) r.redo = true;
    ImGui::EndDisabled();
    ImGui::InputText("TF file", &p.tfPath);
    if (ImGui::Button("load ParaView presets")) r.loadTfFile = true;
    ImGui::SameLine();
    if (ImGui::Button("save as ParaView JSON")) r.saveTfFile = true;
}

// Edits the settings of the copy (the viewer validates them and compares them with its state).
void renderPanel(PanelState& p) {
    scene::RenderSettings& s = p.edit.settings;
    enumCombo("mode", s.mode, {"ae", "ss", "ms", "dvr"}, scene::parseMode, scene::modeName);
    float g = float(s.g);
    if (ImGui::SliderFloat("phase g", &g, -0.99f, 0.99f)) s.g = g;
    if (s.mode == scene::Mode::Dvr) {
        float dt = float(s.dvrStep);
        if (ImGui::SliderFloat("dvr step", &dt, 0.05f, 4.0f, "%.3g", ImGuiSliderFlags_Logarithmic)) s.dvrStep = dt;
        ImGui::Checkbox("gradient shading", &s.dvrShading);
    }
    if (scene::castsShadowRays(s.mode))
        enumCombo("shadow estimator", s.transmittance, {"ratio", "ubrm"}, scene::parseTransmittance,
                  scene::transmittanceName);
    if (s.mode != scene::Mode::Dvr)
        enumCombo("control extinction", s.controlExtinction, {"none", "minorant"}, scene::parseControlExtinction,
                  scene::controlExtinctionName);
    int spp = int(p.edit.spp);
    if (ImGui::InputInt("stop at spp (0: never)", &spp)) p.edit.spp = uint32_t(std::max(0, spp));
    colorEdit("ambient", s.ambient);
    glm::dvec3 bg = s.background.value_or(s.ambient);
    if (colorEdit("background", bg)) s.background = bg;
    ImGui::TextUnformatted("lights");
    for (size_t i = 0; i < s.lights.size(); ++i) {
        ImGui::PushID(int(i));
        scene::Light& L = s.lights[i];
        vec3Edit(L.point ? "position" : "direction", L.posOrDir, 0.01f);
        colorEdit(L.point ? "intensity" : "radiance", L.radiance);
        if (ImGui::Button("remove light")) {
            s.lights.erase(s.lights.begin() + std::ptrdiff_t(i));
            ImGui::PopID();
            break;
        }
        ImGui::Separator();
        ImGui::PopID();
    }
    if (s.lights.size() < 8 && ImGui::Button("add sun")) s.lights.push_back({false, {1.0, -1.0, 2.0}, glm::dvec3(3.0)});
}

// Crop box (a range slider per axis over the data's world bounds) and clip planes. Switching the
// crop off keeps its box for switching it on again.
void cutAwayPanel(PanelState& p) {
    scene::CutAway& cut = p.edit.settings.cut;
    bool crop = cut.crop.has_value();
    if (ImGui::Checkbox("crop box", &crop)) {
        if (crop) {
            cut.crop = p.cropMemory.value_or(scene::CropBox{p.worldLo, p.worldHi});
        } else {
            p.cropMemory = cut.crop;
            cut.crop.reset();
        }
    }
    if (cut.crop) {
        for (int a = 0; a < 3; ++a) {
            const float lo = float(p.worldLo[a]), hi = float(p.worldHi[a]);
            float v0 = float(cut.crop->lo[a]), v1 = float(cut.crop->hi[a]);
            const char* label = a == 0 ? "x range" : a == 1 ? "y range" : "z range";
            if (ImGui::DragFloatRange2(label, &v0, &v1, (hi - lo) / 400.0f, lo, hi, "%.4g", "%.4g",
                                       ImGuiSliderFlags_AlwaysClamp) &&
                v0 < v1) {
                cut.crop->lo[a] = v0;
                cut.crop->hi[a] = v1;
            }
        }
    }
    for (size_t i = 0; i < cut.clips.size(); ++i) {
        ImGui::PushID(int(i) + 100);
        ImGui::Text("plane %zu (removes the side the normal points to)", i + 1);
        vec3Edit("point", cut.clips[i].point, float(glm::length(p.worldHi - p.worldLo) / 400.0));
        vec3Edit("normal", cut.clips[i].normal, 0.01f);
        if (ImGui::Button("flip")) cut.clips[i].normal = -cut.clips[i].normal;
        ImGui::SameLine();
        if (ImGui::Button("remove plane")) {
            cut.clips.erase(cut.clips.begin() + std::ptrdiff_t(i));
            ImGui::PopID();
            break;
        }
        ImGui::PopID();
    }
    if (cut.clips.size() < shared::kMaxClipPlanes && ImGui::Button("add clip plane"))
        cut.clips.push_back({0.5 * (p.worldLo + p.worldHi), {1.0, 0.0, 0.0}});
}

void structurePanel(PanelState& p, PanelRequests& r) {
    scene::StructureConfig& c = p.edit.structure;
    std::vector<std::string> traversals, samplers;
    for (scene::TraversalKind t : scene::allTraversals()) traversals.push_back(scene::traversalName(t));
    for (const scene::SamplerTraits& t : scene::kSamplerTraits) samplers.push_back(t.name);
    enumCombo("traversal", c.traversal, traversals, scene::parseTraversal, scene::traversalName);
    enumCombo("sampler", c.sampler, samplers, scene::parseSampler, scene::samplerName);
    enumCombo("back-end", c.backend, {"sw", "rq", "auto"}, scene::parseBackend, scene::backendName);
    if (ImGui::InputText("macrocell grid", &p.gridText, ImGuiInputTextFlags_EnterReturnsTrue)) r.gridEntered = true;
    int leaves = int(c.kdLeaves);
    if (ImGui::InputInt("kd leaves", &leaves, 256, 1024, ImGuiInputTextFlags_EnterReturnsTrue))
        c.kdLeaves = uint32_t(std::clamp(leaves, 1, int(scene::kMaxKdLeaves)));
    std::string sub = scene::subMajorantsName(c.subMajorants);
    if (namedCombo("sub-majorants", sub, {"off", "2", "4", "8", "16"})) c.subMajorants = scene::parseSubMajorants(sub);
    if (!p.structureError.empty()) wrapped(&kRed, "not applied: " + p.structureError);
}

void cameraPanel(PanelState& p, PanelRequests& r) {
    scene::Camera& cam = p.edit.settings.camera;
    float fov = float(cam.fovYDegrees);
    if (ImGui::SliderFloat("field of view", &fov, 5.0f, 120.0f)) session::OrbitCamera::setFov(cam, fov);
    const int up = session::OrbitCamera::upAxis(cam);
    ImGui::TextUnformatted("up axis");
    for (int a = 0; a < 3; ++a) {
        ImGui::SameLine();
        if (ImGui::RadioButton(a == 0 ? "x" : a == 1 ? "y" : "z", up == a)) session::OrbitCamera::setUpAxis(cam, a);
    }
    if (ImGui::Button("reset view (R)")) r.resetView = true;
    ImGui::SameLine();
    if (ImGui::Button("copy as command")) r.copyCommand = true;
    if (ImGui::Checkbox("image size = picture area", &p.imageFollowsWindow) && !p.imageFollowsWindow)
        p.message = "image size kept at " + std::to_string(p.edit.settings.width) + "x" +
                    std::to_string(p.edit.settings.height);
    noteWidget(p, "image size = picture area");
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("the rendered image (and so the camera's aspect) follows the picture area, pixel for pixel");
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    wrapped(nullptr, "over the picture: left drag orbits, right drag or wheel zooms, middle or shift drag pans");
    ImGui::PopStyleColor();
}

// Keyframes of the current camera at a frame (add, delete, move), the path's fps, the frame slider
// (shows that frame's camera) and play/stop; the app carries the requests out.
void cameraPathPanel(PanelState& p, PanelRequests& r) {
    const session::CameraPath& path = p.edit.cameraPath;
    PathRequests& q = r.path;
    const int last = int(session::kMaxPathFrames) - 1;
    ImGui::InputInt("keyframe frame", &p.keyframeFrame);
    p.keyframeFrame = std::clamp(p.keyframeFrame, 0, last);
    if (ImGui::Button("add at current camera (K)")) q.add = uint32_t(p.keyframeFrame);
    ImGui::SameLine();
    if (ImGui::Button("delete keyframe")) q.remove = uint32_t(p.keyframeFrame);
    ImGui::InputInt("move it to frame", &p.keyframeTo);
    p.keyframeTo = std::clamp(p.keyframeTo, 0, last);
    if (ImGui::Button("move keyframe")) q.move = std::pair(uint32_t(p.keyframeFrame), uint32_t(p.keyframeTo));
    float fps = float(path.fps());
    if (ImGui::InputFloat("frames per second", &fps, 0, 0, "%.3g", ImGuiInputTextFlags_EnterReturnsTrue)) q.fps = fps;
    if (path.empty()) {
        wrapped(nullptr, "no keyframes: set the view, then add one (K adds after the last)");
        return;
    }
    std::string frames;
    for (const session::Keyframe& k : path.keyframes())
        frames += (frames.empty() ? "" : ", ") + std::to_string(k.frame);
    wrapped(nullptr, "keyframes at " + frames + " (" + std::to_string(path.frameCount()) + " frames)");
    int frame = std::clamp(p.pathFrame, 0, int(path.frameCount()) - 1);
    if (ImGui::SliderInt("path frame", &frame, 0, int(path.frameCount()) - 1)) q.show = uint32_t(frame);
    if (ImGui::Button(p.pathPlaying ? "stop (P)" : "play (P)")) (p.pathPlaying ? q.stop : q.play) = true;
}

void filesPanel(PanelState& p, PanelRequests& r) {
    ImGui::InputText("image", &p.screenshotPath);
    if (ImGui::Button("save image")) r.screenshot = true;
    ImGui::InputText("session", &p.sessionPath);
    if (ImGui::Button("save session")) r.saveSession = true;
    ImGui::SameLine();
    if (ImGui::Button("load session")) r.loadSession = true;
}

}  // namespace

UiRect toUi(const session::PixelRect& r) {
    const ImVec2 s = framebufferScale();
    return {float(r.x) / s.x, float(r.y) / s.y, float(r.width) / s.x, float(r.height) / s.y};
}

namespace {

// A time series: the time slider, play/pause, steps per second, what the step is, read ahead.
void seriesPanel(PanelState& p, PanelRequests& r) {
    int step = int(p.seriesStep);
    if (ImGui::SliderInt("step", &step, 0, int(p.seriesSteps) - 1)) r.seriesStep = size_t(step);
    noteWidget(p, "seriesStep");
    if (ImGui::Button(p.seriesPlaying ? "pause (space)" : "play (space)")) r.seriesPlayToggle = true;
    noteWidget(p, "seriesPlay");
    ImGui::SameLine();
    if (ImGui::Button("<")) r.seriesStep = (p.seriesStep + p.seriesSteps - 1) % p.seriesSteps;
    ImGui::SameLine();
    if (ImGui::Button(">")) r.seriesStep = (p.seriesStep + 1) % p.seriesSteps;
    float fps = float(p.seriesFps);
    if (ImGui::SliderFloat("steps/s", &fps, 0.25f, 30.0f, "%.2f", ImGuiSliderFlags_Logarithmic)) r.seriesFps = fps;
    wrapped(nullptr, p.seriesLabel);
    const Statistics& s = *p.stats;
    std::string ahead;
    for (size_t k : s.seriesAhead) ahead += (ahead.empty() ? "" : ", ") + std::to_string(k);
    wrapped(nullptr, strCat("read ahead: ", ahead.empty() ? std::string("none") : ahead, " (",
                            g3(double(s.seriesAheadBytes) / double(1 << 20)), " of ", p.seriesAheadBudget >> 20,
                            " MiB); last step built in ", g3(s.stepSeconds), " s"));
}

}  // namespace

void drawPanels(PanelState& p, PanelRequests& r) {
    // The layout is in framebuffer pixels, ImGui in window coordinates (they differ on HiDPI screens).
    const ImVec2 scale = framebufferScale();
    const float sx = scale.x, sy = scale.y;
    const session::PixelRect& pr = p.panelRect;
    p.widgets.clear();
    if (pr.empty()) return;
    const float height = float(pr.height) / sy;
    // Placed when the layout moves it; in between ImGui keeps what the user dragged it to, and the
    // width read back below goes through the layout's limits before it is placed again.
    if (!(pr == p.panelPlaced)) {
        ImGui::SetNextWindowPos(ImVec2(float(pr.x) / sx, float(pr.y) / sy), ImGuiCond_Always);
        ImGui::SetNextWindowSize(ImVec2(float(pr.width) / sx, height), ImGuiCond_Always);
        p.panelPlaced = pr;
    }
    // Its left edge can be dragged; the app clamps the width (viewerLayout).
    ImGui::SetNextWindowSizeConstraints(ImVec2(float(std::min(kPanelMinWidth, pr.width)) / sx, height),
                                        ImVec2(float(pr.right()) / sx, height));
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse |
                                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBringToFrontOnFocus;
    if (ImGui::Begin("amrvk", nullptr, flags)) {
        p.panelWidth = int(std::lround(ImGui::GetWindowWidth() * sx));
        // The label column: the widest label and its spacing; widgets take the rest.
        const ImGuiStyle& style = ImGui::GetStyle();
        const float labels = ImGui::CalcTextSize("stop at spp (0: never)").x + style.ItemInnerSpacing.x * 2;
        ImGui::PushItemWidth(-labels);
        if (section(p, "statistics", ImGuiTreeNodeFlags_DefaultOpen)) statisticsPanel(*p.stats);
        if (p.seriesSteps > 1 && section(p, "time series", ImGuiTreeNodeFlags_DefaultOpen)) seriesPanel(p, r);
        if (section(p, "transfer function", ImGuiTreeNodeFlags_DefaultOpen)) transferFunctionPanel(p, r);
        if (section(p, "render")) renderPanel(p);
        if (section(p, "cut-away")) cutAwayPanel(p);
        if (section(p, "structures")) structurePanel(p, r);
        if (section(p, "camera")) cameraPanel(p, r);
        if (section(p, "camera path")) cameraPathPanel(p, r);
        if (section(p, "files")) filesPanel(p, r);
        if (!p.shaderError.empty()) wrapped(&kRed, "shader: " + p.shaderError);
        if (!p.message.empty()) wrapped(nullptr, p.message);
        ImGui::PopItemWidth();
    }
    ImGui::End();
}

}  // namespace amrvk::viewer
