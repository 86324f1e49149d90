#pragma once
// The viewer's ImGui panels, in one side panel docked at the window's right edge (its rectangle
// from viewer/logic/viewer_layout.h, so it never covers the picture; the user may drag its left edge):
// statistics, transfer-function editor (colour map, draggable opacity curve over the field
// histogram, log scale, value range, density), render settings and lights, structures, camera,
// camera path (keyframes, preview), files (screenshot, session, TF). They edit a copy of the
// picture (PanelState::edit) and raise requests; the app validates the copy and applies what
// changed, so a rejected edit never reaches its state or a session. Widgets leave a label column as
// wide as the widest label, so no label is cut off at the panel's minimum width. All ImGui widget
// code is here.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "scene/preview_hold.h"
#include "session/orbit_camera.h"
#include "session/session.h"
#include "viewer/logic/histogram.h"
#include "viewer/logic/tf_editor.h"
#include "viewer/logic/viewer_layout.h"

namespace amrvk::viewer {

struct Statistics {
    std::string device, combination;
    double framesPerSecond = 0, frameMilliseconds = 0;
    double mPathsPerSecond = 0, lookupsPerPath = 0, nullPerReal = 0;
    uint64_t violations = 0, trackingCapHits = 0, nanSamples = 0;
    uint32_t spp = 0, sppLimit = 0, rowsDone = 0, height = 0;
    int previewScale = 1;  // > 1: showing a preview rendered at 1/scale of the size
    scene::Shown shown = scene::Shown::Nothing;                      // on screen: the kept preview or the estimate
    double previewNoise = -1, estimateNoise = -1, noiseToReach = 0;  // -1: not measured
    uint64_t deviceBytes = 0;
    int ranks = 1;                    // processes tracing each pass (mpirun -n N amrvk view)
    double firstPictureSeconds = -1;  // from the command's start to the first picture on screen (-1: none yet)
    double tfEditSeconds = 0, structureSeconds = 0;  // last TF edit, last structure change (wall)
    // A time series: the steps read ahead (and their host bytes), the last step's build (wall).
    std::vector<size_t> seriesAhead;
    uint64_t seriesAheadBytes = 0;
    double stepSeconds = 0;
};

// The camera path section's requests (the app carries them out: viewer_camera_path.cpp).
struct PathRequests {
    std::optional<uint32_t> add;                        // a keyframe of the current camera at this frame
    std::optional<uint32_t> remove;                     // delete the keyframe at this frame
    std::optional<std::pair<uint32_t, uint32_t>> move;  // from, to
    std::optional<uint32_t> show;                       // the path frame whose camera to show (the slider)
    std::optional<double> fps;
    bool play = false, stop = false;
};

// `v` to three significant digits ("0.0887", "1.2e+03"): the noises and seconds the panel and
// the screenshot's line show.
std::string g3(double v);

struct PanelRequests {
    bool tfChanged = false;    // the editor state changed this frame (live)
    bool tfCommitted = false;  // an edit finished (push to the undo history)
    bool undo = false, redo = false;
    bool gridEntered = false;  // the macrocell grid text was entered (PanelState::gridText)
    bool resetRange = false;
    bool resetView = false;
    bool screenshot = false, saveSession = false, loadSession = false, copyCommand = false;
    bool loadTfFile = false, saveTfFile = false, applyColorMap = false;
    std::optional<size_t> seriesStep;  // the time slider moved to a step
    bool seriesPlayToggle = false;
    std::optional<double> seriesFps;
    PathRequests path;
};

struct PanelState {
    const Statistics* stats = nullptr;
    session::Session edit;  // this frame's copy of the picture: the panels edit it, the app applies it
    const Histogram* histogram = nullptr;
    bool canUndo = false, canRedo = false;
    std::vector<std::string> colorMapNames;  // built-in ones, then those of a loaded file
    int colorMapChoice = 0;
    bool logHistogram = true;
    float alphaDisplayMax = 1.0f;  // top of the opacity curve's axis
    std::string message;           // last status line (saved files, errors)
    std::string shaderError;       // compile error of the watched shaders (red)
    std::string structureError;    // why the last structure choice was rejected (red; the old one stays)
    std::string screenshotPath = "amrvk-view.png";
    std::string sessionPath = "amrvk-session.json";
    std::string tfPath = "amrvk-tf.json";
    // A time series (none: seriesSteps 0): the step shown, playing, steps per second, and what the
    // step is ("out_2.cells, t = 0.15") and the read-ahead budget.
    size_t seriesSteps = 0, seriesStep = 0;
    bool seriesPlaying = false;
    double seriesFps = 4;
    std::string seriesLabel;
    uint64_t seriesAheadBudget = 0;
    std::string gridText;                          // the macrocell grid as typed, applied on Enter
    int draggingNode = -1;                         // opacity node under a drag, between frames
    session::PixelRect panelRect;                  // where the panel goes (framebuffer pixels; the app's layout)
    int panelWidth = kPanelDefaultWidth;           // out: the width the user dragged the panel to
    session::PixelRect panelPlaced;                // the rectangle last handed to ImGui (a user's drag is kept between)
    glm::dvec3 worldLo{0.0}, worldHi{1.0};         // the data's world bounds (cut-away ranges and handles)
    std::optional<scene::CropBox> cropMemory;      // the crop box while it is switched off (not lost)
    bool imageFollowsWindow = false;               // the image size follows the picture area (camera aspect included)
    int keyframeFrame = 0, keyframeTo = 0;         // the camera path section's frame fields
    int pathFrame = -1;                            // the path frame shown (-1: none; the slider's value)
    bool pathPlaying = false;                      // the path's preview is playing
    // out: where the section headers ("camera header", ...) and the "image size = picture area"
    // checkbox were drawn this frame, those on screen only (framebuffer pixels; --state-file).
    std::vector<std::pair<std::string, session::PixelRect>> widgets;
};

// Draws every panel for this frame and fills `requests`.
void drawPanels(PanelState& panel, PanelRequests& requests);

// A layout rectangle (framebuffer pixels) in ImGui's coordinates (window coordinates: they differ
// on HiDPI screens), for ImGui code that draws over the picture (the legend and crop-box overlays
// over the layout's picture rectangle). Call between ImGui's NewFrame and Render.
struct UiRect {
    float x = 0, y = 0, width = 0, height = 0;
};
UiRect toUi(const session::PixelRect& r);

}  // namespace amrvk::viewer
