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
#include "scene/transfer_function.h"
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
    j["range"] = rangeFromName(range);
    return j.dump();
}

// The union of every output's field range: each read alone (one in memory at a time) with the
// series' read options; `field` (empty: each output's default, then the first's for the rest) is
// set to the field read.
std::pair<float, float> unionRange(const std::vector<std::string>& inputs, const amr::ReadOptions& read,
                                   std::string& field) {
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    ProgressBar bar("series range", "outputs");
    for (size_t i = 0; i < inputs.size(); ++i) {
        amr::ReadOptions ro = read;
        if (!field.empty()) ro.fields = {field};
        const amr::Model model = amr::readModel(inputs[i], ro);
        const amr::Field& f = field.empty() ? model.defaultField() : model.field(field);
        if (field.empty()) field = f.name;
        const amr::FieldStats st = amr::computeFieldStats(model, f);
        lo = std::min(lo, st.minValue);
        hi = std::max(hi, st.maxValue);
        bar.update(i + 1, inputs.size(), inputs[i]);
    }
    bar.finish();
    return {lo, hi};
}

}  // namespace

bool isSeries(const CLI::App& app, const std::vector<std::string>& inputs, const std::string& output) {
    if (inputs.size() > 1) return true;
    for (const char* o : {"--frames", "--orbit", "--series-range", "--fps", "--frames-dir"})
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

    // The frames: inputs in natural order, one frame each or --frames of one.
    std::vector<std::string> inputs =
        request.inputs.empty() ? std::vector<std::string>{} : session::expandInputs(request.inputs);
    session::PictureDescription base = describePicture(app, inputs.empty() ? std::string() : inputs.front(), read, pic);
    if (inputs.empty()) inputs = session::expandInputs({base.session.input});
    base.session.input = inputs.front();
    const bool orbitGiven = given(app, "--orbit");
    const std::optional<uint32_t> frameCount =
        given(app, "--frames") ? std::optional(uint32_t(series.frames)) : std::nullopt;
    const std::vector<std::string> frameInputs = session::planFrames(inputs, frameCount, orbitGiven);
    const uint32_t n = uint32_t(frameInputs.size());
    const double orbit = orbitGiven ? series.orbit : 0.0;
    const RangeFrom rangeFrom = base.tfRange     ? RangeFrom::Given
                                : !base.tfSource ? RangeFrom::Session
                                : session::parseSeriesRange(series.range) == session::SeriesRange::First
                                    ? RangeFrom::First
                                    : RangeFrom::Union;

    // Where they go: numbered frames, or a movie with its frames in a directory beside it.
    const bool movie = fs::path(request.output).extension() == ".mp4";
    AMRVK_CHECK(movie || !given(app, "--frames-dir"), "--frames-dir ", series.framesDir,
                ": only with -o MOVIE.mp4 (without a movie, -o names the frames)");
    AMRVK_CHECK(movie || !given(app, "--fps"), "--fps: only with -o MOVIE.mp4");
    if (movie) requireFfmpeg("-o", request.output);
    const bool keepFrames = !movie || given(app, "--frames-dir");
    const std::string framesOption = movie ? "--frames-dir" : "-o";
    const std::string framesText =
        movie ? (keepFrames ? series.framesDir : request.output + ".frames") + "/" : request.output;
    const session::FrameOutput frames = session::frameOutput(framesOption, framesText, n);
    std::vector<NamedPath> reads;
    for (const std::string& i : inputs) reads.push_back({"input", i});
    for (NamedPath& p : pictureInputs(app, std::string(), pic)) reads.push_back(std::move(p));
    std::vector<NamedPath> outputs = {{"-o", movie ? request.output : std::string()}, {"--json", request.jsonFile}};
    checkOutputs(outputs, reads);
    FramesDirectory directory(frames.directory, framesOption);
    outputs.push_back({framesOption, frames.manifest});
    for (uint32_t k = 0; k < n; ++k) outputs.push_back({framesOption, frames.frame(k)});
    checkOutputs(outputs, reads);
    // A legend goes into every frame (PNG only), with one range for the whole series; its font is
    // read before any work.
    std::unique_ptr<Font> legendFont;
    if (base.session.legend.show) {
        const bool png = frames.extension == ".png";
        AMRVK_CHECK(png || !given(app, "--legend"), "--legend: only PNG frames get a legend (", framesOption, " ",
                    framesText, ")");
        if (png) legendFont = session::openLegendFont(base.session.legend);
    }

    // What a re-run of the same command skips: frames its manifest records as done and that exist.
    std::set<std::string> printed;  // each note once, not once per output
    const std::function<void(const std::string&)> note = [&printed](const std::string& line) {
        if (printed.insert(line).second) std::fprintf(stderr, "amrvk: %s\n", line.c_str());
    };
    const std::string recipe = recipeOf(base, frameInputs, n, orbit, rangeFrom);
    session::FrameManifest manifest;
    const std::optional<session::FrameManifest> previous = session::loadFrameManifest(frames.manifest);
    const bool resume = previous && previous->recipe == recipe;
    // A movie replaces its frames, and deletes them once encoded (without --frames-dir): a file at a
    // frame's name that no manifest of amrvk's lists is not amrvk's, so nothing is touched.
    if (movie) {
        std::vector<uint32_t> foreign;
        std::error_code ec;
        for (uint32_t k = 0; k < n; ++k)
            if ((!previous || !previous->done.count(k)) && fs::exists(fs::symlink_status(frames.frame(k), ec)))
                foreign.push_back(k);
        const std::string names =
            foreign.empty() ? std::string()
                            : frames.frame(foreign[0]).filename().string() + (foreign.size() > 1 ? ", ..." : "");
        AMRVK_CHECK(foreign.empty(), keepFrames ? "--frames-dir " + framesText : "-o " + request.output, ": ",
                    foreign.size(), keepFrames ? " of the frames" : " of its frames in " + framesText,
                    " exist and no manifest of amrvk's lists them (", names, "): refused, the movie would ",
                    keepFrames ? "replace them; move them away, or name another --frames-dir"
                               : "replace and then delete them; move them away, or keep the frames elsewhere with "
                                 "--frames-dir DIR");
        // Another command's frames are amrvk's (its manifest lists them) and are replaced anyway:
        // removed now, so that no frame of the old record outlives it unlisted.
        if (previous && !resume)
            for (const uint32_t k : previous->done)
                if (k < n) fs::remove(frames.frame(k), ec);
    }
    if (resume) {
        manifest = *previous;
        std::error_code ec;
        for (auto it = manifest.done.begin(); it != manifest.done.end();)
            it = (*it < n && fs::is_regular_file(frames.frame(*it), ec)) ? std::next(it) : manifest.done.erase(it);
    } else {
        if (previous) {
            note(frames.manifest.string() + " records another command: rendering all " + std::to_string(n) +
                 " frames anew");
        } else {
            uint32_t existing = 0;
            std::error_code ec;
            for (uint32_t k = 0; k < n; ++k) existing += fs::exists(frames.frame(k), ec) ? 1 : 0;
            if (existing > 0)
                note(std::to_string(existing) + " of the frames exist without a manifest (" + frames.manifest.string() +
                     "): rendering all " + std::to_string(n) + " anew, replacing them");
        }
        manifest.recipe = recipe;
    }
    // The manifest holds the series' camera, centre, field and range once frame 0 was written
    // (they are resolved while it is made; a run stopped before that resolves them again).
    bool resolved = resume && !previous->done.empty();
    // One input (a turntable): its own range is the union; no pass needed.
    const bool rangeOfFirst = rangeFrom == RangeFrom::First || (rangeFrom == RangeFrom::Union && inputs.size() == 1);
    if (!resolved && rangeFrom == RangeFrom::Union && !rangeOfFirst) {
        std::string field = base.session.field;
        manifest.tfRange = unionRange(inputs, base.session.read, field);
        base.session.field = field;
    }
    if (!resolved && rangeFrom == RangeFrom::Given) manifest.tfRange = base.tfRange;

    std::vector<uint32_t> todo;
    for (uint32_t k = 0; k < n; ++k)
        if (!manifest.done.count(k)) todo.push_back(k);
    std::map<uint32_t, Json> stats;  // of the frames rendered now
    std::string deviceName;
    if (!todo.empty()) {
        if (!resume) saveFrameManifest(frames.manifest, manifest);  // before any frame: the old record is void
        gpu::ContextOptions co = dev.context;
        co.requireRayQuery = base.session.structure.backend == scene::Backend::Rq;
        gpu::Context ctx(co);
        deviceName = ctx.deviceReport().name;
        const gpu::ShaderLibrary shaders(dev.shaderDir);
        const uint32_t spp = std::max(base.session.spp, 1u);
        ProgressBar bar("frames", "spp");
        const uint64_t totalSpp = uint64_t(todo.size()) * spp;
        uint64_t doneSpp = 0;
        std::optional<picture::Picture> picture;  // one output in memory at a time
        size_t readsChecked = 0;  // inputFilesRead() entries already checked against the outputs
        std::string pictureInput;
        for (const uint32_t k : todo) {
            const std::string& input = frameInputs[k];
            const double azimuth = session::frameAzimuth(k, n, orbit);
            if (!picture || pictureInput != input) {
                picture.reset();  // released before the next output is read
                session::PictureDescription d = base;
                d.session.input = input;
                if (resolved) {
                    d.session.field = manifest.field;
                    d.fitCamera = false;
                    d.session.settings.camera =
                        session::OrbitCamera::orbitedAbout(manifest.camera, manifest.centre, azimuth);
                }
                bar.finish();
                std::shared_ptr<const scene::Volume> volume = session::loadVolume(d.session);
                if (!resolved && rangeOfFirst) manifest.tfRange = std::make_pair(volume->valueLo(), volume->valueHi());
                // Several outputs: one TF over the series' range (a given --tf-range wins over it in
                // resolvePicture), presets in their range-fixed shape. One output (a turntable): fitted to
                // its data like a single picture, so a resumed run gets the same TF.
                if (inputs.size() > 1) d.dataRange = manifest.tfRange;
                // No frame is a file an output was read from; the outputs are fixed, so only new reads.
                const std::vector<NamedPath> filesRead = inputFilesRead();
                checkOutputs(outputs, {filesRead.begin() + std::ptrdiff_t(readsChecked), filesRead.end()});
                readsChecked = filesRead.size();
                picture = picture::makePicture(ctx, volume, d, {.shaders = shaders, .note = note});
                if (legendFont) session::checkLegendFits(picture->session, *legendFont);  // before the render
                pictureInput = input;
                if (!resolved) {  // the first frame rendered is frame 0 (nothing is done yet)
                    manifest.field = picture->session.field;
                    manifest.camera = picture->session.settings.camera;
                    manifest.centre = 0.5 * (volume->worldLo() + volume->worldHi());
                    resolved = true;
                    base.session.field = manifest.field;
                }
            } else {
                scene::RenderSettings rs = picture->renderer->settings();
                rs.camera = session::OrbitCamera::orbitedAbout(manifest.camera, manifest.centre, azimuth);
                picture->renderer->setSettings(rs);
                picture->session.settings = rs;
            }
            const std::string detail = "frame " + std::to_string(k) + ": " + fs::path(input).filename().string();
            const Timer frameTimer;
            const scene::RenderOutput out =
                picture->render([&](uint32_t done, uint32_t) { bar.update(doneSpp + done, totalSpp, detail); });
            doneSpp += spp;
            AMRVK_CHECK(ctx.validationErrors() == 0, "Vulkan validation reported ", ctx.validationErrors(),
                        " error(s); last: ", ctx.lastValidationMessage());
            session::writePicture(frames.frame(k), out.mean, picture->session, legendFont.get());
            manifest.done.insert(k);
            saveFrameManifest(frames.manifest, manifest);
            stats[k] = picture::renderStats(*picture, out, {.wallSeconds = frameTimer.seconds()});
        }
        bar.finish();
    }
    directory.dismiss();
    Json frameReports = Json::array();
    for (uint32_t k = 0; k < n; ++k) {
        const double azimuth = session::frameAzimuth(k, n, orbit);
        // The movie's temporary frames are gone by the time the report is read.
        const Json file = keepFrames ? Json(frames.frame(k).string()) : Json(nullptr);
        Json report = {{"index", k},
                       {"file", file},
                       {"input", frameInputs[k]},
                       {"azimuthDegrees", azimuth},
                       {"rendered", stats.count(k) > 0}};
        if (resolved) {
            const scene::Camera c = session::OrbitCamera::orbitedAbout(manifest.camera, manifest.centre, azimuth);
            report["camera"] = {{"eye", {c.eye.x, c.eye.y, c.eye.z}},
                                {"target", {c.target.x, c.target.y, c.target.z}},
                                {"up", {c.up.x, c.up.y, c.up.z}},
                                {"fovYDegrees", c.fovYDegrees}};
        }
        if (stats.count(k)) report["stats"] = stats[k];
        frameReports.push_back(std::move(report));
    }

    if (movie) {
        ProgressStage stage("encoding " + request.output + " with ffmpeg");
        encodeMp4(frames.pattern, n, series.fps, request.output);
    }
    const size_t rendered = todo.size();
    if (movie && !keepFrames) {  // the frames were only the movie's: removed with their manifest
        std::error_code ec;
        for (uint32_t k = 0; k < n; ++k) fs::remove(frames.frame(k), ec);  // every one listed by now
        fs::remove(frames.manifest, ec);
        // The directory only when amrvk made it (now, or the run whose manifest was there), and only
        // when nothing else is in it.
        if (directory.made() || previous) fs::remove(frames.directory, ec);
    }
    if (!request.jsonFile.empty()) {
        Json j;
        j["frames"] = frameReports;
        j["frameCount"] = n;
        j["rendered"] = rendered;
        j["field"] = manifest.field;
        j["tfRange"] =
            manifest.tfRange ? Json::array({manifest.tfRange->first, manifest.tfRange->second}) : Json(nullptr);
        j["rangeSource"] = rangeFromName(rangeFrom);
        j["orbitDegrees"] = orbit;
        j["orbitCentre"] =
            resolved ? Json::array({manifest.centre.x, manifest.centre.y, manifest.centre.z}) : Json(nullptr);
        j["movie"] = movie ? Json(request.output) : Json(nullptr);
        j["framesPattern"] = keepFrames ? Json(frames.pattern) : Json(nullptr);
        j["wallSeconds"] = wall.seconds();
        j["peakResidentBytes"] = peakResidentBytes();
        writeFileAtomic(request.jsonFile, j.dump(2) + "\n");
    }
    const std::string where = movie ? request.output : frames.pattern;
    std::printf("wrote %s (%u frames: %zu rendered, %zu already written by this command%s%s) in %.2f s\n",
                where.c_str(), n, rendered, size_t(n) - rendered, deviceName.empty() ? "" : ", on ", deviceName.c_str(),
                wall.seconds());
    return 0;
}

}  // namespace amrvk::cli
