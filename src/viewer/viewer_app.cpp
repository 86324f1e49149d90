#include "viewer/viewer_app.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <future>
#include <iterator>
#include <memory>
#include <numeric>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>

#include "amr/readers.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/image_io.h"
#include "core/progress.h"
#include "core/stats.h"
#include "core/strings.h"
#include "gpu/buffer.h"
#include "gpu/context.h"
#include "gpu/shader_compiler.h"
#include "gpu/shader_library.h"
#include "render/display_pass.h"
#include "picture/picture.h"
#include "render/renderer.h"
#include "session/cut_handles.h"
#include "session/data_change.h"
#include "session/file_watcher.h"
#include "session/frame_budget.h"
#include "session/legend_image.h"
#include "session/script.h"
#include "session/viewer_layout.h"
#include "viewer/imgui_layer.h"
#include "viewer/cut_overlay.h"
#include "viewer/legend_overlay.h"
#include "viewer/panels.h"
#include "viewer/swapchain.h"
#include "viewer/window.h"

namespace fs = std::filesystem;

namespace amrvk::viewer {

namespace {

using Clock = std::chrono::steady_clock;

// The window's pixels beside the picture (packed B, G, R, A): a dark grey, apart from black
// backgrounds, so the picture's edge shows.
constexpr uint32_t kLetterboxColor = 0xff262626u;

double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

nlohmann::ordered_json rectJson(const session::PixelRect& r) {
    return {{"x", r.x}, {"y", r.y}, {"width", r.width}, {"height", r.height}};
}

// JSON with one member a line, objects of objects opened the same way, every other value on its
// member's line: still JSON, and a shell script can read a member with grep (--state-file).
std::string memberPerLine(const nlohmann::ordered_json& j, const std::string& indent = "") {
    std::string text = "{\n";
    for (auto it = j.begin(); it != j.end(); ++it) {
        bool nested = it->is_object() && !it->empty();
        if (nested)
            for (const auto& m : *it) nested = nested && m.is_object();
        text += indent + "  " + nlohmann::ordered_json(it.key()).dump() + ": " +
                (nested ? memberPerLine(*it, indent + "  ") : it->dump()) + (std::next(it) == j.end() ? "\n" : ",\n");
    }
    return text + indent + "}";
}

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
    int run();

private:
    void load();
    void createWindowResources();
    bool frame();
    void runScript();
    // One script action at its frame; errors name the script line.
    void runAction(const session::ScriptAction& a);
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
    // session::tfOnNewScale). On an error nothing changes and it is thrown.
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
    void writeStats() const;
    // The live state for programs that drive the window (--state-file, docs/viewer.md): after
    // every frame and when a rebuild starts beside the event loop.
    void writeState() const;

    ViewerOptions mOpt;
    std::unique_ptr<Window> mWindow;
    std::unique_ptr<gpu::Context> mCtx;
    std::unique_ptr<Swapchain> mSwapchain;
    std::unique_ptr<ImGuiLayer> mImGui;
    std::unique_ptr<render::DisplayPass> mDisplayPass;
    gpu::Buffer mDisplay;  // the window's pixels (B, G, R, A), copied into the swapchain image
    int mDisplayWidth = 0, mDisplayHeight = 0;
    session::PixelRect mDisplayRect;  // where the display buffer's picture was drawn
    session::ViewerLayout mLayout;    // this frame's panel and picture rectangles

    std::shared_ptr<const scene::Volume> mVolume;
    // The picture: its renderer and its description, edited only through mPicture.commit (one
    // commit per edit, however many parts it changes).
    picture::Picture mPicture;

    // The picture: the one copy of every setting (full resolution), the camera and the TF; the
    // camera control and the TF editor edit it in place, the panels edit a copy that is validated.
    session::Session mState;
    session::OrbitCamera mOrbit;  // the data's box: framing and zoom limits
    session::TfHistory mTfHistory;
    session::FrameBudget mBudget;
    std::optional<session::Histogram> mHistogram;
    std::vector<session::ScriptAction> mScript;
    size_t mScriptAt = 0;
    std::optional<session::FileWatcher> mWatcher;
    Clock::time_point mLastShaderPoll = Clock::now();
    std::vector<scene::TfChannels> mColorMaps;

