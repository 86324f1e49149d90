#include "viewer/viewer_app_impl.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <future>
#include <memory>
#include <optional>

#include "amr/readers.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/progress.h"
#include "core/stats.h"
#include "core/strings.h"
#include "gpu/buffer.h"
#include "gpu/context.h"
#include "gpu/shader_compiler.h"
#include "gpu/shader_library.h"
#include "picture/first_frame.h"
#include "picture/picture.h"
#include "render/display_pass.h"
#include "render/renderer.h"
#include "scene/render_output.h"
#include "scene/tf_files.h"
#include "scene/tf_presets.h"
#include "session/legend_image.h"
#include "viewer/cut_overlay.h"
#include "viewer/imgui_layer.h"
#include "viewer/legend_overlay.h"
#include "viewer/logic/data_change.h"
#include "viewer/logic/file_watcher.h"
#include "viewer/logic/frame_budget.h"
#include "viewer/logic/script.h"
#include "viewer/logic/viewer_layout.h"
#include "viewer/panels.h"
#include "viewer/swapchain.h"
#include "viewer/window.h"

namespace fs = std::filesystem;

namespace amrvk::viewer {

namespace {

// The window's pixels beside the picture (packed B, G, R, A): a dark grey, apart from black
// backgrounds, so the picture's edge shows.
constexpr uint32_t kLetterboxColor = 0xff262626u;

double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

}  // namespace

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
    if (mOpt.ranks) mOpt.ranks->start(p);  // every rank made the same picture (before the editor's form of its TF)
    adoptPicture(std::move(p));
    noteReset("picture");
}

picture::Options ViewerApp::pictureOptions() const {
    return {.shaders = gpu::ShaderLibrary(mOpt.shaderDir),
            .note = [](const std::string& line) { std::fprintf(stderr, "amrvk: %s\n", oneLineMessage(line).c_str()); }};
}

void ViewerApp::adoptPicture(picture::Picture&& p) {
    mPicture = std::move(p);
    mPicture.renderer->setSubMajorantsInBackground(true);  // a TF edit does not wait for them
    // The editor's form of the TF: the same function, with both channels spanning its range.
    const scene::TfChannels editable = TfEditor::editable(mPicture.described.tf);
    if (!(editable == mPicture.described.tf)) mPicture.commit({.tf = editable});
    mState = mPicture.session();
    mTfHistory = TfHistory(mState.tf);
    mStats.combination = mPicture.renderer->config().labelWithGrid();
    mPanel.gridText = mState.structure.grid;
    mHistogram.reset();  // the data may be new
    updateHistogram();
}

void ViewerApp::updateHistogram() {
    // The histogram depends on the value range only: colour and opacity drags do not recompute it.
    const TfEditor editor(mState.tf);
    if (!mHistogram || mHistogram->lo != editor.lo() || mHistogram->hi != editor.hi())
        mHistogram = fieldHistogram(mVolume->model, mVolume->field(), editor.lo(), editor.hi(), 128);
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
        if (refitTf) d.session.tf = tfOnNewScale(d.session.tf, *mVolume, *volume);
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
    scheduleAhead();  // the steps read ahead were read on the old scale
    std::fprintf(stderr, "amrvk view: %s scale, field range [%g, %g]\n", amr::fieldScaleName(mState.read.scale),
                 double(mVolume->valueLo()), double(mVolume->valueHi()));
}

bool ViewerApp::setReadScale(const amr::ReadOptions& read) {
    session::Session next = mState;
    next.read.scale = read.scale;
    next.read.logFloor = read.logFloor;
    if (dataChange(mState, next).kind == DataChange::Rescale) {
        reloadData(next, true);
        return true;
    }
    mState.read = next.read;  // a floor on the linear scale: recorded, no value changes
    return false;
}

