#pragma once
// The viewer's application object (internal to src/viewer): the state of one `amrvk view` run and
// its frame loop. Its members are defined by concern: viewer_app.cpp (the picture, its edits and
// the frame loop), viewer_input.cpp (keys and mouse), viewer_script.cpp (frame-numbered script
// actions), viewer_capture.cpp (screenshots and window captures), viewer_report.cpp (--stats and
// --state-file), viewer_session_io.cpp (session files and copy-as-command) and
// viewer_camera_path.cpp (the camera path's keyframes and preview).
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include "core/font.h"
#include "core/image_io.h"
#include "gpu/buffer.h"
#include "gpu/context.h"
#include "picture/picture.h"
#include "render/display_pass.h"
#include "scene/preview_hold.h"
#include "session/orbit_camera.h"
#include "session/session.h"
#include "viewer/imgui_layer.h"
#include "viewer/logic/file_watcher.h"
#include "viewer/logic/frame_budget.h"
#include "viewer/logic/histogram.h"
#include "viewer/logic/script.h"
#include "viewer/logic/series_player.h"
#include "viewer/logic/tf_editor.h"
#include "viewer/logic/viewer_layout.h"
#include "viewer/panels.h"
#include "viewer/swapchain.h"
#include "viewer/viewer_app.h"
#include "viewer/window.h"

namespace amrvk::viewer {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Frame times and the time from each change to the first complete full-resolution sample.
struct Timings {
    std::vector<double> interactiveFrames, idleFrames, toFirstFullSample;
    static double percentile(std::vector<double> v, double p) {
        if (v.empty()) return 0.0;
        std::sort(v.begin(), v.end());
        return v[std::min(v.size() - 1, size_t(p * double(v.size() - 1) + 0.5))];
    }
    static double mean(const std::vector<double>& v) {
        return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
    }
};

class ViewerApp {
public:
    ViewerApp(const ViewerOptions& o, std::shared_ptr<const scene::Volume> volume);
    ~ViewerApp();  // viewer_series.cpp: stops the read-ahead worker
    int run();

private:
    void load();
    void createWindowResources();
    bool frame();
    void runScript();
    // One script action at its frame; errors name the script line.
    void runAction(const ScriptAction& a);
    // The panels' copy of the picture, validated and applied part by part (structure, TF,
    // settings): a rejected part leaves the state as it was and shows why.
    void applyPanelEdits(PanelRequests& req);
    void pollShaders();
    void reloadShaders();
    void handleInput();
    void handleKey(int code, double h, double step);
    void applyEdits();
    void trace();  // within the frame budget
    void present();
    void recordCapture(VkCommandBuffer cmd, VkImage image, VkExtent2D extent);
    void saveCapture(VkExtent2D extent);
    void updateStatistics(double frameSeconds);
    // The one way the viewer changes the picture: the parts of `e` committed at once beside the
    // event loop (mPicture.commit: one majorant pass and at most one build, however many parts),
    // then taken into the state; on an error nothing changes and it is thrown.
    void commit(const picture::PictureEdit& e);
    // Validates `next` (back-end resolved for the device) and builds it; on an error nothing
    // changes (the renderer keeps the previous structures) and the error is thrown.
    void setStructure(const scene::StructureConfig& next) { commit({.structure = next}); }
    // The renderer takes mState.tf (majorants), the histogram follows its range.
    void setTransferFunction() { commit({.tf = mState.tf, .tfColors = mState.tfColors}); }
    // The data read again with `next.read` (another scale or log floor) beside the event loop, and
    // a renderer made for it with next's camera, settings, structure and TF (refitTf: an unedited
    // fitted preset fitted again, any other TF's shape moved onto the new field range:
    // tfOnNewScale). On an error nothing changes and it is thrown.
    void reloadData(const session::Session& next, bool refitTf);
    // The field's scale and log floor of `read`: on another scale the data is read again (true, the
    // TF refitted), else the floor is only recorded (false).
    bool setReadScale(const amr::ReadOptions& read);
    // What load() and reloadData() give makePicture: the shader library, notes on stderr.
    picture::Options pictureOptions() const;
    // A ready picture becomes the state: its renderer and session, the TF in the editor's form (the
    // undo history starting with it), the histogram over the TF's range.
    void adoptPicture(picture::Picture&& p);
    // The histogram under the TF editor, recomputed when the editor's value range differs from it.
    void updateHistogram();
    // Where the panel and the picture are this frame (framebuffer size, panel width, image size).
    void updateLayout();
    // Runs a long CPU/GPU rebuild on a worker thread while this (the main) thread keeps handling
    // window events, so closing (the window button, q or Esc) works during it: the window is
    // hidden at once and the viewer ends when the build returns. Other input during it is dropped.
    void whileResponsive(const std::function<void()>& work);
    void noteReset(const std::string& what);
    void screenshot(const fs::path& file);
    // The state as a session: the camera and TF as shown, the input path absolute (so the file and
    // the command line work from any directory). What save-session and copy-as-command write.
    session::Session currentSession() const;
    void saveSessionFile(const fs::path& file);
    void loadSessionFile(const fs::path& file);
    void copyCommand();
    void finishSample();
    // The still picture's preview completed (kFirstFrameSpp samples at mPreviewScale): its noise
    // measured, kept on the device for the display and on the host for screenshots.
    void keepPreview();
    // The estimate's noise measured where mHold asks for it; mShown updated.
    void updateShown();
    // Traces the current picture's preview to completion now (a screenshot of what the screen will
    // show right after an edit), unless it has one.
    void finishPreview();
    void writeStats() const;
    // The live state for programs that drive the window (--state-file, docs/viewer.md): after
    // every frame and when a rebuild starts beside the event loop.
    void writeState() const;
    // The camera path (viewer_camera_path.cpp): keyframes edited in mState.cameraPath; the preview
    // sets mState.settings.camera to the path's camera of a frame, a camera edit like an orbit.
    void runPathAction(const ScriptAction& a);      // keyframe-* and path-* script actions
    void applyPathRequests(const PathRequests& r);  // the camera path section's requests
    void handlePathKey(int code);                   // K adds a keyframe, P plays or stops
    // Each frame (after the script): while playing, the next path frame, one a viewer frame and at
    // most fps a second (the frame waits for its time); after the last frame the preview stops.
    void advancePathPreview();
    void showPathFrame(uint32_t k);  // the camera := cameraAt(k), recorded in mPathPreview.shown
    void playPath();                 // from frame 0, shown at once
    void stopPath();
    // The path frame whose camera the camera is now (none once the camera was moved, or no path).
    std::optional<uint32_t> shownPathFrame() const;

