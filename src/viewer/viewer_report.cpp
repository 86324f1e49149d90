// What the viewer reports: the statistics panel, --stats at exit and --state-file after every frame.

#include <iterator>
#include <nlohmann/json.hpp>

#include "amr/readers.h"
#include "amr/step_time.h"
#include "core/file_io.h"
#include "gpu/context.h"
#include "render/renderer.h"
#include "viewer/logic/viewer_layout.h"
#include "viewer/viewer_app_impl.h"
#include "viewer/window.h"

namespace amrvk::viewer {

namespace {

nlohmann::ordered_json optionalJson(std::optional<double> v) { return v ? nlohmann::ordered_json(*v) : nullptr; }

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

}  // namespace

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
    st.shown = mShown;
    st.previewNoise = mHold.previewNoise().value_or(-1);
    st.estimateNoise = mHold.estimateNoise().value_or(-1);
    st.noiseToReach = mHold.threshold();
    st.deviceBytes = mCtx->memory().currentBytes();
    st.ranks = mOpt.ranks ? mOpt.ranks->ranks() : 1;
}

void ViewerApp::writeStats() const {
    nlohmann::ordered_json j;
    j["device"] = mStats.device;
    j["frames"] = mFrame;
    j["frameBudgetSeconds"] = mBudget.budgetSeconds();
    j["ranks"] = mStats.ranks;  // processes tracing each pass of the estimate (mpirun -n N amrvk view)
    j["timeToFirstPicture"] = mStats.firstPictureSeconds;  // seconds from the command's start (-1: none)
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
    j["shown"] = scene::shownName(mShown);  // on screen at exit: the preview or the estimate
    j["previewNoise"] = optionalJson(mHold.previewNoise());
    j["estimateNoise"] = optionalJson(mHold.estimateNoise());
    // The last time a kept preview gave way: at which frame and spp, the estimate's noise then and
    // the noise it had to reach, or that it reached the session's spp (atLimit).
    j["estimateShown"] = nullptr;
    if (mEstimateShown)
        j["estimateShown"] = {{"frame", mEstimateShown->frame},
                              {"spp", mEstimateShown->spp},
                              {"noise", mEstimateShown->noise},
                              {"threshold", mEstimateShown->threshold},
                              {"atLimit", mEstimateShown->atLimit}};
    j["resets"] = nlohmann::ordered_json::array();
    for (const Reset& r : mResets)
        j["resets"].push_back({{"frame", r.frame}, {"what", r.what}, {"samplesLeft", r.samplesLeft}});
    // A time series: each step shown (in order), the wall seconds from the request to a picture
    // ready, and whether its data had been read ahead.
    if (mPlayer) {
        j["steps"] = nlohmann::ordered_json::array();
        for (const StepTiming& t : mStepTimings)
            j["steps"].push_back({{"step", t.step}, {"seconds", t.seconds}, {"wasAhead", t.wasAhead}});
    }
    j["secondsPerPixelSample"] = mBudget.secondsPerPixelSample();
    // What the edits cost the renderer (render::UpdateCounts): device copies and majorant passes.
    const render::UpdateCounts u = mPicture.renderer->updateCounts();
    j["updates"] = {{"deviceScenes", u.deviceScenes}, {"majorantPasses", u.majorantDispatches}};
    // The field's scale and the histogram under the TF editor (the range it spans, cells counted).
    j["scale"] = amr::fieldScaleName(mState.read.scale);
    // Every camera path frame the preview showed, in order, with the camera it set (world space).
    j["pathFramesShown"] = nlohmann::ordered_json::array();
    for (const auto& [k, c] : mPathPreview.shown)
        j["pathFramesShown"].push_back({{"frame", k},
                                        {"camera",
                                         {{"eye", {c.eye.x, c.eye.y, c.eye.z}},
                                          {"target", {c.target.x, c.target.y, c.target.z}},
                                          {"up", {c.up.x, c.up.y, c.up.z}},
                                          {"fovY", c.fovYDegrees}}}});
    if (mHistogram) {
        double inRange = 0;  // counts of cells: whole numbers, exact in double
        for (double c : mHistogram->counts) inRange += c;
        const double cells = inRange + mHistogram->below + mHistogram->above + mHistogram->nan;
        j["histogram"] = {{"lo", mHistogram->lo},
                          {"hi", mHistogram->hi},
                          {"bins", mHistogram->counts.size()},
                          {"inRange", inRange},
                          {"cells", cells}};
    }
    // The last frame's layout (framebuffer pixels, viewer/logic/viewer_layout.h); with a window only.
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
    j["ranks"] = mStats.ranks;
    j["firstPictureSeconds"] = mStats.firstPictureSeconds;
    j["spp"] = mPicture.renderer ? mPicture.renderer->accumulatedSpp() : 0u;  // complete full-resolution samples
    j["previewScale"] = mPreviewScale;                                        // > 1: the last frame showed a preview
    // What is on screen (scene/preview_hold.h): "preview" until the estimate is as clean, then
    // "estimate"; the noises compared (mean relative standard error), null until measured.
    j["shown"] = scene::shownName(mShown);
    j["previewNoise"] = optionalJson(mHold.previewNoise());
    j["estimateNoise"] = optionalJson(mHold.estimateNoise());
    j["estimateNoiseSpp"] = mHold.estimateSpp();
    j["image"] = {{"width", mState.settings.width}, {"height", mState.settings.height}};  // pixels
    j["imageFollowsPicture"] = mPanel.imageFollowsWindow;
    // A time series: the step shown (from 0) of how many, its input, when it is (amrvk info's
    // "when"), playing, steps per second, and the steps read ahead.
    if (mPlayer) {
        const std::optional<amr::StepTime> when = amr::stepTimeOf(mVolume->model.attributes);
        j["series"] = {{"step", mPlayer->step()},
                       {"steps", mPlayer->steps()},
                       {"input", mOpt.series[mPlayer->step()]},
                       {"when", when ? amr::describe(*when) : std::string()},
                       {"playing", mPlayer->playing()},
                       {"fps", mPlayer->fps()},
                       {"ahead", mStats.seriesAhead}};
    }
    const scene::Camera& c = mState.settings.camera;  // world space
    auto vec = [](const glm::dvec3& v) { return nlohmann::ordered_json::array({v.x, v.y, v.z}); };
    j["camera"] = {{"eye", vec(c.eye)}, {"target", vec(c.target)}, {"up", vec(c.up)}, {"fovY", c.fovYDegrees}};
    // The camera path: its keyframes and frames, the path frame whose camera the camera is (null
    // when none), whether its preview plays.
    const std::optional<uint32_t> shown = shownPathFrame();
    j["path"] = {{"keyframes", mState.cameraPath.keyframes().size()},
                 {"frames", mState.cameraPath.frameCount()},
                 {"frame", shown ? nlohmann::ordered_json(*shown) : nlohmann::ordered_json(nullptr)},
                 {"playing", mPathPreview.playing}};
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

}  // namespace amrvk::viewer