    PanelState mPanel;
    Statistics mStats;
    Timings mTimings;
    uint64_t mFrame = 0;
    bool mQuit = false;
    bool mInteracting = false;                    // a change or a drag this frame: preview
    bool mNeedPreview = true;                     // nothing on screen for the current picture yet: preview first
    bool mPreviewing = false;                     // this frame traces a preview (ray-marched, one sample)
    int mPreviewScale = 1;                        // the renderer's current size is full / scale
    std::map<std::string, uint64_t> mPreviewFrames;  // preview frames traced, by mode (--stats)
    bool mDisplayFresh = false;                   // the display buffer holds an image worth showing
    std::optional<Clock::time_point> mChangedAt;  // since the last change, until the first full sample
    double mTraceSeconds = 0;  // wall seconds spent in trace() in all
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
    bool mBuilding = false;             // whileResponsive is running a rebuild beside the event loop
    std::unique_ptr<Font> mLegendFont;  // the PNG legend's font, opened at the first screenshot with the legend
    std::string mLegendFontFile;        // the legend.font it was opened for
};

ViewerApp::ViewerApp(const ViewerOptions& o, std::shared_ptr<const scene::Volume> volume)
    : mOpt(o),
      mVolume(std::move(volume)),
      mState(o.start.session),
      mOrbit(mVolume->worldLo(), mVolume->worldHi()),
      mTfHistory(scene::TfChannels{}),  // load() starts it with the picture's TF
      mBudget(o.frameBudgetSeconds) {
    AMRVK_CHECK(o.frameBudgetSeconds > 0, "internal: the frame budget must be positive");
}

void ViewerApp::load() {
    // The same entry as amrvk render: the description fitted to the data, the back-end chosen for
    // the device, the structures built, TF and settings applied.
    picture::Picture p;
    whileResponsive([&] { p = picture::makePicture(*mCtx, mVolume, mOpt.start, pictureOptions()); });
    adoptPicture(std::move(p));
    noteReset("picture");
}

picture::Options ViewerApp::pictureOptions() const {
    return {.shaders = gpu::ShaderLibrary(mOpt.shaderDir),
            .note = [](const std::string& line) {
                std::fprintf(stderr, "amrvk: %s\n", oneLineMessage(line).c_str());
            }};
}

void ViewerApp::adoptPicture(picture::Picture&& p) {
    mPicture = std::move(p);
    mPicture.renderer->setSubMajorantsInBackground(true);  // a TF edit does not wait for them
    // The editor's form of the TF: the same function, with both channels spanning its range.
    const scene::TfChannels editable = session::TfEditor::editable(mPicture.described.tf);
    if (!(editable == mPicture.described.tf)) mPicture.commit({.tf = editable});
    mState = mPicture.session();
    mTfHistory = session::TfHistory(mState.tf);
    mStats.combination = mPicture.renderer->config().labelWithGrid();
    mPanel.gridText = mState.structure.grid;
    mHistogram.reset();  // the data may be new
    updateHistogram();
}

void ViewerApp::updateHistogram() {
    // The histogram depends on the value range only: colour and opacity drags do not recompute it.
    const session::TfEditor editor(mState.tf);
    if (!mHistogram || mHistogram->lo != editor.lo() || mHistogram->hi != editor.hi())
        mHistogram = session::fieldHistogram(mVolume->model, mVolume->field(), editor.lo(), editor.hi(), 128);
}

void ViewerApp::reloadData(const session::Session& next, bool refitTf) {
    session::PictureDescription d;
    d.session = next;
    scene::StructureConfig structure = next.structure;
    picture::resolveStructure(*mCtx, structure);  // an invalid combination fails before the read
    std::shared_ptr<const scene::Volume> volume;
    picture::Picture p;
    Timer t;
    whileResponsive([&] {
        volume = session::loadVolume(d.session);
        if (refitTf) d.session.tf = session::tfOnNewScale(d.session.tf, *mVolume, *volume);
        p = picture::makePicture(*mCtx, volume, d, pictureOptions());
    });
    // Frames in flight may still read the old accumulation: wait before it goes.
    vkQueueWaitIdle(mCtx->queue());
    mVolume = std::move(volume);
    mOrbit = session::OrbitCamera(mVolume->worldLo(), mVolume->worldHi());
    // The old TFs are in the other scale's units: the undo history starts again here.
    adoptPicture(std::move(p));
    mApplied = mState.settings;  // the new renderer has them; the reset is noted below
    mStats.structureSeconds = t.seconds();
    mPanel.structureError.clear();
    mDisplayFresh = false;
    noteReset("scale");
    std::fprintf(stderr, "amrvk view: %s scale, field range [%g, %g]\n", amr::fieldScaleName(mState.read.scale),
                 double(mVolume->valueLo()), double(mVolume->valueHi()));
}

bool ViewerApp::setReadScale(const amr::ReadOptions& read) {
    session::Session next = mState;
    next.read.scale = read.scale;
    next.read.logFloor = read.logFloor;
    if (session::dataChange(mState, next).kind == session::DataChange::Rescale) {
        reloadData(next, true);
        return true;
    }
    mState.read = next.read;  // a floor on the linear scale: recorded, no value changes
    return false;
}

void ViewerApp::updateLayout() {
    int w = 0, h = 0;
    if (mWindow) mWindow->framebufferSize(w, h);
    mLayout = session::viewerLayout(w, h, mPanel.panelWidth, mState.settings.width, mState.settings.height);
}

void ViewerApp::createWindowResources() {
    int w = 0, h = 0;
    mWindow->framebufferSize(w, h);
    mSwapchain = std::make_unique<Swapchain>(*mCtx, std::max(w, 1), std::max(h, 1));
    mImGui = std::make_unique<ImGuiLayer>(*mCtx, mWindow->handle(), mSwapchain->renderPass(),
                                          mSwapchain->minImageCount(), mSwapchain->imageCount());
}

void ViewerApp::commit(const picture::PictureEdit& e) {
    std::string stageName;
    if (e.structure) {
        scene::StructureConfig next = *e.structure;
        picture::resolveStructure(*mCtx, next);  // validated before anything changes
        stageName = "structures for " + next.label();
    }
    Timer t;
    whileResponsive([&] {
        std::optional<ProgressStage> stage;
        if (e.structure) stage.emplace(stageName);
        mPicture.commit(e);
    });
    if (e.tf) mState.tf = *e.tf;
    if (e.tfColors) mState.tfColors = *e.tfColors;
    if (e.settings) mState.settings = *e.settings;
    if (e.structure) {
        mStats.structureSeconds = t.seconds();
        mStats.combination = mPicture.renderer->config().labelWithGrid();
        mState.structure = *e.structure;
        mPanel.gridText = e.structure->grid;
        mPanel.structureError.clear();
        noteReset("structure");
    }
    if (e.tf || e.tfColors) {
        if (!e.structure) mStats.tfEditSeconds = t.seconds();
        updateHistogram();
        noteReset("transfer function");
    }
}

void ViewerApp::noteReset(const std::string& what) {
    // The renderer must have dropped every sample of the old picture.
    mResets.push_back(
        {mFrame, what, mPicture.renderer ? mPicture.renderer->accumulatedSpp() + mPicture.renderer->rowsDone() : 0});
    mNeedPreview = true;
    mChangedAt = Clock::now();
}

void ViewerApp::whileResponsive(const std::function<void()>& work) {
    if (!mWindow) return work();
    mBuilding = true;
    if (!mOpt.stateJson.empty()) writeState();  // before the job: it reads the renderer
    // The main thread touches neither the scene, the renderer nor the Vulkan queue until the job ends.
    std::future<void> job = std::async(std::launch::async, work);
    while (job.wait_for(std::chrono::milliseconds(0)) != std::future_status::ready) {
        mWindow->waitEvents(0.05);
        for (const InputEvent& e : mWindow->takeEvents())
            if (e.kind == InputEvent::Kind::Key && e.action == GLFW_PRESS &&
                (e.code == GLFW_KEY_Q || e.code == GLFW_KEY_ESCAPE))
                mWindow->requestClose();
        if (mWindow->shouldClose() && !mQuit) {
            mWindow->hide();
            mQuit = true;
            std::fprintf(stderr, "amrvk view: closing when the build in progress returns\n");
        }
    }
    mBuilding = false;
    job.get();  // rethrows the build's error
}

int ViewerApp::run() {
    gpu::ContextOptions co = mOpt.context;
    co.requireRayQuery = mState.structure.backend == scene::Backend::Rq;
    if (!mOpt.headless) {
        // Default: the image pixel for pixel beside the panel.
        int w = mOpt.windowWidth, h = mOpt.windowHeight;
        if (w <= 0 || h <= 0) session::defaultWindowSize(mState.settings.width, mState.settings.height, w, h);
        mWindow = std::make_unique<Window>(w, h, "amrvk view - " + fs::path(mState.input).filename().string());
        co.instanceExtensions = Window::requiredInstanceExtensions();
        co.createSurface = [this](VkInstance instance) { return mWindow->createSurface(instance); };
    }
    mCtx = std::make_unique<gpu::Context>(co);
    mValidationBefore = mCtx->validationErrors();
    mStats.device = mCtx->deviceReport().name;
    if (!mOpt.shaderDir.empty()) mWatcher.emplace(std::vector<fs::path>{gpu::shaderSourceRoot(mOpt.shaderDir)});
    load();
    mColorMaps.push_back(mState.tf);  // the starting colour map first
    for (const std::string& name : scene::presetNames()) mColorMaps.push_back(scene::builtInChannels(name));
    if (!mOpt.script.empty()) {
        mScript = session::loadScript(mOpt.script);
        session::checkScript(mScript, {mOpt.shaderDir, mState.structure});  // every line before frame 0
    }
    if (mWindow) {
        createWindowResources();
        mDisplayPass = std::make_unique<render::DisplayPass>(*mCtx);
    }
    mChangedAt = Clock::now();
    while (!mQuit && (mOpt.frames == 0 || mFrame < mOpt.frames)) {
        const Clock::time_point start = Clock::now();
        const double traceBefore = mTraceSeconds;
        if (!frame()) break;
        const double seconds = secondsSince(start);
        // The rest of the frame (UI, display, present) comes out of the path tracer's share.
        mBudget.recordOtherWork(seconds - (mTraceSeconds - traceBefore));
        (mInteracting ? mTimings.interactiveFrames : mTimings.idleFrames).push_back(seconds);
        updateStatistics(seconds);
        ++mFrame;
        if (!mOpt.stateJson.empty()) writeState();
    }
    if (!mOpt.screenshot.empty()) screenshot(mOpt.screenshot);
    if (!mOpt.saveSession.empty()) saveSessionFile(mOpt.saveSession);
    if (!mOpt.statsJson.empty()) writeStats();
    mImGui.reset();
    mSwapchain.reset();
    const uint64_t errors = mCtx->validationErrors() - mValidationBefore;
    if (mOpt.context.validation && errors > 0) {
        std::fprintf(stderr, "amrvk view: error: Vulkan validation reported %llu error(s); last: %s\n",
                     (unsigned long long)errors, mCtx->lastValidationMessage().c_str());
        return 1;
    }
    return 0;
}

bool ViewerApp::frame() {
    if (mWindow) {
        mWindow->pollEvents();
        if (mWindow->shouldClose()) return false;
        int w = 0, h = 0;
        mWindow->framebufferSize(w, h);
        if (w == 0 || h == 0) {  // minimised: nothing to draw, keep the accumulation
            mWindow->waitEvents(0.1);
            return true;
        }
        const VkExtent2D e = mSwapchain->extent();
        if (uint32_t(w) != e.width || uint32_t(h) != e.height) {
            mSwapchain->recreate(w, h);
            mImGui->setMinImageCount(mSwapchain->minImageCount());
        }
    }
    mInteracting = false;
    runScript();
    if (mQuit) return false;  // a quit action, or closed during a rebuild an action started
    pollShaders();
    if (mWindow) {
        updateLayout();
        mImGui->beginFrame();
        mPanel.panelRect = mLayout.panel;
        mPanel.stats = &mStats;
        mPanel.edit = mState;
        mPanel.histogram = mHistogram ? &*mHistogram : nullptr;
        mPanel.worldLo = mVolume->worldMin();
        mPanel.worldHi = mVolume->worldMax();
        mPanel.canUndo = mTfHistory.canUndo();
        mPanel.canRedo = mTfHistory.canRedo();
        mPanel.colorMapNames.clear();
        for (const scene::TfChannels& c : mColorMaps) mPanel.colorMapNames.push_back(c.name);
        PanelRequests req;
        drawPanels(mPanel, req);
        const UiRect pr = toUi(mLayout.picture);
        drawLegendOverlay(mState, mVolume->field().units, ImVec2(pr.x, pr.y),
                          ImVec2(pr.x + pr.width, pr.y + pr.height));
        drawCutOverlay(mState, ImVec2(pr.x, pr.y), ImVec2(pr.x + pr.width, pr.y + pr.height), mCutFace);
        try {
            applyPanelEdits(req);
        } catch (const Error& e) {
            mPanel.message = std::string("error: ") + e.what();
        }
        handleInput();
    }
    applyEdits();
    const Clock::time_point traceStart = Clock::now();
    trace();
    mTraceSeconds += secondsSince(traceStart);
    if (mWindow) present();
    return !mQuit;
}

void ViewerApp::applyPanelEdits(PanelRequests& req) {
    session::Session& e = mPanel.edit;
    // Requests that edit the copy's TF or camera.
    if (req.undo) e.tf = mTfHistory.undo();
    if (req.redo) e.tf = mTfHistory.redo();
    if (req.resetRange) {
        e.tf = session::refitTfRange(e.tf, mVolume->valueLo(), mVolume->valueHi());
        req.tfCommitted = true;
    }
    if (req.applyColorMap && mPanel.colorMapChoice >= 0 && size_t(mPanel.colorMapChoice) < mColorMaps.size()) {
        session::TfEditor(e.tf).setColorMap(mColorMaps[size_t(mPanel.colorMapChoice)]);
        req.tfCommitted = true;
    }
    if (req.loadTfFile) {
        const scene::ParaViewPresets p = scene::loadParaViewPresets(mPanel.tfPath);
        AMRVK_CHECK(!p.presets.empty(), mPanel.tfPath, ": no usable preset");
        for (const scene::TfChannels& c : p.presets) mColorMaps.push_back(c);
        session::TfEditor(e.tf).setPreset(p.presets.front());
        mPanel.message = "loaded " + std::to_string(p.presets.size()) + " preset(s) from " + mPanel.tfPath +
                         (p.skipped.empty() ? "" : " (" + std::to_string(p.skipped.size()) + " skipped)");
        req.tfCommitted = true;
    }
    if (req.saveTfFile) {
        writeFileAtomic(mPanel.tfPath, session::TfEditor(e.tf).toParaViewJson(fs::path(mPanel.tfPath).stem().string()));
        mPanel.message = "saved " + mPanel.tfPath;
    }
    if (req.resetView) mOrbit.reset(e.settings.camera);
    if (req.gridEntered) e.structure.grid = mPanel.gridText;
    if (mPanel.imageFollowsWindow && !mLayout.area.empty())
        std::tie(e.settings.width, e.settings.height) = std::pair(mLayout.area.width, mLayout.area.height);

    // The field's scale (log scale, log floor): read again, everything else of the state kept.
    if (!(e.read.scale == mState.read.scale && e.read.logFloor == mState.read.logFloor)) {
        AMRVK_CHECK(std::isfinite(e.read.logFloor) && e.read.logFloor >= 0, "log floor ", e.read.logFloor,
                    " must be >= 0 (0: the field's smallest positive value)");
        if (setReadScale(e.read)) {
            mInteracting = true;
            return;  // this frame's other edits were made on the old scale's state
        }
    }

    // This frame's structure and TF edits in one commit. A structure that is refused or fails to
    // build shows its reason and changes nothing; the TF edit is then committed alone.
    picture::PictureEdit pe;
    if (!(e.structure == mState.structure)) pe.structure = e.structure;
    if (!(e.tf == mState.tf) || e.tfColors != mState.tfColors) {
        pe.tf = e.tf;
        pe.tfColors = e.tfColors;
    }
    if (pe.structure || pe.tf) {
        try {
            commit(pe);
        } catch (const Error& err) {
            if (!pe.structure) throw;
            mPanel.structureError = err.what();
            mPanel.gridText = mState.structure.grid;
            mPanel.message = std::string("structure not applied: ") + err.what();
            pe.structure.reset();
            if (pe.tf) commit(pe);
        }
        mInteracting = true;
    }
    if (req.tfCommitted) mTfHistory.push(mState.tf);
    if (!(e.settings == mState.settings)) {
        scene::validateSettings(e.settings);  // throws: the state keeps its settings
        mState.settings = e.settings;
    }
    mState.spp = e.spp;
    mState.legend = e.legend;  // drawn over the picture and into PNG screenshots; the picture is unchanged
    if (req.screenshot) screenshot(mPanel.screenshotPath);
    if (req.saveSession) saveSessionFile(mPanel.sessionPath);
    if (req.loadSession) loadSessionFile(mPanel.sessionPath);
    if (req.copyCommand) copyCommand();
}

// A key the panels did not take: arrows orbit by `step` of a picture `h` pixels high, +/- and
// page up/down zoom, r resets the view, q and Esc quit.
void ViewerApp::handleKey(int code, double h, double step) {
    switch (code) {
        case GLFW_KEY_LEFT:
        case GLFW_KEY_RIGHT:
            mOrbit.orbit(mState.settings.camera, code == GLFW_KEY_LEFT ? -step : step, 0, h);
            break;
        case GLFW_KEY_UP:
        case GLFW_KEY_DOWN:
            mOrbit.orbit(mState.settings.camera, 0, code == GLFW_KEY_UP ? step : -step, h);
            break;
        case GLFW_KEY_EQUAL:
        case GLFW_KEY_KP_ADD:
        case GLFW_KEY_PAGE_UP:
            mOrbit.zoom(mState.settings.camera, 1);
            break;
        case GLFW_KEY_MINUS:
        case GLFW_KEY_KP_SUBTRACT:
        case GLFW_KEY_PAGE_DOWN:
            mOrbit.zoom(mState.settings.camera, -1);
            break;
        case GLFW_KEY_R:
            mOrbit.reset(mState.settings.camera);
            break;
        case GLFW_KEY_Q:
        case GLFW_KEY_ESCAPE:
            mQuit = true;
            break;
        default:
            break;
    }
}

void ViewerApp::handleInput() {
    // Drags are measured against the picture as shown (its height in pixels): a drag across the
    // whole picture turns as far whatever the window size.
    const session::PixelRect& picture = mLayout.picture;
    const double h = double(std::max(picture.height, 1)), step = h / 18.0;  // arrow keys: 10 degrees
    // Cursor positions are in window coordinates, the layout in framebuffer pixels (HiDPI).
    int windowW = 0, windowH = 0;
    glfwGetWindowSize(mWindow->handle(), &windowW, &windowH);
    const double toPixelsX = windowW > 0 ? double(mLayout.window.width) / windowW : 1.0;
    const double toPixelsY = windowH > 0 ? double(mLayout.window.height) / windowH : 1.0;
    auto overPicture = [&](double x, double y) { return picture.contains(x * toPixelsX, y * toPixelsY); };
    // ImGui decides per frame whether the pointer or keyboard is its own; the camera takes the mouse
    // only over the picture, and a drag that starts there stays a camera drag when it crosses a panel.
    const bool uiMouse = mImGui->wantsMouse(), uiKeys = mImGui->wantsKeyboard();
    // A cursor position (window coordinates) in the pixels of the image the picture shows.
    const scene::RenderSettings& rs = mState.settings;
    const double toImageX = double(rs.width) / std::max(picture.width, 1), toImageY = double(rs.height) / std::max(picture.height, 1);
    auto inImage = [&](double x, double y) {
        return glm::dvec2((x * toPixelsX - picture.x) * toImageX, (y * toPixelsY - picture.y) * toImageY);
    };
    for (const InputEvent& e : mWindow->takeEvents()) {
        switch (e.kind) {
            case InputEvent::Kind::Button:
                ++mInputSeen.buttons;
                if (e.code >= 0 && e.code < 32) {
                    if (e.action == GLFW_PRESS) mInputSeen.held |= 1u << e.code;
                    if (e.action == GLFW_RELEASE) mInputSeen.held &= ~(1u << e.code);
                }
                // A left press on a crop-box handle drags that face (docs/cut-aways.md), not the camera.
                if (e.action == GLFW_PRESS && e.code == GLFW_MOUSE_BUTTON_LEFT && mDragButton < 0 && !uiMouse &&
                    overPicture(e.x, e.y) && rs.cut.crop) {
                    const double radius = kCutHandleRadius * toImageX;
                    mCutFace = session::CutHandles::pick(rs.camera, rs.width, rs.height, *rs.cut.crop, inImage(e.x, e.y), radius);
                    if (mCutFace >= 0) {
                        mDragButton = e.code;
                        mLastX = e.x;
                        mLastY = e.y;
                        break;
                    }
                }
                if (e.action == GLFW_PRESS && mDragButton < 0 && !uiMouse && overPicture(e.x, e.y)) {
                    mDragButton = e.code;
                    mDragPans = e.code == GLFW_MOUSE_BUTTON_MIDDLE || (e.mods & GLFW_MOD_SHIFT);
                } else if (e.action == GLFW_RELEASE && e.code == mDragButton) {
                    mDragButton = -1;
                    mCutFace = -1;
                }
                break;
            case InputEvent::Kind::Cursor:
                ++mInputSeen.cursor;
                if (mDragButton >= 0 && mCutFace >= 0 && mState.settings.cut.crop) {
                    // The face follows the pointer along its normal, inside the data, never past the
                    // opposite face (a thousandth of the box's diagonal apart at least).
                    const glm::dvec2 delta = inImage(e.x, e.y) - inImage(mLastX, mLastY);
                    const glm::dvec3 lo = mVolume->worldMin(), hi = mVolume->worldMax();
                    scene::CropBox& box = *mState.settings.cut.crop;
                    box = session::CutHandles::drag(rs.camera, rs.width, rs.height, box, mCutFace, delta,
                                                    glm::min(lo, box.lo), glm::max(hi, box.hi), 1e-3 * glm::length(hi - lo));
                    mInteracting = true;
                } else if (mDragButton >= 0) {
                    const double dx = e.x - mLastX, dy = e.y - mLastY;
                    scene::Camera& cam = mState.settings.camera;
                    if (mDragPans)
                        mOrbit.pan(cam, dx, dy, h);
                    else if (mDragButton == GLFW_MOUSE_BUTTON_RIGHT)
                        mOrbit.zoom(cam, -dy / 20.0);
                    else
                        mOrbit.orbit(cam, dx, dy, h);
                    mInteracting = true;
                }
                mLastX = e.x;
                mLastY = e.y;
                break;
            case InputEvent::Kind::Scroll:
                ++mInputSeen.scroll;
                if (!uiMouse && e.y != 0 && overPicture(mLastX, mLastY)) mOrbit.zoom(mState.settings.camera, e.y);
                break;
            case InputEvent::Kind::Key:
                ++mInputSeen.keys;
                if (uiKeys || e.action == GLFW_RELEASE) break;
                handleKey(e.code, h, step);
                break;
        }
    }
}

void ViewerApp::runScript() {
    while (!mQuit && mScriptAt < mScript.size() && mScript[mScriptAt].frame <= mFrame) {
        const session::ScriptAction& a = mScript[mScriptAt++];
        try {
            runAction(a);
        } catch (const gpu::ShaderCompileError&) {
            throw;  // names its file and line
        } catch (const Error& e) {
            throw Error(a.where + ": " + a.name + ": " + e.what());
        }
        std::fprintf(stderr, "amrvk view: frame %llu: %s\n", (unsigned long long)mFrame,
                     oneLineMessage(a.name).c_str());
    }
}

void ViewerApp::runAction(const session::ScriptAction& a) {
    const std::string& n = a.name;
    scene::Camera& camera = mState.settings.camera;
    const double height = double(mState.settings.height);
    scene::StructureConfig structure = mState.structure;
    if (n == "orbit" || n == "pan" || n == "zoom") {
        scene::Camera moved = camera;
        if (n == "orbit") mOrbit.orbit(moved, a.number(0), a.number(1), height);
        else if (n == "pan") mOrbit.pan(moved, a.number(0), a.number(1), height);
        else mOrbit.zoom(moved, a.number(0));
        // A move the camera cannot take fails here, on its script line, not at the next frame as
        // a --camera error (pan 1e300 1e300: the eye and target round to one point, or overflow).
        const glm::dvec3 forward = moved.target - moved.eye;
        const auto finite = [](glm::dvec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
        AMRVK_CHECK(finite(moved.eye) && finite(moved.target),
                    "the camera leaves the range of finite numbers");
        AMRVK_CHECK(glm::length(forward) > 0, "eye and target coincide");
        camera = moved;
    } else if (n == "tf-preset" || n == "tf-range") {
        session::TfEditor editor(mState.tf);
        if (n == "tf-preset") editor.setPreset(scene::builtInChannels(a.args[0]));
        else editor.setRange(float(a.number(0)), float(a.number(1)));
        mTfHistory.push(mState.tf);
        setTransferFunction();
    } else if (n == "density") {
        scene::RenderSettings s = mState.settings;
        s.densityScale = a.number(0);
        scene::validateSettings(s);
        mState.settings = s;
    } else if (n == "crop" || n == "clip" || n == "cut-off") {
        scene::RenderSettings s = mState.settings;
        if (n == "cut-off") {
            s.cut = {};
        } else {
            const glm::dvec3 u(a.number(0), a.number(1), a.number(2)), v(a.number(3), a.number(4), a.number(5));
            if (n == "crop") s.cut.crop = scene::CropBox{u, v};
            else s.cut.clips.push_back({u, v});
        }
        scene::validateSettings(s);
        mState.settings = s;
    } else if (n == "mode") {
        mState.settings.mode = scene::parseMode(a.args[0]);
    } else if (n == "scale" || n == "log-floor") {
        amr::ReadOptions read = mState.read;
        if (n == "scale") read.scale = amr::parseFieldScale(a.args[0]);
        else read.logFloor = a.number(0);
        setReadScale(read);
    } else if (n == "traversal" || n == "sampler" || n == "backend" || n == "grid") {
        if (n == "traversal") structure.traversal = scene::parseTraversal(a.args[0]);
        if (n == "sampler") structure.sampler = scene::parseSampler(a.args[0]);
        if (n == "backend") structure.backend = scene::parseBackend(a.args[0]);
        if (n == "grid") structure.grid = a.args[0];
        if (!(structure == mState.structure)) setStructure(structure);
    } else if (n == "edit-shader") {
        const fs::path file = session::confinedShaderPath(mOpt.shaderDir, a.args[0]);
        std::string text = readTextFile(file);
        const size_t at = text.find(a.args[1]);
        AMRVK_CHECK(at != std::string::npos, "'", a.args[1], "' not found in ", file.string());
        text.replace(at, a.args[1].size(), a.args[2]);
        writeFileAtomic(file, text);
    } else if (n == "reload") {
        reloadShaders();
    } else if (n == "screenshot") {
        screenshot(a.args[0]);
    } else if (n == "save-session") {
        saveSessionFile(a.args[0]);
    } else if (n == "load-session") {
        loadSessionFile(a.args[0]);
    } else if (n == "legend") {
        mState.legend.show = a.args[0] == "on";
    } else if (n == "tf-colors") {
        mState.tfColors = scene::parseTfColors(a.args[0], "tf-colors");
        setTransferFunction();
    } else if (n == "capture-window") {
        if (mWindow) mCapturePath = a.args[0];
    } else if (n == "quit") {
        mQuit = true;
    } else {
        AMRVK_CHECK(false, "the viewer has no action '", n, "'");
    }
}

void ViewerApp::pollShaders() {
    if (!mWatcher || secondsSince(mLastShaderPoll) < 0.25) return;
    mLastShaderPoll = Clock::now();
    if (!mWatcher->poll().empty()) reloadShaders();
}

void ViewerApp::reloadShaders() {
    try {
        mPicture.renderer->reloadShaders();
        noteReset("shaders");
        mPanel.shaderError.clear();
        mPanel.message = "shaders reloaded";
        std::fprintf(stderr, "amrvk view: shaders reloaded from %s\n", mOpt.shaderDir.string().c_str());
    } catch (const gpu::ShaderCompileError& e) {
        mPanel.shaderError = e.what();  // the previous pipeline keeps running
        std::fprintf(stderr, "amrvk view: shader error (previous pipeline kept): %s\n", e.what());
    }
    mChangedAt = Clock::now();
}

void ViewerApp::applyEdits() {
    // The picture the state describes, at full resolution or as a preview while interacting.
    const scene::RenderSettings& full = mState.settings;
    const scene::ChangeSet changes = scene::settingsChanges(mApplied, full);
    if (!changes.empty() && mFrame > 0) mInteracting = true;
    scene::RenderSettings s = full;
    if (mInteracting) mNeedPreview = true;
    mPreviewing = mNeedPreview;
    mPreviewScale = mNeedPreview ? mBudget.previewScale(full.width, full.height) : 1;
    s.width = std::max(1, full.width / mPreviewScale);
    s.height = std::max(1, full.height / mPreviewScale);
    // The preview (the first frame of a picture, and every frame while interacting) is the same
    // TF ray-marched: clean in one sample where path tracing a haze is grainy for many; the path
    // tracer then refines the still picture at full resolution.
    if (mPreviewing) s.mode = scene::Mode::Dvr;
    mPicture.commit({.settings = s});
    if (!changes.empty() && mFrame > 0) noteReset(scene::describe(changes));
    if (mInteracting) mChangedAt = Clock::now();
    mApplied = full;
}

void ViewerApp::trace() {
    const scene::RenderSettings& s = mPicture.renderer->settings();
    const uint32_t limit = mState.spp;
    const bool done = !mPreviewing && limit > 0 && mPicture.renderer->accumulatedSpp() >= limit;
    if (done) {
        if (mWindow) mWindow->waitEvents(0.03);  // converged: wait for the user instead of spinning
        return;
    }
    const uint64_t pixels = uint64_t(s.width) * uint64_t(s.height);
    const double gpuBefore = mPicture.renderer->stats().gpuSeconds;
    if (mPreviewing) {
        ++mPreviewFrames[scene::modeName(s.mode)];
        mPicture.renderer->accumulate(1);
        mBudget.record(mPicture.renderer->stats().gpuSeconds - gpuBefore, pixels);
        mNeedPreview = mInteracting;  // shown once: refine at full resolution when the user stops
    } else {
        const uint32_t rows = mBudget.rowsPerFrame(s.width, s.height, mPicture.renderer->rowsDone());
        if (rows >= uint32_t(s.height) && mPicture.renderer->rowsDone() == 0) {
            // Fast device: whole samples, as many as fit.
            const double perSample = std::max(mBudget.secondsPerPixelSample() * double(pixels), 1e-9);
            uint32_t n = uint32_t(std::clamp(mBudget.budgetSeconds() / perSample, 1.0, 64.0));
            if (limit > 0) n = std::min(n, limit - mPicture.renderer->accumulatedSpp());
            mPicture.renderer->accumulate(n);
            mBudget.record(mPicture.renderer->stats().gpuSeconds - gpuBefore, pixels * n);
        } else {
            const uint32_t before = mPicture.renderer->rowsDone();
            const double gpu = mPicture.renderer->accumulateRows(rows);
            mBudget.recordRows(gpu, before, std::min(rows, uint32_t(s.height) - before), s.width, s.height);
        }
        if (mChangedAt && mPicture.renderer->accumulatedSpp() >= 1) {
            mTimings.toFirstFullSample.push_back(secondsSince(*mChangedAt));
            mChangedAt.reset();
        }
    }
    mDisplayFresh = mPreviewing || mPicture.renderer->accumulatedSpp() >= 1;
}

void ViewerApp::present() {
    const VkExtent2D e = mSwapchain->extent();
    const session::PixelRect& picture = mLayout.picture;
    const bool resized = int(e.width) != mDisplayWidth || int(e.height) != mDisplayHeight;
    if (resized || !(picture == mDisplayRect)) {
        if (resized) {  // a new size needs a new buffer; a moved picture (a panel drag) only a clear
            mDisplay = gpu::Buffer();
            mDisplay = gpu::Buffer(*mCtx, uint64_t(e.width) * e.height * 4, gpu::MemoryKind::Device, "display");
            mDisplayWidth = int(e.width);
            mDisplayHeight = int(e.height);
        }
        mDisplay.fillZero();
        mDisplayRect = picture;
        mDisplayFresh = mPreviewing || mPicture.renderer->accumulatedSpp() >= 1;
    }
    // The swapchain can lag the layout by a frame while the window is resized: draw only a
    // rectangle that lies in it.
    const bool drawable = !picture.empty() && picture.right() <= mDisplayWidth && picture.bottom() <= mDisplayHeight;
    const scene::RenderSettings& s = mPicture.renderer->settings();
    const bool ok = mSwapchain->frame([&](VkCommandBuffer cmd, VkImage image, VkFramebuffer framebuffer) {
        // Until the first full-resolution sample is complete the last picture stays on screen.
        if (mDisplayFresh && drawable)
            mDisplayPass->record(
                cmd, mPicture.renderer->accumulationAddress(), s.width, s.height, mDisplay,
                {mDisplayWidth, mDisplayHeight, picture.x, picture.y, picture.width, picture.height, kLetterboxColor});
        // display pass (compute) -> copy into the swapchain image -> the UI's render pass.
        const gpu::ImageUse copyDst{VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                    VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL};
        gpu::computeBarrier(cmd);
        gpu::imageBarrier(cmd, image, {VK_PIPELINE_STAGE_2_NONE, 0, VK_IMAGE_LAYOUT_UNDEFINED}, copyDst);
        const VkBufferImageCopy region = gpu::wholeImageCopy(e);
        vkCmdCopyBufferToImage(cmd, mDisplay.handle(), image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        gpu::imageBarrier(cmd, image, copyDst,
                          {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                           VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                           VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL});
        VkRenderPassBeginInfo rbi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
        rbi.renderPass = mSwapchain->renderPass();
        rbi.framebuffer = framebuffer;
        rbi.renderArea = {{0, 0}, e};
        vkCmdBeginRenderPass(cmd, &rbi, VK_SUBPASS_CONTENTS_INLINE);
        mImGui->render(cmd);
        vkCmdEndRenderPass(cmd);
        if (!mCapturePath.empty()) recordCapture(cmd, image, e);
    });
    if (ok && !mCapturePath.empty()) saveCapture(e);
    if (!ok) {
        int w = 0, h = 0;
        mWindow->framebufferSize(w, h);
        if (w > 0 && h > 0) {
            mSwapchain->recreate(w, h);
            mImGui->setMinImageCount(mSwapchain->minImageCount());
        }
    }
}

// The presented image (UI included) into a host buffer: present layout -> copy -> present layout.
void ViewerApp::recordCapture(VkCommandBuffer cmd, VkImage image, VkExtent2D e) {
    const uint64_t bytes = uint64_t(e.width) * e.height * 4;
    if (!mCaptureBuffer.valid() || mCaptureBuffer.size() < bytes)
        mCaptureBuffer = gpu::Buffer(*mCtx, bytes, gpu::MemoryKind::HostRead, "windowCapture");
    const gpu::ImageUse present{VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                                VK_IMAGE_LAYOUT_PRESENT_SRC_KHR};
    const gpu::ImageUse copySrc{VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                                VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL};
    gpu::imageBarrier(cmd, image, present, copySrc);
    const VkBufferImageCopy region = gpu::wholeImageCopy(e);
    vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, mCaptureBuffer.handle(), 1, &region);
    gpu::imageBarrier(cmd, image, copySrc, {VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR});
}

void ViewerApp::saveCapture(VkExtent2D e) {
    vkQueueWaitIdle(mCtx->queue());
    std::vector<uint8_t> bgra(size_t(e.width) * e.height * 4);
    mCaptureBuffer.download(bgra.data(), bgra.size());
    Image8 png{int(e.width), int(e.height), std::vector<uint8_t>(bgra.size())};
    for (size_t i = 0; i < bgra.size(); i += 4) {
        png.rgba[i] = bgra[i + 2];
        png.rgba[i + 1] = bgra[i + 1];
        png.rgba[i + 2] = bgra[i];
        png.rgba[i + 3] = 255;
    }
    writePng8(mCapturePath, png);
    std::fprintf(stderr, "amrvk view: captured the window to %s\n", mCapturePath.c_str());
    mCapturePath.clear();
}

void ViewerApp::updateStatistics(double frameSeconds) {
    Statistics& st = mStats;
    st.frameMilliseconds =
        st.frameMilliseconds > 0 ? 0.9 * st.frameMilliseconds + 0.1 * frameSeconds * 1e3 : frameSeconds * 1e3;
    st.framesPerSecond = st.frameMilliseconds > 0 ? 1e3 / st.frameMilliseconds : 0;
    const scene::RenderStats& stats = mPicture.renderer->stats();
    const double paths = double(stats.paths);
    const auto& c = stats.counters;
    st.mPathsPerSecond = stats.gpuSeconds > 0 ? paths / stats.gpuSeconds * 1e-6 : 0;
    st.lookupsPerPath = paths > 0 ? double(c[shared::kCounterDensityLookups]) / paths : 0;
    const double real = double(c[shared::kCounterRealCollisions]);
    st.nullPerReal = real > 0 ? double(c[shared::kCounterNullCollisions]) / real : 0;
    st.violations = c[shared::kCounterMajorantViolations];
    st.trackingCapHits = c[shared::kCounterTrackingCapHits];
    st.nanSamples = c[shared::kCounterNanSamples];
    st.spp = mPicture.renderer->accumulatedSpp();
    st.sppLimit = mState.spp;
    st.rowsDone = mPicture.renderer->rowsDone();
    st.height = uint32_t(mPicture.renderer->settings().height);
    st.previewScale = mPreviewScale;
    st.deviceBytes = mCtx->memory().currentBytes();
}

void ViewerApp::finishSample() {
    // The full-resolution picture with at least one complete sample (no half-traced rows).
    const scene::RenderSettings& s = mState.settings;
    mPicture.commit({.settings = s});
    mPreviewScale = 1;
    mPreviewing = false;
    if (mPicture.renderer->accumulatedSpp() == 0 || mPicture.renderer->rowsDone() > 0)
        mPicture.renderer->accumulateRows(uint32_t(s.height) - mPicture.renderer->rowsDone());
}

void ViewerApp::screenshot(const fs::path& file) {
    finishSample();
    if (mState.legend.show && toLower(file.extension().string()) == ".png") {
        if (!mLegendFont || mLegendFontFile != mState.legend.font) {
            mLegendFont = session::openLegendFont(mState.legend);
            mLegendFontFile = mState.legend.font;
        }
        const session::LegendContent legend = session::legendContent(mState, mVolume->field().units);
        writeImage(file,
                   session::drawLegend(mPicture.renderer->output().mean, legend, mState.legend.place, *mLegendFont));
    } else {
        writeImage(file, mPicture.renderer->output().mean);
    }
    mPanel.message = "saved " + file.string() + " (" + std::to_string(mPicture.renderer->accumulatedSpp()) + " spp)";
    std::fprintf(stderr, "amrvk view: %s\n", oneLineMessage(mPanel.message).c_str());
}

session::Session ViewerApp::currentSession() const {
    session::Session s = mState;
    s.input = fs::absolute(s.input).lexically_normal().string();
    return s;
}

void ViewerApp::saveSessionFile(const fs::path& file) {
    session::saveSession(file, currentSession());
    mPanel.message = "saved " + file.string();
}

void ViewerApp::loadSessionFile(const fs::path& file) {
    session::Session s = session::loadSession(file);
    const session::DataChangeCheck change = session::dataChange(mState, s);
    AMRVK_CHECK(change.kind != session::DataChange::Other, file.string(), ": ", change.reason,
                "; open it with amrvk view --session ", file.string());
    scene::validateSettings(s.settings);
    s.input = mState.input;  // the same data set (compared as absolute paths)
    if (change.kind == session::DataChange::Rescale) {
        // Read again on the session's scale, with its structure, settings and TF (in that scale's
        // units) at once: when anything fails nothing of the session is taken.
        reloadData(s, false);
    } else {
        // Structure, TF (with the meaning its colours were saved with) and settings in one commit:
        // one build and one majorant pass; when the structure cannot be built nothing is taken.
        picture::PictureEdit e{.tf = session::TfEditor::editable(s.tf), .tfColors = s.tfColors, .settings = s.settings};
        if (!(s.structure == mState.structure)) e.structure = s.structure;
        commit(e);
        mState.spp = s.spp;
        mTfHistory.push(mState.tf);
    }
    mPanel.message = "loaded " + file.string();
}

void ViewerApp::copyCommand() {
    const session::Session s = currentSession();
    // The TF beside the session file's default place, so the command does not depend on the viewer.
    const fs::path tfFile = fs::absolute(mPanel.tfPath);
    writeFileAtomic(tfFile, session::TfEditor(mState.tf).toParaViewJson(tfFile.stem().string()));
    const std::string line = session::renderCommandLine(s, tfFile.string(), "amrvk.png");
    if (mWindow) mWindow->setClipboard(line);
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
    mPanel.message = "command copied (TF in " + tfFile.string() + ")";
}

void ViewerApp::writeStats() const {
    nlohmann::ordered_json j;
    j["device"] = mStats.device;
    j["frames"] = mFrame;
    j["frameBudgetSeconds"] = mBudget.budgetSeconds();
    auto summary = [](const std::vector<double>& v) {
        return nlohmann::ordered_json{{"count", v.size()},
                                      {"meanSeconds", Timings::mean(v)},
                                      {"medianSeconds", Timings::percentile(v, 0.5)},
                                      {"p95Seconds", Timings::percentile(v, 0.95)}};
    };
    j["interactiveFrames"] = summary(mTimings.interactiveFrames);
    j["idleFrames"] = summary(mTimings.idleFrames);
    j["timeToFirstFullSample"] = summary(mTimings.toFirstFullSample);
    j["previewFrames"] = mPreviewFrames;  // by mode: dvr (the preview is always ray-marched)
    j["spp"] = mPicture.renderer->accumulatedSpp();
    j["resets"] = nlohmann::ordered_json::array();
    for (const Reset& r : mResets)
        j["resets"].push_back({{"frame", r.frame}, {"what", r.what}, {"samplesLeft", r.samplesLeft}});
    j["secondsPerPixelSample"] = mBudget.secondsPerPixelSample();
    // What the edits cost the renderer (render::UpdateCounts): device copies and majorant passes.
    const render::UpdateCounts u = mPicture.renderer->updateCounts();
    j["updates"] = {{"deviceScenes", u.deviceScenes}, {"majorantPasses", u.majorantDispatches}};
    // The field's scale and the histogram under the TF editor (the range it spans, cells counted).
    j["scale"] = amr::fieldScaleName(mState.read.scale);
    if (mHistogram) {
        double inRange = 0;  // counts of cells: whole numbers, exact in double
        for (double c : mHistogram->counts) inRange += c;
        const double cells = inRange + mHistogram->below + mHistogram->above + mHistogram->nan;
        j["histogram"] = {{"lo", mHistogram->lo}, {"hi", mHistogram->hi}, {"bins", mHistogram->counts.size()},
                          {"inRange", inRange}, {"cells", cells}};
    }
    // The last frame's layout (framebuffer pixels, session/viewer_layout.h); with a window only.
    if (mWindow)
        j["layout"] = {{"window", rectJson(mLayout.window)},
                       {"panel", rectJson(mLayout.panel)},
                       {"area", rectJson(mLayout.area)},
                       {"picture", rectJson(mLayout.picture)}};
    writeFileAtomic(mOpt.statsJson, j.dump(2) + "\n");
}

void ViewerApp::writeState() const {
    nlohmann::ordered_json j;
    j["frame"] = mFrame;  // frames completed (input, trace, present)
    j["building"] = mBuilding;
    j["spp"] = mPicture.renderer ? mPicture.renderer->accumulatedSpp() : 0u;  // complete full-resolution samples
    j["previewScale"] = mPreviewScale;                         // > 1: the last frame showed a preview
    j["image"] = {{"width", mState.settings.width}, {"height", mState.settings.height}};  // pixels
    j["imageFollowsPicture"] = mPanel.imageFollowsWindow;
    const scene::Camera& c = mState.settings.camera;  // world space
    auto vec = [](const glm::dvec3& v) { return nlohmann::ordered_json::array({v.x, v.y, v.z}); };
    j["camera"] = {{"eye", vec(c.eye)}, {"target", vec(c.target)}, {"up", vec(c.up)}, {"fovY", c.fovYDegrees}};
    if (mWindow) {
        // The last cursor position taken (window coordinates, rounded) and the buttons held.
        j["pointer"] = {{"x", std::lround(mLastX)}, {"y", std::lround(mLastY)}, {"held", mInputSeen.held}};
        j["events"] = {{"keys", mInputSeen.keys},
                       {"buttons", mInputSeen.buttons},
                       {"cursor", mInputSeen.cursor},
                       {"scroll", mInputSeen.scroll}};
        // This frame's layout and the panel's named widgets on screen (framebuffer pixels).
        j["layout"] = {{"window", rectJson(mLayout.window)},
                       {"panel", rectJson(mLayout.panel)},
                       {"area", rectJson(mLayout.area)},
                       {"picture", rectJson(mLayout.picture)}};
        nlohmann::ordered_json widgets = nlohmann::ordered_json::object();
        for (const auto& [name, r] : mPanel.widgets) widgets[name] = rectJson(r);
        j["widgets"] = widgets;
    }
    writeFileAtomic(mOpt.stateJson, memberPerLine(j) + "\n");
}

}  // namespace

int runViewer(const ViewerOptions& options, std::shared_ptr<const scene::Volume> volume) {
    return ViewerApp(options, std::move(volume)).run();
}

}  // namespace amrvk::viewer