    // A time series (viewer_series.cpp): the player, the steps read ahead beside the event loop
    // (a worker thread reading the nearest steps within mOpt.seriesAheadBytes), and stepping:
    // another step's data under the same camera, TF, settings and structure.
    void startSeries();
    void stopSeries();
    // Shows step k: its volume read ahead, or read now beside the event loop, then built; the
    // camera, TF (its undo history too), settings and structure kept. Errors name the step.
    void showStep(size_t k);
    // Once a frame: the shown step's picture on screen, the next step when playing makes it due.
    void playSeries();
    // The steps to read ahead of the shown one handed to the worker; the others dropped.
    void scheduleAhead();
    // "step 2 of 8: out_2.cells, t = 0.15" (the time as amrvk info reads it).
    std::string stepLabel() const;
    std::shared_ptr<const scene::Volume> takeAhead(size_t k);
    struct ReadAhead;
    struct ReadAheadDelete {
        void operator()(ReadAhead* a) const;  // viewer_series.cpp, where ReadAhead is complete
    };
    std::unique_ptr<ReadAhead, ReadAheadDelete> mAhead;
    uint64_t mAheadStepBytes = 0;  // host bytes of a step (the shown one's cells, fields and bricks)
    std::optional<SeriesPlayer> mPlayer;
    struct StepTiming {
        size_t step;
        double seconds;  // from the request to a picture ready to trace (wall)
        bool wasAhead;   // its volume had been read ahead
    };
    std::vector<StepTiming> mStepTimings;  // --stats

    ViewerOptions mOpt;
    std::unique_ptr<Window> mWindow;
    std::unique_ptr<gpu::Context> mCtx;
    std::unique_ptr<Swapchain> mSwapchain;
    std::unique_ptr<ImGuiLayer> mImGui;
    std::unique_ptr<render::DisplayPass> mDisplayPass;
    gpu::Buffer mDisplay;  // the window's pixels (B, G, R, A), copied into the swapchain image
    int mDisplayWidth = 0, mDisplayHeight = 0;
    session::PixelRect mDisplayRect;  // where the display buffer's picture was drawn
    ViewerLayout mLayout;             // this frame's panel and picture rectangles