void ViewerApp::updateLayout() {
    int w = 0, h = 0;
    if (mWindow) mWindow->framebufferSize(w, h);
    mLayout = viewerLayout(w, h, mPanel.panelWidth, mState.settings.width, mState.settings.height);
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
    mHold.reset();  // the new picture's preview is made, then beaten
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
        if (w <= 0 || h <= 0) defaultWindowSize(mState.settings.width, mState.settings.height, w, h);
        mWindow = std::make_unique<Window>(w, h, "amrvk view - " + fs::path(mState.input).filename().string());
        co.instanceExtensions = Window::requiredInstanceExtensions();
        co.createSurface = [this](VkInstance instance) { return mWindow->createSurface(instance); };
    }
    mCtx = std::make_unique<gpu::Context>(co);
    mValidationBefore = mCtx->validationErrors();
    mStats.device = mCtx->deviceReport().name;
    if (!mOpt.shaderDir.empty()) mWatcher.emplace(std::vector<fs::path>{gpu::shaderSourceRoot(mOpt.shaderDir)});
    load();
    startSeries();
    mColorMaps.push_back(mState.tf);  // the starting colour map first
    for (const std::string& name : scene::presetNames()) mColorMaps.push_back(scene::builtInChannels(name));
    if (!mOpt.script.empty()) {
        mScript = loadScript(mOpt.script);
        checkScript(mScript, {mOpt.shaderDir, mState.structure});  // every line before frame 0
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
    playSeries();
    advancePathPreview();
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
        if (mPlayer) {
            mPanel.seriesSteps = mPlayer->steps();
            mPanel.seriesStep = mPlayer->step();
            mPanel.seriesPlaying = mPlayer->playing();
            mPanel.seriesFps = mPlayer->fps();
            mPanel.seriesLabel = stepLabel();
            mPanel.seriesAheadBudget = mOpt.seriesAheadBytes;
        }
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
        e.tf = refitTfRange(e.tf, mVolume->valueLo(), mVolume->valueHi());
        req.tfCommitted = true;
    }
    if (req.applyColorMap && mPanel.colorMapChoice >= 0 && size_t(mPanel.colorMapChoice) < mColorMaps.size()) {
        TfEditor(e.tf).setColorMap(mColorMaps[size_t(mPanel.colorMapChoice)]);
        req.tfCommitted = true;
    }
    if (req.loadTfFile) {
        const scene::ParaViewPresets p = scene::loadParaViewPresets(mPanel.tfPath);
        AMRVK_CHECK(!p.presets.empty(), mPanel.tfPath, ": no usable preset");
        for (const scene::TfChannels& c : p.presets) mColorMaps.push_back(c);
        TfEditor(e.tf).setPreset(p.presets.front());
        mPanel.message = "loaded " + std::to_string(p.presets.size()) + " preset(s) from " + mPanel.tfPath +
                         (p.skipped.empty() ? "" : " (" + std::to_string(p.skipped.size()) + " skipped)");
        req.tfCommitted = true;
    }
    if (req.saveTfFile) {
        writeFileAtomic(mPanel.tfPath, TfEditor(e.tf).toParaViewJson(fs::path(mPanel.tfPath).stem().string()));
        mPanel.message = "saved " + mPanel.tfPath;
    }
    if (req.resetView) mOrbit.reset(e.settings.camera);
    if (mPlayer && req.seriesPlayToggle) mPlayer->setPlaying(!mPlayer->playing());
    if (mPlayer && req.seriesFps) mPlayer->setFps(*req.seriesFps);
    if (mPlayer && req.seriesStep) {  // another step: this frame's other edits were made on this one's state
        showStep(*req.seriesStep);
        return;
    }
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
    applyPathRequests(req.path);
    if (req.screenshot) screenshot(mPanel.screenshotPath);
    if (req.saveSession) saveSessionFile(mPanel.sessionPath);
    if (req.loadSession) loadSessionFile(mPanel.sessionPath);
    if (req.copyCommand) copyCommand();
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
    // A still picture's preview continues at its scale to its second sample (keepPreview); a new
    // scale would restart it.
    const bool continuing = mNeedPreview && mPreviewing && !mInteracting;
    mPreviewing = mNeedPreview;
    if (!continuing) mPreviewScale = mNeedPreview ? mBudget.previewScale(full.width, full.height) : 1;
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
        updateShown();
        if (mWindow) mWindow->waitEvents(0.03);  // converged: wait for the user instead of spinning
        return;
    }
    const uint64_t pixels = uint64_t(s.width) * uint64_t(s.height);
    const double gpuBefore = mPicture.renderer->stats().gpuSeconds;
    if (mPreviewing) {
        ++mPreviewFrames[scene::modeName(s.mode)];
        mPicture.renderer->accumulate(1);
        mBudget.record(mPicture.renderer->stats().gpuSeconds - gpuBefore, pixels);
        // While the user interacts every frame shows a new preview; when they stop it gets its
        // second sample (its noise measured) and stays on screen until the estimate is as clean.
        mNeedPreview = mInteracting || mPicture.renderer->accumulatedSpp() < picture::kFirstFrameSpp;
        if (!mNeedPreview) keepPreview();
        mShown = scene::Shown::Preview;
    } else {
        const uint32_t rows = mBudget.rowsPerFrame(s.width, s.height, mPicture.renderer->rowsDone());
        // Whole samples that fit the budget, 1 to 64.
        const auto samplesThatFit = [&] {
            const double perSample = std::max(mBudget.secondsPerPixelSample() * double(pixels), 1e-9);
            return uint32_t(std::clamp(mBudget.budgetSeconds() / perSample, 1.0, 64.0));
        };
        if (mOpt.ranks && mPicture.renderer->rowsDone() == 0) {
            // An MPI job: whole samples, every rank a share of each pass (as many as fit rank 0's budget).
            uint32_t n = samplesThatFit();
            const uint32_t ranks = uint32_t(mOpt.ranks->ranks());
            if (limit > 0) n = std::max(1u, std::min(n, (limit - mPicture.renderer->accumulatedSpp()) / ranks));
            const Clock::time_point passStart = Clock::now();
            mOpt.ranks->pass(mPicture, n);
            mBudget.record(secondsSince(passStart), pixels * n);
        } else if (rows >= uint32_t(s.height) && mPicture.renderer->rowsDone() == 0) {
            // Fast device: whole samples, as many as fit.
            uint32_t n = samplesThatFit();
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
        updateShown();
    }
    mDisplayFresh = mShown != scene::Shown::Nothing;
    if (mStats.firstPictureSeconds < 0 && mDisplayFresh) mStats.firstPictureSeconds = secondsSince(mOpt.startedAt);
}

