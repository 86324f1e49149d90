#include "cli/render_series.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>

#include "amr/readers.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/image_io.h"
#include "core/movie_io.h"
#include "core/progress.h"
#include "core/stats.h"
#include "gpu/context.h"
#include "gpu/shader_library.h"
#include "picture/picture.h"
#include "render/renderer.h"
#include "scene/tf_files.h"
#include "scene/transfer_function.h"
#include "session/camera_path.h"
#include "session/legend_image.h"
#include "session/orbit_camera.h"
#include "session/series.h"

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace amrvk::cli {

namespace {

// Where the series' TF range comes from.
enum class RangeFrom { Given, Session, First, Union };
const char* rangeFromName(RangeFrom r) {
    switch (r) {
        case RangeFrom::Given:
            return "given";
        case RangeFrom::Session:
            return "session";
        case RangeFrom::First:
            return "first";
        case RangeFrom::Union:
            return "union";
    }
    return "";
}

// The frames directory, made when it is missing (its parent must exist); removed again, if still
// empty, when the command fails before it is dismissed.
class FramesDirectory {
public:
    FramesDirectory(const fs::path& dir, const std::string& option) : mDir(dir) {
        std::error_code ec;
        if (fs::exists(dir, ec)) return;
        mMade = fs::create_directory(dir, ec);
        AMRVK_CHECK(!ec && mMade, option, " ", dir.string(), ": cannot make the frames directory (",
                    ec ? ec.message() : std::string("exists"), ")");
    }
    ~FramesDirectory() {
        std::error_code ec;
        if (mMade && !mDismissed) fs::remove(mDir, ec);  // only when empty
    }
    FramesDirectory(const FramesDirectory&) = delete;
    FramesDirectory& operator=(const FramesDirectory&) = delete;
    void dismiss() { mDismissed = true; }
    bool made() const { return mMade; }

private:
    fs::path mDir;
    bool mMade = false, mDismissed = false;
};

// What makes the frames, as one canonical text: the picture's render command line (the options
// amrvk read, defaults explicit; a --tf file and the inputs as absolute paths), the session's TF
// when it is the one used, the frame count, the orbit and the range policy. Two runs with the same
// recipe write the same frames (amrvk does not look into the inputs' or TF files' contents).
std::string recipeOf(const session::PictureDescription& base, const std::vector<std::string>& inputs, uint32_t frames,
                     double orbit, RangeFrom range) {
    session::PictureDescription d = base;
    d.session.input = "INPUT";
    std::error_code ec;
    if (d.tfSource && fs::is_regular_file(d.tfSource->name, ec))
        d.tfSource->name = fs::absolute(d.tfSource->name).string();
    Json j;
    j["picture"] = session::renderCommandLine(d, "SESSION_TF", "FRAMES");
    if (!d.tfSource) j["sessionTf"] = scene::paraViewPresetJson(d.session.tf);
    Json in = Json::array();
    for (const std::string& i : inputs) in.push_back(fs::absolute(i).lexically_normal().string());
    j["inputs"] = in;
    j["frames"] = frames;
    j["orbitDegrees"] = orbit;
    if (!d.session.cameraPath.empty()) {  // every keyframe exactly: another path renders every frame anew
        Json keys = Json::array();
        for (const session::Keyframe& k : d.session.cameraPath.keyframes()) {
            const scene::Camera& c = k.camera;
            keys.push_back({k.frame, c.eye.x, c.eye.y, c.eye.z, c.target.x, c.target.y, c.target.z, c.up.x, c.up.y,
                            c.up.z, c.fovYDegrees});
        }
        j["cameraPath"] = keys;
    }
    j["range"] = rangeFromName(range);
    return j.dump();
}

// One series, carried from phase to phase of renderSeries.
struct Series {
    // The frames (planSeriesFrames).
    std::vector<std::string> inputs;       // the outputs (data sets), in natural order
    session::PictureDescription base;      // every frame's picture; its field once resolved
    std::vector<std::string> frameInputs;  // frame k's input
    uint32_t n = 0;                        // the frame count
    double orbit = 0;                      // degrees turned over the frames
    const session::CameraPath* path = nullptr;  // the session's camera path (frame k: its camera), or none
    double fps = 24;                            // the movie's frames per second
    RangeFrom rangeFrom = RangeFrom::Given;
    // Where they go (planOutputs, addFrameOutputs, openLegend).
    bool movie = false;                    // -o MOVIE.mp4
    bool keepFrames = false;               // the frames stay once the movie is encoded (or there is no movie)
    std::string framesOption, framesText;  // the option naming the frames, and its text
    session::FrameOutput frames;
    std::vector<NamedPath> reads, outputs;  // the files read, and every file written
    std::unique_ptr<Font> legendFont;       // null: no legend
    // What is done already (loadManifest, resolveRange).
    std::optional<session::FrameManifest> previous;  // the manifest found beside the frames
    session::FrameManifest manifest;
    bool resume = false;        // `previous` records this command: its frames are kept
    bool resolved = false;      // `manifest` holds the series' camera, centre and field
    bool rangeOfFirst = false;  // the range is the first output's, taken as it is read
    // What is rendered now (renderFrames).
    std::vector<uint32_t> todo;      // the frames not yet written, in order
    std::map<uint32_t, Json> stats;  // of the frames rendered now
    std::optional<scene::TfChannels> tf;  // the TF of the frames rendered now (one for the series)
    std::string deviceName;          // empty: nothing rendered
};

// The frames of the session's camera path: its frame count, frame k seen from its cameraAt(k) and
// showing output stepOfFrame(k) of the series (one input: that one in every frame). The options
// that would move the camera otherwise or count the frames contradict it: refused.
void planPathFrames(const CLI::App& app, Series& s) {
    s.path = &s.base.session.cameraPath;
    s.n = s.path->frameCount();
    const std::string has = "the session's camera path (" + std::to_string(s.n) + " frames)";
    AMRVK_CHECK(!given(app, "--orbit"), "--orbit: ", has, " moves the camera; leave out --orbit");
    AMRVK_CHECK(!given(app, "--frames"), "--frames: ", has, " sets the frame count; leave out --frames");
    AMRVK_CHECK(!given(app, "--camera"), "--camera: ", has,
                " sets every frame's camera; leave out --camera (one picture: -o x.png --camera ...)");
    AMRVK_CHECK(s.inputs.size() <= s.n, s.inputs.size(), " inputs over ", has,
                ": some outputs would show in no frame (add frames to the path, or give fewer inputs)");
    for (uint32_t k = 0; k < s.n; ++k)
        s.frameInputs.push_back(s.inputs[session::stepOfFrame(k, s.n, uint32_t(s.inputs.size()))]);
}

// Frame k's camera once the series is resolved: the camera path's at frame k, or the series'
// camera turned to the frame's azimuth.
scene::Camera frameCamera(const Series& s, uint32_t k) {
    if (s.path) return s.path->cameraAt(double(k));
    return session::OrbitCamera::orbitedAbout(s.manifest.camera, s.manifest.centre,
                                              session::frameAzimuth(k, s.n, s.orbit));
}

// The frames: inputs in natural order (none given: the session's), one frame each or --frames of
// one (or the session's camera path's frames), the orbit, and where the TF's range comes from.
void planSeriesFrames(const CLI::App& app, const SeriesRequest& request, const ReadArgs& read, const PictureArgs& pic,
                      const SeriesArgs& series, Series& s) {
    s.inputs = request.inputs.empty() ? std::vector<std::string>{} : session::expandInputs(request.inputs);
    s.base = describePicture(app, s.inputs.empty() ? std::string() : s.inputs.front(), read, pic);
    if (s.inputs.empty()) s.inputs = session::expandInputs({s.base.session.input});
    s.base.session.input = s.inputs.front();
    // Several outputs share one scale: the first output decides an auto scale for all of them, so
    // one TF range means the same on every frame.
    if (s.inputs.size() > 1)
        s.base.session.read.scale = session::seriesScale(s.inputs, s.base.session.read, s.base.session.field);
    const bool orbitGiven = given(app, "--orbit");
    const std::optional<uint32_t> frameCount =
        given(app, "--frames") ? std::optional(uint32_t(series.frames)) : std::nullopt;
    if (!s.base.session.cameraPath.empty()) {
        planPathFrames(app, s);
    } else {
        s.frameInputs = session::planFrames(s.inputs, frameCount, orbitGiven);
        s.n = uint32_t(s.frameInputs.size());
        s.orbit = orbitGiven ? series.orbit : 0.0;
    }
    s.fps = given(app, "--fps") || !s.path ? series.fps : s.path->fps();
    s.rangeFrom = s.base.tfRange                                                           ? RangeFrom::Given
                  : !s.base.tfSource                                                       ? RangeFrom::Session
                  : session::parseSeriesRange(series.range) == session::SeriesRange::First ? RangeFrom::First
                                                                                           : RangeFrom::Union;
}

// Where they go: numbered frames, or a movie with its frames in a directory beside it. The
// options' combination, ffmpeg, and -o (a movie) and --json against the inputs are checked; the
// frames' directory is not made yet.
void planOutputs(const CLI::App& app, const SeriesRequest& request, const PictureArgs& pic, const SeriesArgs& series,
                 Series& s) {
    s.movie = fs::path(request.output).extension() == ".mp4";
    AMRVK_CHECK(s.movie || !given(app, "--frames-dir"), "--frames-dir ", series.framesDir,
                ": only with -o MOVIE.mp4 (without a movie, -o names the frames)");
    AMRVK_CHECK(s.movie || !given(app, "--fps"), "--fps: only with -o MOVIE.mp4");
    if (s.movie) requireFfmpeg("-o", request.output);
    s.keepFrames = !s.movie || given(app, "--frames-dir");
    s.framesOption = s.movie ? "--frames-dir" : "-o";
    s.framesText = s.movie ? (s.keepFrames ? series.framesDir : request.output + ".frames") + "/" : request.output;
    s.frames = session::frameOutput(s.framesOption, s.framesText, s.n);
    for (const std::string& i : s.inputs) s.reads.push_back({"input", i});
    for (NamedPath& p : pictureInputs(app, std::string(), pic)) s.reads.push_back(std::move(p));
    s.outputs = {{"-o", s.movie ? request.output : std::string()}, {"--json", request.jsonFile}};
    checkOutputs(s.outputs, s.reads);
}

// The manifest and every frame added to the outputs, and all checked again (in their directory,
// which exists now).
void addFrameOutputs(Series& s) {
    s.outputs.push_back({s.framesOption, s.frames.manifest});
    for (uint32_t k = 0; k < s.n; ++k) s.outputs.push_back({s.framesOption, s.frames.frame(k)});
    checkOutputs(s.outputs, s.reads);
}

// A legend goes into every frame (PNG only), with one range for the whole series; its font is
// read before any work.
void openLegend(const CLI::App& app, Series& s) {
    if (!s.base.session.legend.show) return;
    const bool png = s.frames.extension == ".png";
    AMRVK_CHECK(png || !given(app, "--legend"), "--legend: only PNG frames get a legend (", s.framesOption, " ",
                s.framesText, ")");
    if (png) s.legendFont = session::openLegendFont(s.base.session.legend);
}

// A movie replaces its frames, and deletes them once encoded (without --frames-dir): a file at a
// frame's name that no manifest of amrvk's lists is not amrvk's, so nothing is touched (refused).
// Another command's frames are amrvk's (its manifest lists them) and are replaced anyway: removed
// now, so that no frame of the old record outlives it unlisted.
void clearMovieFrames(const Series& s, const std::string& output) {
    std::vector<uint32_t> foreign;
    std::error_code ec;
    for (uint32_t k = 0; k < s.n; ++k)
        if ((!s.previous || !s.previous->done.count(k)) && fs::exists(fs::symlink_status(s.frames.frame(k), ec)))
            foreign.push_back(k);
    const std::string names =
        foreign.empty() ? std::string()
                        : s.frames.frame(foreign[0]).filename().string() + (foreign.size() > 1 ? ", ..." : "");
    AMRVK_CHECK(foreign.empty(), s.keepFrames ? "--frames-dir " + s.framesText : "-o " + output, ": ", foreign.size(),
                s.keepFrames ? " of the frames" : " of its frames in " + s.framesText,
                " exist and no manifest of amrvk's lists them (", names, "): refused, the movie would ",
                s.keepFrames ? "replace them; move them away, or name another --frames-dir"
                             : "replace and then delete them; move them away, or keep the frames elsewhere with "
                               "--frames-dir DIR");
    if (s.previous && !s.resume)
        for (const uint32_t k : s.previous->done)
            if (k < s.n) fs::remove(s.frames.frame(k), ec);
}

// What a re-run of the same command skips: frames its manifest records as done and that exist.
// Otherwise every frame is rendered anew (a note says so when frames are replaced) under a
// manifest of this recipe.
void loadManifest(Series& s, const std::string& recipe, const std::string& output,
                  const std::function<void(const std::string&)>& note) {
    s.previous = session::loadFrameManifest(s.frames.manifest);
    s.resume = s.previous && s.previous->recipe == recipe;
    if (s.resume && !s.previous->inputsRead) {
        // An older amrvk's record does not say which files its frames were read from: without
        // that, no output can be checked against them, so nothing is skipped.
        note(s.frames.manifest.string() +
             " does not list the files its frames were read from (an older amrvk): "
             "rendering all " +
             std::to_string(s.n) + " frames anew");
        s.resume = false;
        s.previous.reset();
    }
    bool changed = false;
    if (s.resume) {
        // The frames are as old as the files they were read from: one changed (or gone) makes
        // every frame anew (a union range, and so every frame's TF, may depend on it).
        for (const auto& [file, stamp] : *s.previous->inputsRead) {
            if (session::fileStamp(file) == stamp) continue;
            note(file + " changed since the frames in " + s.frames.manifest.string() +
                 " were rendered: rendering all " + std::to_string(s.n) + " frames anew");
            changed = true;
            s.resume = false;
            break;
        }
    }
    if (s.movie) clearMovieFrames(s, output);
    if (s.resume) {
        s.manifest = *s.previous;
        std::error_code ec;
        for (auto it = s.manifest.done.begin(); it != s.manifest.done.end();)
            it =
                (*it < s.n && fs::is_regular_file(s.frames.frame(*it), ec)) ? std::next(it) : s.manifest.done.erase(it);
        // Frames skipped now read no file in this run: the outputs are checked against what they
        // were read from (a re-run with --json onto an input's .scalars replaced it).
        std::vector<NamedPath> reads;
        for (const auto& [file, stamp] : *s.manifest.inputsRead) reads.push_back({"input", file});
        checkOutputs(s.outputs, reads);
    } else {
        if (s.previous) {
            if (!changed)
                note(s.frames.manifest.string() + " records another command: rendering all " + std::to_string(s.n) +
                     " frames anew");
        } else {
            uint32_t existing = 0;
            std::error_code ec;
            for (uint32_t k = 0; k < s.n; ++k) existing += fs::exists(s.frames.frame(k), ec) ? 1 : 0;
            if (existing > 0)
                note(std::to_string(existing) + " of the frames exist without a manifest (" +
                     s.frames.manifest.string() + "): rendering all " + std::to_string(s.n) + " anew, replacing them");
        }
        s.manifest.recipe = recipe;
    }
    // The manifest holds the series' camera, centre, field and range once frame 0 was written
    // (they are resolved while it is made; a run stopped before that resolves them again).
    s.resolved = s.resume && !s.previous->done.empty();
}

// The series' TF range, unless the manifest holds it: given, or the union of every output's (a
// reading pass, which also settles the field); the first output's is taken as frame 0 is read.
void resolveRange(Series& s) {
    // One input (a turntable): its own range is the union; no pass needed.
    s.rangeOfFirst = s.rangeFrom == RangeFrom::First || (s.rangeFrom == RangeFrom::Union && s.inputs.size() == 1);
    if (!s.resolved && s.rangeFrom == RangeFrom::Union && !s.rangeOfFirst) {
        std::string field = s.base.session.field;
        session::SeriesStatistics pooled = session::seriesStatistics(s.inputs, s.base.session.read, field);
        s.manifest.tfRange = pooled.range;
        s.manifest.tfPercentiles = pooled.percentiles;
        if (!pooled.volumes.empty()) s.manifest.tfHistogram = pooled.volumes;
        s.base.session.field = field;
    }
    if (!s.resolved && s.rangeFrom == RangeFrom::Given) s.manifest.tfRange = s.base.tfRange;
}

// Frame k's picture on `ctx`, read from its input (the caller released the last one): frameCamera
// once resolved (a camera path's from the start); the first frame made (frame 0) resolves the field,
// camera and centre, and the range when it is the first output's. No file read is an output
// (`readsChecked`: the inputFilesRead() entries checked already).
picture::Picture framePicture(Series& s, gpu::Context& ctx, const gpu::ShaderLibrary& shaders, uint32_t k,
                              size_t& readsChecked, const std::function<void(const std::string&)>& note) {
    session::PictureDescription d = s.base;
    d.session.input = s.frameInputs[k];
    if (s.resolved) {
        d.session.field = s.manifest.field;
        d.fitCamera = false;
        d.session.settings.camera = frameCamera(s, k);
    } else if (s.path) {
        d.session.settings.camera = s.path->cameraAt(double(k));  // a session's: never fitted
    }
    // Each frame is one picture and nothing after it reads the cells (the histogram and ranges are
    // made with the bricks): they go once the bricks exist, as for one render (issue 31, point 7);
    // the dense sampler rasterises them.
    std::shared_ptr<const scene::Volume> volume = session::loadVolume(
        d.session, {.releaseCells = d.session.structure.sampler != scene::SamplerKind::Dense});
    if (!s.resolved && s.rangeOfFirst) {
        s.manifest.tfRange = std::make_pair(volume->valueLo(), volume->valueHi());
        s.manifest.tfPercentiles = volume->percentiles;
        if (!volume->volumeHistogram.empty()) s.manifest.tfHistogram = volume->volumeHistogram;
    }
    // Several outputs: one TF for the series (a given --tf-range wins over it in resolvePicture):
    // spiky and foggy fitted to the series' percentiles and layers to its volume histogram (the
    // first output's, or all outputs' pooled), the other presets in their range-fixed shape over
    // its range; a manifest of an older amrvk has the range only, and its frames had every preset
    // range-fixed. One output (a turntable): fitted to its data like a single picture, so a
    // resumed run gets the same TF.
    if (s.inputs.size() > 1) {
        if (s.manifest.tfPercentiles && (s.rangeFrom == RangeFrom::First || s.rangeFrom == RangeFrom::Union)) {
            d.dataPercentiles = s.manifest.tfPercentiles;
            d.dataHistogram = s.manifest.tfHistogram;
        } else {
            d.dataRange = s.manifest.tfRange;
        }
    }
    // No frame is a file an output was read from; the outputs are fixed, so only new reads.
    const std::vector<NamedPath> filesRead = inputFilesRead();
    checkOutputs(s.outputs, {filesRead.begin() + std::ptrdiff_t(readsChecked), filesRead.end()});
    readsChecked = filesRead.size();
    picture::Picture picture = picture::makePicture(ctx, volume, d, {.shaders = shaders, .note = note});
    if (s.legendFont)  // before the render
        session::checkLegendFits(picture.session(), picture.volume->field().units, *s.legendFont);
    s.tf = picture.described.tf;
    if (!s.resolved) {  // the first frame rendered is frame 0 (nothing is done yet)
        s.manifest.field = picture.described.field;
        s.manifest.camera = picture.renderer->settings().camera;
        s.manifest.centre = 0.5 * (volume->worldLo() + volume->worldHi());
        s.resolved = true;
        s.base.session.field = s.manifest.field;
    }
    return picture;
}

// The frames not written yet (s.todo, not empty), rendered in order on one device, one output in
// memory at a time; each frame is written, then recorded in the manifest.
void renderFrames(Series& s, const DeviceArgs& dev, const std::function<void(const std::string&)>& note) {
    if (!s.resume) saveFrameManifest(s.frames.manifest, s.manifest);  // before any frame: the old record is void
    gpu::ContextOptions co = dev.context;
    co.requireRayQuery = s.base.session.structure.backend == scene::Backend::Rq;
    gpu::Context ctx(co);
    s.deviceName = ctx.deviceReport().name;
    const gpu::ShaderLibrary shaders(dev.shaderDir);
    const uint32_t spp = std::max(s.base.session.spp, 1u);
    ProgressBar bar("frames", "spp");
    const uint64_t totalSpp = uint64_t(s.todo.size()) * spp;
    uint64_t doneSpp = 0;
    std::optional<picture::Picture> picture;  // one output in memory at a time
    size_t readsChecked = 0;                  // inputFilesRead() entries already checked against the outputs
    std::string pictureInput;
    for (const uint32_t k : s.todo) {
        const std::string& input = s.frameInputs[k];
        if (!picture || pictureInput != input) {
            picture.reset();  // released before the next output is read
            bar.finish();
            picture = framePicture(s, ctx, shaders, k, readsChecked, note);
            pictureInput = input;
        } else {
            scene::RenderSettings rs = picture->renderer->settings();
            rs.camera = frameCamera(s, k);
            picture->commit({.settings = rs});  // Picture::session() reads it from the renderer
        }
        const std::string detail = "frame " + std::to_string(k) + ": " + fs::path(input).filename().string();
        const Timer frameTimer;
        const scene::RenderOutput out =
            picture->render([&](uint32_t done, uint32_t) { bar.update(doneSpp + done, totalSpp, detail); });
        doneSpp += spp;
        AMRVK_CHECK(ctx.validationErrors() == 0, "Vulkan validation reported ", ctx.validationErrors(),
                    " error(s); last: ", ctx.lastValidationMessage());
        session::writePicture(s.frames.frame(k), out.mean, picture->session(), picture->volume->field().units,
                              s.legendFont.get());
        s.manifest.done.insert(k);
        if (!s.manifest.inputsRead) s.manifest.inputsRead.emplace();
        for (const NamedPath& f : inputFilesRead()) {
            const std::string file = fs::absolute(f.path).lexically_normal().string();
            if (!s.manifest.inputsRead->count(file))
                (*s.manifest.inputsRead)[file] = session::fileStamp(file).value_or(session::FileStamp{});
        }
        saveFrameManifest(s.frames.manifest, s.manifest);
        s.stats[k] = picture::renderStats(*picture, out, {.wallSeconds = frameTimer.seconds()});
    }
    bar.finish();
}

// --json's report of every frame: its file (null for a movie's temporary frames), input, azimuth
// (a camera path: its frame), whether it was rendered now, its camera once resolved (a camera
// path's always), and its statistics when rendered now.
Json frameReports(const Series& s) {
    Json reports = Json::array();
    for (uint32_t k = 0; k < s.n; ++k) {
        const double azimuth = session::frameAzimuth(k, s.n, s.orbit);
        // The movie's temporary frames are gone by the time the report is read.
        const Json file = s.keepFrames ? Json(s.frames.frame(k).string()) : Json(nullptr);
        Json report = {{"index", k},
                       {"file", file},
                       {"input", s.frameInputs[k]},
                       {"azimuthDegrees", azimuth},
                       {"rendered", s.stats.count(k) > 0}};
        if (s.path) report["pathFrame"] = k;
        if (s.resolved || s.path) {
            const scene::Camera c = frameCamera(s, k);
            report["camera"] = {{"eye", {c.eye.x, c.eye.y, c.eye.z}},
                                {"target", {c.target.x, c.target.y, c.target.z}},
                                {"up", {c.up.x, c.up.y, c.up.z}},
                                {"fovYDegrees", c.fovYDegrees}};
        }
        if (s.stats.count(k)) report["stats"] = s.stats.at(k);
        reports.push_back(std::move(report));
    }
    return reports;
}

// -o MOVIE.mp4: encoded from the frames. Frames that were only the movie's are then removed with
// their manifest, and so is their directory when amrvk made it (`madeDirectory`: now, or the run
// whose manifest was there) and nothing else is in it.
void finishMovie(const Series& s, const std::string& output, bool madeDirectory) {
    {
        ProgressStage stage("encoding " + output + " with ffmpeg");
        encodeMp4(s.frames.pattern, s.n, s.fps, output);
    }
    if (s.keepFrames) return;
    std::error_code ec;
    for (uint32_t k = 0; k < s.n; ++k) fs::remove(s.frames.frame(k), ec);  // every one listed by now
    fs::remove(s.frames.manifest, ec);
    if (madeDirectory || s.previous) fs::remove(s.frames.directory, ec);
}

// --json: the frames' reports and the series' count, field, range, orbit, movie and frames.
void writeSeriesJson(const std::string& file, const Series& s, const std::string& output, Json frames,
                     const Timer& wall) {
    Json j;
    j["frames"] = std::move(frames);
    j["frameCount"] = s.n;
    j["rendered"] = s.todo.size();
    j["field"] = s.manifest.field;
    j["tfRange"] =
        s.manifest.tfRange ? Json::array({s.manifest.tfRange->first, s.manifest.tfRange->second}) : Json(nullptr);
    j["rangeSource"] = rangeFromName(s.rangeFrom);
    // The percentiles spiky and foggy were fitted to, and the TF itself (a ParaView preset, as
    // --tf FILE takes it), when frames were rendered now.
    j["tfPercentiles"] = s.manifest.tfPercentiles ? Json(s.manifest.tfPercentiles->values) : Json(nullptr);
    j["transferFunction"] = s.tf ? Json::parse(scene::paraViewPresetJson(*s.tf)).at(0) : Json(nullptr);
    j["orbitDegrees"] = s.orbit;
    j["cameraPath"] = s.path ? Json{{"frames", s.n}, {"fps", s.path->fps()}} : Json(nullptr);
    j["fps"] = s.movie ? Json(s.fps) : Json(nullptr);
    j["orbitCentre"] =
        s.resolved ? Json::array({s.manifest.centre.x, s.manifest.centre.y, s.manifest.centre.z}) : Json(nullptr);
    j["movie"] = s.movie ? Json(output) : Json(nullptr);
    j["framesPattern"] = s.keepFrames ? Json(s.frames.pattern) : Json(nullptr);
    j["wallSeconds"] = wall.seconds();
    j["peakResidentBytes"] = peakResidentBytes();
    writeFileAtomic(file, j.dump(2) + "\n");
}

}  // namespace

bool isSeries(const CLI::App& app, const std::vector<std::string>& inputs, const std::string& output) {
    if (inputs.size() > 1) return true;
    // --series-range alone does not make one input a series (one input has one range).
    for (const char* o : {"--frames", "--orbit", "--fps", "--frames-dir"})
        if (given(app, o)) return true;
    if (!inputs.empty() && session::isInputPattern(inputs.front())) return true;
    return fs::path(output).extension() == ".mp4" || session::hasFrameNumber(output) ||
           (!output.empty() && output.back() == '/');
}

int renderSeries(const CLI::App& app, const SeriesRequest& request, const ReadArgs& read, const PictureArgs& pic,
                 const SeriesArgs& series, const DeviceArgs& dev, mpi::World* world) {
    AMRVK_CHECK(!world,
                "a series (several inputs, --frames, --orbit, numbered frames or a movie) is rendered by one "
                "process, not under an MPI launcher (render each output with mpirun, or the series without it)");
    AMRVK_CHECK(request.varianceFile.empty(), "--variance ", request.varianceFile,
                ": one image only, not with a series of frames (render a single frame for error bars)");
    const Timer wall;
    Series s;
    planSeriesFrames(app, request, read, pic, series, s);
    planOutputs(app, request, pic, series, s);
    FramesDirectory directory(s.frames.directory, s.framesOption);
    addFrameOutputs(s);
    openLegend(app, s);

    std::set<std::string> printed;  // each note once, not once per output
    const std::function<void(const std::string&)> note = [&printed](const std::string& line) {
        if (printed.insert(line).second) std::fprintf(stderr, "amrvk: %s\n", oneLineMessage(line).c_str());
    };
    loadManifest(s, recipeOf(s.base, s.frameInputs, s.n, s.orbit, s.rangeFrom), request.output, note);
    resolveRange(s);
    for (uint32_t k = 0; k < s.n; ++k)
        if (!s.manifest.done.count(k)) s.todo.push_back(k);
    if (!s.todo.empty()) {
        try {
            renderFrames(s, dev, note);
        } catch (...) {
            // A run that wrote no frame leaves no record of one in a directory it made (the
            // directory itself is removed once empty).
            std::error_code ec;
            if (directory.made() && s.manifest.done.empty()) fs::remove(s.frames.manifest, ec);
            throw;
        }
    }
    directory.dismiss();
    Json reports = frameReports(s);
    if (s.movie) finishMovie(s, request.output, directory.made());
    if (!request.jsonFile.empty()) writeSeriesJson(request.jsonFile, s, request.output, std::move(reports), wall);
    const std::string where = s.movie ? request.output : s.frames.pattern;
    const size_t rendered = s.todo.size();
    std::printf("wrote %s (%u frames: %zu rendered, %zu already written by this command%s%s) in %.2f s\n",
                where.c_str(), s.n, rendered, size_t(s.n) - rendered, s.deviceName.empty() ? "" : ", on ",
                s.deviceName.c_str(), wall.seconds());
    return 0;
}

}  // namespace amrvk::cli