    std::shared_ptr<const scene::Volume> mVolume;
    // The picture: its renderer and its description, edited only through mPicture.commit (one
    // commit per edit, however many parts it changes).
    picture::Picture mPicture;

    // The picture: the one copy of every setting (full resolution), the camera and the TF; the
    // camera control and the TF editor edit it in place, the panels edit a copy that is validated.
    session::Session mState;
    session::OrbitCamera mOrbit;  // the data's box: framing and zoom limits
    TfHistory mTfHistory;
    FrameBudget mBudget;
    std::optional<Histogram> mHistogram;
    std::vector<ScriptAction> mScript;
    size_t mScriptAt = 0;
    std::optional<FileWatcher> mWatcher;
    Clock::time_point mLastShaderPoll = Clock::now();
    std::vector<scene::TfChannels> mColorMaps;

    PanelState mPanel;
    Statistics mStats;
    Timings mTimings;
    uint64_t mFrame = 0;
    bool mQuit = false;
    bool mInteracting = false;                       // a change or a drag this frame: preview
    bool mNeedPreview = true;                        // nothing on screen for the current picture yet: preview first
    bool mPreviewing = false;                        // this frame traces a preview (ray-marched, one sample)
    int mPreviewScale = 1;                           // the renderer's current size is full / scale
    std::map<std::string, uint64_t> mPreviewFrames;  // preview frames traced, by mode (--stats)
    bool mDisplayFresh = false;                      // the display buffer holds an image worth showing
    // Never a worse picture than the one it replaces (scene/preview_hold.h): the still picture's
    // preview stays on screen until the estimate is as clean. mPreviewAccum holds the preview's
    // accumulation (AccumPixelGpu, mPreviewImage's size) for the display, mPreviewImage its mean
    // (linear, at the preview's size) for screenshots.
    scene::PreviewHold mHold;
    scene::Shown mShown = scene::Shown::Nothing;  // what the last frame put on screen
    gpu::Buffer mPreviewAccum;
    Image mPreviewImage;
    struct EstimateShown {
        uint64_t frame;
        uint32_t spp;
        double noise, threshold;  // the estimate's last measured noise, and what it had to reach
        bool atLimit;             // shown because it reached the session's spp
    };
    std::optional<EstimateShown> mEstimateShown;     // when the last kept preview gave way (--stats)
    std::optional<Clock::time_point> mChangedAt;     // since the last change, until the first full sample
    double mTraceSeconds = 0;                        // wall seconds spent in trace() in all
    uint64_t mValidationBefore = 0;
    scene::RenderSettings mApplied;  // what the renderer was last given
    int mDragButton = -1;            // the mouse button that started the current drag, or -1
    int mCutFace = -1;               // the crop-box face whose handle is being dragged, or -1
    bool mDragPans = false;          // the drag began as shift+left: pan
    std::string mCapturePath;        // the next presented frame is saved there (UI included)
    struct Reset {
        uint64_t frame;
        std::string what;
        uint32_t samplesLeft;  // samples of the old picture still in the image right after (must be 0)
    };
    std::vector<Reset> mResets;
    gpu::Buffer mCaptureBuffer;
    double mLastX = 0, mLastY = 0;
    // Input events handleInput has taken so far, by kind, and the mouse buttons they leave held
    // (bit i: GLFW button i): what a driving program waits on (--state-file).
    struct InputSeen {
        uint64_t keys = 0, buttons = 0, cursor = 0, scroll = 0;
        unsigned held = 0;
    } mInputSeen;
    // The camera path's preview (viewer_camera_path.cpp).
    struct PathPreview {
        bool playing = false;
        std::optional<uint32_t> frame;  // the last path frame shown
        uint64_t shownOnFrame = 0;      // the viewer frame (mFrame) it was shown on
        Clock::time_point shownAt;      // and when: playing shows the next 1/fps later at the earliest
        // Every path frame shown and its camera, in order (--stats "pathFramesShown").
        std::vector<std::pair<uint32_t, scene::Camera>> shown;
    } mPathPreview;
    bool mBuilding = false;             // whileResponsive is running a rebuild beside the event loop
    std::unique_ptr<Font> mLegendFont;  // the PNG legend's font, opened at the first screenshot with the legend
    std::string mLegendFontFile;        // the legend.font it was opened for
};

}  // namespace amrvk::viewer
