#pragma once
// `amrvk view`: the interactive viewer on the same renderer and shaders as `amrvk render`. A
// window (GLFW + Vulkan swapchain + Dear ImGui overlay) or --headless (no window, no display):
// the image accumulates progressively and resets on every change that alters it; while the user
// interacts it renders a preview small enough for one sample to fit the frame budget, and when
// they stop it refines at full resolution in time-budgeted bands of rows, so the UI stays
// responsive whatever one sample costs. Window, swapchain and ImGui code live in src/viewer only;
// the state and its rules are window-free: the session and camera in src/session, the TF editor,
// scripts, frame budget and layout in src/viewer/logic.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "gpu/context.h"
#include "picture/picture.h"
#include "scene/volume.h"
#include "session/picture_description.h"

namespace amrvk::viewer {

// The other processes of an MPI job that render with the viewer (mpirun -n N amrvk view; the CLI
// makes it from mpi/view_link.h): rank 0 runs the viewer, every rank traces a share of each pass.
class RankPasses {
public:
    virtual ~RankPasses() = default;
    virtual int ranks() const = 0;
    // Collective, once rank 0's picture is ready: every rank's is the same picture of the same data
    // (refused with one line otherwise).
    virtual void start(const picture::Picture& p) = 0;
    // One pass of the estimate over the picture as it is now: `perRank` samples per pixel on every
    // rank; rank 0's share is accumulated into p.renderer and the others' are added to it.
    virtual void pass(const picture::Picture& p, uint32_t perRank) = 0;
};

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
    std::shared_ptr<RankPasses> ranks;      // an MPI job's other ranks (null: one process)
    // When the command started (what the time to the first picture counts from: reading included).
    std::chrono::steady_clock::time_point startedAt = std::chrono::steady_clock::now();
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
