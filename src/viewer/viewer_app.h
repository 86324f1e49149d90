#pragma once
// `amrvk view`: the interactive viewer on the same renderer and shaders as `amrvk render`. A
// window (GLFW + Vulkan swapchain + Dear ImGui overlay) or --headless (no window, no display):
// the image accumulates progressively and resets on every change that alters it; while the user
// interacts it renders a preview small enough for one sample to fit the frame budget, and when
// they stop it refines at full resolution in time-budgeted bands of rows, so the UI stays
// responsive whatever one sample costs. Window, swapchain and ImGui code live in src/viewer only;
// the state and its rules are window-free: the session and camera in src/session, the TF editor,
// scripts, frame budget and layout in src/viewer/logic.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "gpu/context.h"
#include "scene/volume.h"
#include "session/picture_description.h"

namespace amrvk::viewer {

struct ViewerOptions {
    session::PictureDescription start;      // what to show first (fitted to the volume like render's)
    bool headless = false;                  // no window: automation and tests
    uint64_t frames = 0;                    // stop after this many frames (0: until the window closes)
    std::filesystem::path screenshot;       // at exit: the accumulated linear image (.png, .exr, .pfm), no UI
    std::filesystem::path script;           // frame-numbered actions (viewer/logic/script.h)
    std::filesystem::path shaderDir;        // watched: a saved edit recompiles and swaps the pipeline
    std::filesystem::path statsJson;        // at exit: frame times, times to the first full sample, resets
    std::filesystem::path stateJson;        // after every frame: the live state (frame, camera, layout, input seen)
    std::filesystem::path saveSession;      // at exit: the state as a session file
    gpu::ContextOptions context;            // with validation, any validation error makes the exit status 1
    double frameBudgetSeconds = 0.05;       // target frame time; path tracing gets what the UI leaves of it
    int windowWidth = 0, windowHeight = 0;  // 0: the session's image size
    // A time series (several inputs, a glob): every step's input in natural order, start's input
    // the first (its TF range already fixed for the series: --series-range). Empty: one data set.
    std::vector<std::string> series;
    double seriesFps = 4;                           // steps per second while playing
    uint64_t seriesAheadBytes = uint64_t(1) << 30;  // host memory for the steps read ahead
};

// Shows `volume` (read with options.start's input, read options and field: session::loadVolume)
// until the window closes, the frames are done or a script says quit. Returns the exit status: 0,
// or 1 after Vulkan validation errors with `validation`.
int runViewer(const ViewerOptions& options, std::shared_ptr<const scene::Volume> volume);

}  // namespace amrvk::viewer