void ViewerApp::keepPreview() {
    const scene::RenderOutput out = mPicture.renderer->output();
    mHold.reset();
    mHold.previewReady(scene::meanRelativeError(out));
    mPreviewImage = out.mean;
    if (!mWindow) return;
    // The display pass reads sums and a count per pixel: the mean times the samples.
    std::vector<shared::AccumPixelGpu> accum(out.mean.pixels.size(), shared::AccumPixelGpu{});
    const float n = float(out.spp);
    for (size_t i = 0; i < accum.size(); ++i) accum[i].sumHi = glm::vec4(glm::vec3(out.mean.pixels[i]) * n, n);
    const uint64_t bytes = accum.size() * sizeof(shared::AccumPixelGpu);
    vkQueueWaitIdle(mCtx->queue());  // a frame in flight may still read the last preview
    if (!mPreviewAccum.valid() || mPreviewAccum.size() != bytes)
        mPreviewAccum = gpu::Buffer(*mCtx, bytes, gpu::MemoryKind::Device, "previewShown");
    mPreviewAccum.upload(accum.data(), bytes);
}

void ViewerApp::updateShown() {
    if (mPreviewing) {  // the renderer holds the preview, not the estimate
        mShown = scene::Shown::Preview;
        return;
    }
    render::Renderer& r = *mPicture.renderer;
    const uint32_t spp = r.accumulatedSpp();
    if (r.rowsDone() == 0 && mHold.wantsMeasure(spp)) mHold.estimateMeasured(spp, scene::meanRelativeError(r.output()));
    const scene::Shown was = mShown;
    mShown = mHold.shown(spp, mState.spp);
    if (was == scene::Shown::Preview && mShown == scene::Shown::Estimate && mHold.hasPreview())
        mEstimateShown = EstimateShown{mFrame, spp, mHold.estimateNoise().value_or(-1), mHold.threshold(),
                                       mState.spp > 0 && spp >= mState.spp};
}

void ViewerApp::finishPreview() {
    if (mHold.hasPreview()) return;
    const scene::RenderSettings& full = mState.settings;
    if (!mPreviewing) mPreviewScale = mBudget.previewScale(full.width, full.height);
    scene::RenderSettings s = full;
    s.width = std::max(1, full.width / mPreviewScale);
    s.height = std::max(1, full.height / mPreviewScale);
    s.mode = scene::Mode::Dvr;
    mPicture.commit({.settings = s});
    const uint32_t have = mPicture.renderer->accumulatedSpp();
    if (have < picture::kFirstFrameSpp) mPicture.renderer->accumulate(picture::kFirstFrameSpp - have);
    ++mPreviewFrames[scene::modeName(s.mode)];
    keepPreview();
    mPreviewing = true;    // the renderer holds the preview
    mNeedPreview = false;  // the next frame starts the estimate
    mShown = scene::Shown::Preview;
    mDisplayFresh = true;
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
        mDisplayFresh = mShown != scene::Shown::Nothing;
    }
    // The swapchain can lag the layout by a frame while the window is resized: draw only a
    // rectangle that lies in it.
    const bool drawable = !picture.empty() && picture.right() <= mDisplayWidth && picture.bottom() <= mDisplayHeight;
    // The picture on screen: the preview in progress (mPreviewing), the kept preview the estimate
    // has not beaten yet, or the estimate.
    const scene::RenderSettings& s = mPicture.renderer->settings();
    const bool kept = !mPreviewing && mShown == scene::Shown::Preview && mPreviewAccum.valid();
    const uint64_t source = kept ? mPreviewAccum.address() : mPicture.renderer->accumulationAddress();
    const int sourceWidth = kept ? mPreviewImage.width : s.width, sourceHeight = kept ? mPreviewImage.height : s.height;
    const bool ok = mSwapchain->frame([&](VkCommandBuffer cmd, VkImage image, VkFramebuffer framebuffer) {
        // Until the first full-resolution sample is complete the last picture stays on screen.
        if (mDisplayFresh && drawable)
            mDisplayPass->record(
                cmd, source, sourceWidth, sourceHeight, mDisplay,
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

void ViewerApp::finishSample() {
    // The full-resolution picture with at least one complete sample (no half-traced rows).
    const scene::RenderSettings& s = mState.settings;
    mPicture.commit({.settings = s});
    mPreviewScale = 1;
    mPreviewing = false;
    if (mPicture.renderer->accumulatedSpp() == 0 || mPicture.renderer->rowsDone() > 0)
        mPicture.renderer->accumulateRows(uint32_t(s.height) - mPicture.renderer->rowsDone());
}

int runViewer(const ViewerOptions& options, std::shared_ptr<const scene::Volume> volume) {
    return ViewerApp(options, std::move(volume)).run();
}

}  // namespace amrvk::viewer
