#include "python/py_renderer.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "core/file_io.h"
#include "core/font.h"
#include "core/image_io.h"
#include "core/stats.h"
#include "core/strings.h"
#include "gpu/context.h"
#include "gpu/shader_compiler.h"
#include "picture/first_frame.h"
#include "picture/picture.h"
#include "python/context_cache.h"
#include "python/fair_mutex.h"
#include "python/py_transfer_function.h"
#include "python/py_volume.h"
#include "python/renderer_keywords.h"
#include "scene/camera.h"
#include "scene/limits.h"
#include "scene/preview_hold.h"
#include "scene/render_output.h"
#include "session/legend_image.h"
#include "session/picture_description.h"
#include "session/session.h"
#include "session/setting_table.h"

namespace amrvk::python {

namespace {

class PyRenderer {
public:
    PyRenderer(std::shared_ptr<gpu::Context> ctx, std::shared_ptr<const scene::Volume> volume,
               const session::PictureDescription& d, const fs::path& shaderDir, bool quiet,
               std::vector<NamedPath> dataFiles)
        : mCtx(std::move(ctx)), mDataFiles(std::move(dataFiles)) {
        picture::Options o;
        o.shaders = gpu::ShaderLibrary(shaderDir);
        if (!quiet) o.note = [](const std::string& line) { std::fprintf(stderr, "amrvk: %s\n", line.c_str()); };
        py::gil_scoped_release release;
        mPicture = picture::makePicture(*mCtx, std::move(volume), d, o);
    }

    // ---- the picture ----
    session::Session session() const { return open().session(); }
    // The data set shown (its path as given); None for a volume made from arrays or yt.
    py::object input() const {
        const std::string in = session().input;
        return in.empty() ? py::object(py::none()) : py::object(py::str(in));
    }
    // Another data set shown (a series step: the widget's time slider): read with the picture's
    // read options and field, and built, the camera, TF, settings and structure kept; the image
    // starts again. A renderer over arrays or yt has no file to replace (ValueError).
    void setInput(const py::object& value) {
        if (session().input.empty())
            throw py::value_error("input: this renderer's volume was made from arrays or yt, not read from a file");
        if (!py::isinstance<py::str>(value) && !py::hasattr(value, "__fspath__"))
            throw py::type_error(
                strCat("input: expected a path, got ", std::string(py::str(py::type::of(value).attr("__name__")))));
        session::PictureDescription d;
        d.session = session();
        d.session.input = py::str(py::module_::import("os").attr("fspath")(value)).cast<std::string>();
        onDevice([&](render::Renderer& r) {
            InputFileRecorder recorder;
            std::shared_ptr<const scene::Volume> volume = session::loadVolume(d.session);
            std::vector<NamedPath> files = recorder.files("the volume's data");
            picture::Picture p = picture::makePicture(*mCtx, std::move(volume), d, {.shaders = r.shaders()});
            mPicture = std::move(p);  // r is gone from here on
            mDataFiles = std::move(files);
            mFirstFrame.reset();
        });
    }
    const scene::RenderSettings& settings() const { return open().renderer->settings(); }
    scene::Camera camera() const { return settings().camera; }
    void setCamera(const scene::Camera& c) {
        editSettings([&](scene::RenderSettings& s) { s.camera = c; });
    }
    PyTf tf() const { return {session().tf}; }
    void setTf(const PyTf& tf) {
        locked([&] { mPicture.setTransferFunction(tf.channels); });
    }
    std::string tfColors() const { return scene::tfColorsName(session().tfColors); }
    void setTfColors(const py::object& o) {
        const scene::TfColors c =
            scene::parseTfColors(keywordArg<std::string>(o, "tf_colors", "'srgb' or 'linear'"), "tf_colors");
        locked([&] { mPicture.setTfColors(c); });
    }
    // Settings edited by `edit` on a copy, validated, then applied (the renderer redoes what the
    // invalidation rule says); an invalid value changes nothing.
    template <typename Edit>
    void editSettings(Edit edit) {
        // Read under the lock: a first frame being made in another thread (the widget's) holds it
        // while the renderer is switched to dvr; a copy read then wrote dvr back for good.
        scene::RenderSettings s = onDevice([](render::Renderer& r) { return r.settings(); });
        edit(s);
        scene::validateSettings(s);
        locked([&] { mPicture.commit({.settings = s}); });
    }
    // A setting of session::settingTable(): read from the picture, or edited as the command line
    // and the session file would take it (the settings through editSettings, the structure's
    // through a structure commit).
    py::object setting(const session::Setting& st) const { return settingToPython(st, session()); }
    void setSetting(const session::Setting& st, const py::object& o) {
        session::Session given;
        setSettingFromPython(st, o, given);  // checked before anything changes
        if (st.section == "structure") {
            session::Session next;
            next.structure = open().described.structure;
            copySetting(st, given, next);
            commitStructure(next.structure);
            return;
        }
        editSettings([&](scene::RenderSettings& rs) {
            session::Session now;
            now.settings = rs;
            copySetting(st, given, now);
            rs = now.settings;
        });
    }
    // Structure settings of session::settingTable() by keyword (None: as they are), committed at once.
    void setStructure(const std::vector<std::pair<const char*, py::object>>& given) {
        session::Session next;
        next.structure = open().described.structure;
        for (const auto& [keyword, o] : given)
            if (!o.is_none()) setSettingFromPython(*session::settingForKeyword(keyword), o, next);
        commitStructure(next.structure);
    }
    // The structure as requested, refused (resolved for the device) before the device lock is taken.
    void commitStructure(const scene::StructureConfig& c) {
        scene::StructureConfig resolved = c;
        picture::resolveStructure(*mCtx, resolved);
        locked([&] { mPicture.commit({.structure = c}); });
    }
    py::dict structure() const {
        const scene::StructureConfig& c = open().renderer->config();
        py::dict d;
        d["traversal"] = scene::traversalName(c.traversal);
        d["sampler"] = scene::samplerName(c.sampler);
        d["backend"] = scene::backendName(c.backend);
        d["backend_requested"] = scene::backendName(session().structure.backend);
        d["grid"] = c.grid;
        d["kd_leaves"] = c.kdLeaves;
        d["sub_majorants"] = scene::subMajorantsName(c.subMajorants);
        return d;
    }

    // ---- accumulation ----
    void reset() {
        locked([&] { mPicture.renderer->resetAccumulation(); });
    }
    uint32_t spp() const { return open().renderer->accumulatedSpp(); }
    // Adds n samples per pixel to the current estimate in chunks of about a quarter second, serving
    // signals (Ctrl-C) and `progress(done, n)` between chunks with the GIL held, and other threads'
    // calls in turn (FairMutex: a widget on the same renderer goes on refreshing).
    void accumulate(const py::object& count, const py::object& progress) {
        accumulateChunks(countArg(count, "n"), progress, false);
    }
    // The chunks of accumulate(), and of render() (`restart`: the estimate reset under the first
    // chunk's lock, so that it ends with exactly n samples). The call counts the image's samples, not
    // its own: samples another thread adds meanwhile count, and an edit from another thread that
    // restarts the estimate restarts the count, so the call ends with the image at n samples of the
    // picture as it then is (issue 52, point 15).
    void accumulateChunks(uint32_t n, const py::object& progress, bool restart) {
        open();
        uint32_t target = 0;             // the image's samples when this call is done
        std::optional<uint64_t> resets;  // the estimate's resets when this call last worked on it
        for (uint32_t done = 0; done < n;) {
            uint32_t spp = 0;
            {
                py::gil_scoped_release release;
                std::lock_guard lock(mMutex);
                if (mClosed) break;  // closed by another thread between chunks
                render::Renderer& r = *mPicture.renderer;
                if (restart && !resets) r.resetAccumulation();
                if (!resets) {
                    target = restart ? n : r.accumulatedSpp() + n;
                } else if (*resets != r.updateCounts().accumulationResets) {
                    target = n;  // restarted meanwhile
                }
                if (r.accumulatedSpp() < target) accumulateChunk(r, target - r.accumulatedSpp());
                resets = r.updateCounts().accumulationResets;
                spp = r.accumulatedSpp();
            }
            const uint32_t was = done;
            done = n - (target - std::min(spp, target));
            requireNoValidationErrors();
            if (PyErr_CheckSignals() != 0) throw py::error_already_set();
            if (!progress.is_none() && done > was) progress(done, n);
        }
    }
    // One chunk of at most `most` samples per pixel (the device lock held): whole samples where
    // they fit about a quarter second, else tiles of rows.
    void accumulateChunk(render::Renderer& r, uint32_t most) {
        const uint32_t height = uint32_t(r.settings().height);
        uint32_t rows = 0;
        Timer t;
        const double perSample = mSecondsPerRow * double(height);
        if (mSecondsPerRow > 0 && perSample < kChunkSeconds && r.rowsDone() == 0) {
            const uint32_t k = std::min(most, uint32_t(std::clamp(kChunkSeconds / perSample, 1.0, 64.0)));
            r.accumulate(k, {}, k);
            rows = k * height;
        } else {
            // Tiles of rows: the first sample (its cost unknown), and samples slower than a chunk.
            rows = mSecondsPerRow > 0 ? uint32_t(std::clamp(kChunkSeconds / mSecondsPerRow, 1.0, double(height)))
                                      : std::min(height, 8u);
            rows = std::min(rows, height - r.rowsDone());
            r.accumulateRows(rows);
        }
        const double perRow = t.seconds() / double(std::max(rows, 1u));
        mSecondsPerRow = mSecondsPerRow > 0 ? 0.5 * (mSecondsPerRow + perRow) : perRow;
    }
    py::array_t<float> render(const py::object& spp, const py::object& progress, const py::object& legend,
                              const py::object& until) {
        const bool withLegend = !legend.is_none() && keywordArg<bool>(legend, "legend", "True, False or None");
        const uint32_t n = spp.is_none() ? (session().spp > 0 ? session().spp : 64) : countArg(spp, "spp");
        if (until.is_none()) {
            accumulateChunks(n, progress, true);
            return imageArray(picture(withLegend));
        }
        reset();
        // As render --until-error: checks at scene::kFirstNoiseCheckSpp and at each doubling, spp the cap.
        const double target = keywordArg<double>(until, "until", "a number in (0, 1]");
        if (!(target > 0 && target <= 1))
            throw py::value_error(strCat("until: ", formatDouble(target), " is outside (0, 1]"));
        if (n < 2) throw py::value_error(strCat("until: needs spp of at least 2 as its cap (got ", n, ")"));
        for (uint32_t k; (k = scene::nextNoiseBatch(output(), n, target)) > 0;) accumulate(py::int_(k), progress);
        return imageArray(picture(withLegend));
    }
    // The image's noise so far (scene::meanRelativeError); None below 2 spp.
    py::object noise() const {
        const scene::RenderOutput out = output();
        return out.spp < 2 ? py::object(py::none()) : py::object(py::float_(scene::meanRelativeError(out)));
    }
    scene::RenderOutput output() const {
        return onDevice([](render::Renderer& r) { return r.output(); });
    }
    // ---- the colour legend (session/legend_image.h: the CLI's --legend drawing) ----
    // `legend` True/False, or None for the session's setting (Renderer(legend=True), .legend).
    bool legendWanted(const py::object& legend) const {
        return legend.is_none() ? session().legend.show : keywordArg<bool>(legend, "legend", "True, False or None");
    }
    // The picture so far, with the legend drawn at its side or over it when `withLegend`. Before
    // any sample it is the first frame (firstFrame), not a black image.
    Image picture(bool withLegend) const { return pictureOf(output(), withLegend); }
    Image pictureOf(const scene::RenderOutput& out, bool withLegend) const {
        Image mean = out.spp > 0 ? out.mean : firstFrame().image;  // before any sample: the first frame
        if (!withLegend) return mean;
        const session::Session s = session();
        if (!mFont || !(mFontFor == s.legend.font)) {
            mFont = session::openLegendFont(s.legend);
            mFontFor = s.legend.font;
        }
        const std::string& units = mPicture.volume->field().units;
        session::checkLegendFits(s, units, *mFont);
        return session::drawLegend(mean, session::legendContent(s, units), s.legend.place, *mFont);
    }
    session::Legend legend() const { return session().legend; }
    template <typename Edit>
    void editLegend(Edit edit) {
        session::Legend l = legend();
        edit(l);
        session::checkLegendText(l);
        locked([&] { mPicture.described.legend = l; });
    }

    // Arrays (image, render) are the picture alone unless legend=True: they match variance()'s shape.
    py::array_t<float> image(const py::object& legend) const {
        return imageArray(picture(!legend.is_none() && keywordArg<bool>(legend, "legend", "True, False or None")));
    }
    py::array_t<float> variance() const {
        const scene::RenderOutput out = output();
        if (out.spp < 2)
            throw py::value_error("variance needs at least 2 samples per pixel (have " + std::to_string(out.spp) + ")");
        const std::vector<float> v = scene::varianceOfMean(out);
        py::array_t<float> a({py::ssize_t(out.mean.height), py::ssize_t(out.mean.width), py::ssize_t(3)});
        std::memcpy(a.mutable_data(), v.data(), v.size() * sizeof(float));
        return a;
    }
    py::object stats() const {
        const scene::RenderOutput out = output();
        const std::string text = picture::renderStats(mPicture, out).dump();
        return py::module_::import("json").attr("loads")(text);
    }
    std::vector<std::string> notes() const { return open().report.notes; }
    // Outputs never replace a file the renderer's data set was read from (as the CLI refuses
    // -o onto an input); everything else is checkOutputs' and AtomicFileWriter's policy.
    // legend None: drawn into PNGs where the session has it on (other formats as they are, as the
    // CLI does with a session's legend); True: a PNG is required.
    void save(const fs::path& path, const py::object& legend) const {
        checkOutputs({{"save", path}}, mDataFiles);
        std::string ext = path.extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
        if (!legend.is_none() && legendWanted(legend) && ext != ".png")
            throw py::value_error("legend: only PNG images get a legend (save to a .png, or legend=False)");
        writeImage(path, picture(legendWanted(legend) && ext == ".png"));
    }
    // One state of the image, read together (the widget's status counted samples in one call and
    // showed the image of another: "16/64" over 72): (spp, PNG bytes, mean standard error or None);
    // (0, None, None) while the image has no sample (no first frame is made for it).
    py::tuple snapshot(const py::object& legend) const {
        const scene::RenderOutput out = output();
        if (out.spp == 0) return py::make_tuple(0, py::none(), py::none());
        const std::vector<uint8_t> bytes = pngBytes(pictureOf(out, legendWanted(legend)));
        return py::make_tuple(out.spp, py::bytes(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
                              out.spp >= 2 ? py::object(py::float_(meanStandardError(out))) : py::object(py::none()));
    }
    // What a front end that keeps the first frame on screen shows (scene/preview_hold.h: the
    // widget): the estimate once its noise is as low as this picture's first frame's (or below the
    // no-grain level, or at `limit` spp), else the first frame. hold=False: the estimate whenever it
    // has a sample. A dict: spp, png (None with nothing to show), error (mean standard error),
    // noise (mean relative standard error, None below 2 spp), shown ("estimate", "first frame" or
    // None) and first_frame_noise (None without a first frame of this picture).
    py::dict shown(uint32_t limit, bool hold, const py::object& legend) const {
        const scene::RenderOutput out = output();
        scene::PreviewHold rule;
        py::dict d;
        d["first_frame_noise"] = py::none();
        if (hold && firstFrameCurrent()) {
            rule.previewReady(mFirstFrame->frame.noise);
            d["first_frame_noise"] = mFirstFrame->frame.noise;
        }
        const double noise = out.spp >= 2 ? scene::meanRelativeError(out) : -1;
        if (noise >= 0 && rule.hasPreview()) rule.estimateMeasured(out.spp, noise);
        const scene::Shown shown = rule.shown(out.spp, limit);
        d["spp"] = out.spp;
        d["noise"] = noise >= 0 ? py::object(py::float_(noise)) : py::object(py::none());
        d["error"] = out.spp >= 2 ? py::object(py::float_(meanStandardError(out))) : py::object(py::none());
        d["shown"] = py::none();
        d["png"] = py::none();
        if (shown == scene::Shown::Nothing) return d;
        d["shown"] = shown == scene::Shown::Preview ? "first frame" : "estimate";
        // pictureOf shows the first frame for an output without samples.
        const Image image =
            pictureOf(shown == scene::Shown::Preview ? scene::RenderOutput{} : out, legendWanted(legend));
        const std::vector<uint8_t> bytes = pngBytes(image);
        d["png"] = py::bytes(reinterpret_cast<const char*>(bytes.data()), bytes.size());
        return d;
    }
    py::bytes png(const py::object& legend) const {
        const std::vector<uint8_t> bytes = pngBytes(picture(legendWanted(legend)));
        return py::bytes(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    }
    void saveSession(const fs::path& path) const {
        session::Session s = session();
        s.input = s.input.empty() ? s.input : fs::absolute(s.input).lexically_normal().string();
        if (s.input.empty()) throw py::value_error(noSessionReason);
        checkOutputs({{"save_session", path}}, mDataFiles);
        session::saveSession(path, s);
    }
    void close() {
        std::lock_guard lock(mMutex);
        mPicture.renderer.reset();
        mPicture.volume.reset();
        mClosed = true;
    }
    bool closed() const { return mClosed; }
    // "Renderer(DD0018 'Density', 256x256 ms, tf 'ramp' over [-31, -26.5], density_scale 1, 16 spp so
    // far, mean standard error 0.0021, grid-dda/grid/sw)".
    std::string repr() const {
        if (mClosed || !mPicture.renderer) return "Renderer(closed)";
        const session::Session s = session();
        const scene::RenderSettings& rs = settings();
        const scene::TransferFunction tf = s.tf.merged();
        const scene::StructureConfig& c = mPicture.renderer->config();
        std::string noise;
        const scene::RenderOutput out = output();
        if (out.spp >= 2) noise = ", mean standard error " + g4(meanStandardError(out));
        const picture::FirstFrame* f = shownFirstFrame();
        const std::string first = f ? strCat(" (shown: the dvr first frame, ", picture::kFirstFrameSpp, " spp, dt ",
                                             g4(f->dt), ", noise ", g4(f->noise), ")")
                                    : std::string();
        return strCat("Renderer(", mPicture.volume->model.source, " '", mPicture.volume->field().name, "', ", rs.width,
                      "x", rs.height, " ", scene::modeName(rs.mode), ", tf '", s.tf.name, "' over [",
                      g4(tf.firstPosition()), ", ", g4(tf.lastPosition()), "], density_scale ", g4(rs.densityScale),
                      ", ", out.spp, " spp so far", noise, first, ", ", scene::traversalName(c.traversal), "/",
                      scene::samplerName(c.sampler), "/", scene::backendName(c.backend), ")");
    }
    std::string noSessionReason;  // why save_session cannot name a file (a volume from arrays or yt)

    // The first frame (picture/first_frame.h): what a renderer with no sample shows (inline,
    // image(), save()): the same picture ray-marched, clean in about a second where path tracing a
    // haze is still grainy at 16 spp (docs/python.md section 1). The renderer keeps its own mode
    // and no sample, so render() and accumulate() path-trace from scratch and refine it. Kept
    // until an edit resets the image.
    struct ShownFirstFrame {
        picture::FirstFrame frame;
        uint64_t resets = 0;  // the renderer's accumulationResets after it was made
    };
    // Whether the last first frame made is of the renderer's current picture (no edit since).
    bool firstFrameCurrent() const {
        return mFirstFrame && mFirstFrame->resets == mPicture.renderer->updateCounts().accumulationResets;
    }
    const picture::FirstFrame& firstFrame() const {
        open();
        if (firstFrameCurrent()) return mFirstFrame->frame;
        onDevice([&](render::Renderer& r) {
            ShownFirstFrame shown{picture::renderFirstFrame(r)};
            requireNoValidationErrors();
            shown.resets = r.updateCounts().accumulationResets;
            mFirstFrame = std::move(shown);
        });
        return mFirstFrame->frame;
    }
    // The first frame shown while the renderer holds no sample: {"mode", "spp", "dt", "noise",
    // "gpu_seconds", "frames"}; None before one is shown and once the image has samples.
    const picture::FirstFrame* shownFirstFrame() const {
        if (mClosed || !mPicture.renderer || mPicture.renderer->accumulatedSpp() > 0 || !firstFrameCurrent())
            return nullptr;
        return &mFirstFrame->frame;
    }
    py::object firstFrameInfo() const {
        const picture::FirstFrame* f = shownFirstFrame();
        if (!f) return py::none();
        py::dict d;
        d["mode"] = "dvr";
        d["spp"] = picture::kFirstFrameSpp;
        d["dt"] = f->dt;
        d["noise"] = f->noise;
        d["gpu_seconds"] = f->gpuSeconds;
        d["frames"] = f->frames;
        return d;
    }

private:
    static constexpr double kChunkSeconds = 0.25;

    // The mean over pixels and channels of the standard error of the mean (out.spp >= 2).
    static double meanStandardError(const scene::RenderOutput& out) {
        const std::vector<float> var = scene::varianceOfMean(out);
        double sum = 0;
        for (float x : var) sum += std::sqrt(std::max(x, 0.0f));
        return sum / double(std::max<size_t>(var.size(), 1));
    }

    // As the CLI: with validation on, any validation error fails the call (its message went to
    // stderr when it happened).
    void requireNoValidationErrors() const {
        AMRVK_CHECK(mCtx->validationErrors() == 0, "Vulkan validation reported ", mCtx->validationErrors(),
                    " error(s); last: ", mCtx->lastValidationMessage());
    }

    const picture::Picture& open() const {
        if (mClosed || !mPicture.renderer) throw py::value_error("the renderer is closed");
        return mPicture;
    }
    template <typename F>
    void locked(F f) {
        onDevice([&](render::Renderer&) { f(); });
    }
    // f(renderer) with the GIL released and the device lock held, the renderer checked open under
    // the lock: close() from another thread takes the same lock, so it cannot free the renderer
    // between the check and the call (it did: SIGSEGV in PathTracePass::read).
    template <typename F>
    std::invoke_result_t<F, render::Renderer&> onDevice(F f) const {
        open();
        py::gil_scoped_release release;
        std::lock_guard lock(mMutex);
        if (mClosed || !mPicture.renderer) throw py::value_error("the renderer is closed");
        return f(*mPicture.renderer);
    }

    std::shared_ptr<gpu::Context> mCtx;  // outlives the picture (declared first)
    std::vector<NamedPath> mDataFiles;   // outputs refuse these
    picture::Picture mPicture;
    mutable python::FairMutex mMutex;     // one device call at a time, in the order they came (the GIL is
                                          // released around them)
    mutable std::unique_ptr<Font> mFont;  // the legend's, opened when first drawn
    mutable std::string mFontFor;         // the legend.font it was opened for
    double mSecondsPerRow = 0;            // measured, for chunk sizes
    mutable std::optional<ShownFirstFrame> mFirstFrame;  // the last first frame made (firstFrame)
    bool mClosed = false;
};

// Renderer(volume, tf=None, camera=None, **options): each argument checked for its type first.
std::shared_ptr<PyRenderer> makeRenderer(const py::object& volumeObj, const py::object& tfObj,
                                         const py::object& cameraObj, const py::kwargs& kw) {
    if (!py::isinstance<PyVolume>(volumeObj))
        throw py::type_error("volume: expected an amrvk.Volume, got " +
                             py::repr(volumeObj).cast<std::string>().substr(0, 60));
    const PyVolume& volume = volumeObj.cast<const PyVolume&>();
    const std::optional<PyTf> tf =
        tfObj.is_none() ? std::nullopt
                        : std::optional<PyTf>(keywordArg<PyTf>(tfObj, "tf", "an amrvk.TransferFunction or None"));
    const std::optional<scene::Camera> camera =
        cameraObj.is_none()
            ? std::nullopt
            : std::optional<scene::Camera>(keywordArg<scene::Camera>(cameraObj, "camera", "an amrvk.Camera or None"));
    const session::PictureDescription d = describe(volume, tf, camera, kw);
    gpu::ContextOptions co = contextOptions(kw);
    co.requireRayQuery = d.session.structure.backend == scene::Backend::Rq;
    const fs::path shaderDir = kw.contains("shader_dir") && !kw["shader_dir"].is_none()
                                   ? fs::path(py::str(kw["shader_dir"]).cast<std::string>())
                                   : fs::path();
    const bool quiet = kw.contains("quiet") && keywordArg<bool>(kw["quiet"], "quiet", "True or False");
    std::shared_ptr<gpu::Context> ctx;
    {
        py::gil_scoped_release release;
        ctx = contextFor(co);
    }
    auto r = std::make_shared<PyRenderer>(std::move(ctx), volume.volume, d, shaderDir, quiet, volume.files);
    r->noSessionReason = volume.noFileReason();
    return r;
}

std::shared_ptr<PyRenderer> rendererFromSession(const fs::path& path, const py::kwargs& kw) {
    session::PictureDescription d;
    d.session = session::loadSession(path);
    std::shared_ptr<const scene::Volume> volume;
    std::vector<NamedPath> files;
    {
        py::gil_scoped_release release;
        InputFileRecorder recorder;
        volume = session::loadVolume(d.session);
        files = recorder.files("the volume's data");
    }
    gpu::ContextOptions co = contextOptions(kw);
    co.requireRayQuery = d.session.structure.backend == scene::Backend::Rq;
    const bool quiet = kw.contains("quiet") && keywordArg<bool>(kw["quiet"], "quiet", "True or False");
    std::shared_ptr<gpu::Context> ctx;
    {
        py::gil_scoped_release release;
        ctx = contextFor(co);
    }
    return std::make_shared<PyRenderer>(std::move(ctx), std::move(volume), d, fs::path(), quiet, std::move(files));
}

// Renderer: construction, accumulation, the image and the structure.
py::class_<PyRenderer, std::shared_ptr<PyRenderer>> bindRenderer(py::module_& m) {
    return py::class_<PyRenderer, std::shared_ptr<PyRenderer>>(m, "Renderer",
                                                               "a path-traced picture of a volume on a Vulkan device")
        .def(py::init(&makeRenderer), py::arg("volume"), py::arg("tf") = py::none(), py::arg("camera") = py::none(),
             "options: amrvk render's, with underscores (docs/python.md)")
        .def_property("input", &PyRenderer::input, &PyRenderer::setInput,
                      "the data set shown (None for arrays or yt); set another of a series (a path) to show it with "
                      "the same camera, TF, settings and structure (the image starts again)")
        .def_static("from_session", &rendererFromSession, py::arg("path"),
                    "the picture a session file describes (amrvk view's, amrvk render --session's)")
        .def("render", &PyRenderer::render, py::arg("spp") = py::none(), py::arg("progress") = py::none(),
             py::arg("legend") = py::none(), py::arg("until") = py::none(),
             "from scratch: spp samples per pixel (default the session's), returns image(legend); until=E stops "
             "once the noise (mean relative standard error of the visible pixels) is at most E, spp the cap")
        .def_property_readonly("first_frame", &PyRenderer::firstFrameInfo,
                               "while the image has no sample and its first frame was shown (inline, image(), "
                               "save()): {'mode': 'dvr', 'spp', 'dt', 'noise', 'gpu_seconds', 'frames'}; else None")
        .def_property_readonly(
            "noise", &PyRenderer::noise,
            "the image's noise: mean relative standard error of its visible pixels (None below 2 spp)")
        .def("accumulate", &PyRenderer::accumulate, py::arg("n"), py::arg("progress") = py::none(),
             "n more samples per pixel, continuing the same estimate")
        .def("reset", &PyRenderer::reset)
        .def("image", &PyRenderer::image, py::arg("legend") = py::none(),
             "the mean so far: float32 (height, width, 4), row 0 = top, linear radiance, alpha 1; legend=True: "
             "with the colour legend drawn (wider with legend_place 'side')")
        .def("variance", &PyRenderer::variance, "variance of the mean per pixel: float32 (height, width, 3)")
        .def_property_readonly("spp", &PyRenderer::spp)
        .def_property_readonly("stats", &PyRenderer::stats, "amrvk render --json's content for the image so far")
        .def_property_readonly("notes", &PyRenderer::notes, "what was fitted to the data, one line each")
        .def_property_readonly("structure", &PyRenderer::structure)
        .def(
            "set_structure",
            [](PyRenderer& r, const py::object& traversal, const py::object& sampler, const py::object& backend,
               const py::object& grid, const py::object& kdLeaves, const py::object& subMajorants) {
                r.setStructure({{"traversal", traversal},
                                {"sampler", sampler},
                                {"backend", backend},
                                {"grid", grid},
                                {"kd_leaves", kdLeaves},
                                {"sub_majorants", subMajorants}});
            },
            py::arg("traversal") = py::none(), py::arg("sampler") = py::none(), py::arg("backend") = py::none(),
            py::arg("grid") = py::none(), py::arg("kd_leaves") = py::none(), py::arg("sub_majorants") = py::none())
        .def_property("camera", &PyRenderer::camera,
                      [](PyRenderer& r, const py::object& c) {
                          r.setCamera(keywordArg<scene::Camera>(c, "camera", "an amrvk.Camera"));
                      })
        .def_property(
            "tf", &PyRenderer::tf,
            [](PyRenderer& r, const py::object& t) { r.setTf(keywordArg<PyTf>(t, "tf", "an amrvk.TransferFunction")); })
        .def_property("tf_colors", &PyRenderer::tfColors, &PyRenderer::setTfColors,
                      "what the TF's colours mean: 'srgb' (display colours, as matplotlib, yt and ParaView; the "
                      "default) or 'linear' (albedo as given)");
}

// Renderer: the picture's settings as properties (each edit through editSettings).
void bindRendererSettings(py::class_<PyRenderer, std::shared_ptr<PyRenderer>>& c) {
    // Every setting of session::settingTable() as a property of its keyword, with its help.
    for (const session::Setting& st : session::settingTable()) {
        if (!st.pythonProperty || st.kind == session::SettingKind::Compound) continue;  // a property of its own
        c.def_property(
            std::string(st.keyword).c_str(), [&st](const PyRenderer& r) { return r.setting(st); },
            [&st](PyRenderer& r, const py::object& o) { r.setSetting(st, o); },
            strCat(st.help, st.unit.empty() ? "" : strCat(" (", st.unit, ")"), "; as ", st.option).c_str());
    }
    c.def_property(
         "size", [](const PyRenderer& r) { return py::make_tuple(r.settings().width, r.settings().height); },
         [](PyRenderer& r, const py::object& o) {
             const auto wh = keywordArg<std::pair<py::object, py::object>>(o, "size", "(width, height)");
             const int w = int(wholeArg(wh.first, "size: width", 1, scene::kMaxImageSide));
             const int h = int(wholeArg(wh.second, "size: height", 1, scene::kMaxImageSide));
             r.editSettings([&](auto& s) {
                 s.width = w;
                 s.height = h;
             });
         },
         "(width, height) in pixels, each in [1, 16384] as --size")
        .def_property(
            "crop", [](const PyRenderer& r) { return cropObject(r.settings().cut.crop); },
            [](PyRenderer& r, const py::object& o) { r.editSettings([&](auto& s) { s.cut.crop = cropOf(o); }); },
            "cut-away box (lo, hi) in world space, or None; the medium outside is empty (docs/cut-aways.md)")
        .def_property(
            "clip", [](const PyRenderer& r) { return clipObject(r.settings().cut.clips); },
            [](PyRenderer& r, const py::object& o) { r.editSettings([&](auto& s) { s.cut.clips = clipsOf(o); }); },
            "clip planes [(point, normal), ...] in world space; the side each normal points to is removed (at most 4)")
        .def_property(
            "lights", [](const PyRenderer& r) { return r.settings().lights; },
            [](PyRenderer& r, const py::object& o) {
                const auto l = keywordArg<std::vector<scene::Light>>(o, "lights", kLights);
                r.editSettings([&](auto& s) { s.lights = l; });
            })
        .def_property(
            "ambient", [](const PyRenderer& r) { return list3(r.settings().ambient); },
            [](PyRenderer& r, const py::object& o) {
                const glm::dvec3 a = vec3(keywordArg<std::vector<double>>(o, "ambient", kThree), "ambient");
                r.editSettings([&](auto& s) { s.ambient = a; });
            })
        .def_property(
            "background",
            [](const PyRenderer& r) -> py::object {
                const auto& b = r.settings().background;
                return b ? py::cast(list3(*b)) : py::none();
            },
            [](PyRenderer& r, const py::object& o) {
                const std::optional<glm::dvec3> b =
                    o.is_none() ? std::nullopt
                                : std::optional<glm::dvec3>(
                                      vec3(keywordArg<std::vector<double>>(o, "background", kThree), "background"));
                r.editSettings([&](auto& s) { s.background = b; });
            },
            "radiance seen by rays that escape without scattering; None = the ambient light");
}

// Renderer: output (files, PNG bytes, the session file, the widget's snapshot), close and repr.
void bindRendererOutput(py::class_<PyRenderer, std::shared_ptr<PyRenderer>>& c) {
    c.def("save", &PyRenderer::save, py::arg("path"), py::arg("legend") = py::none(),
          "the image so far: .png (sRGB), .exr or .pfm (linear); the legend in PNGs (legend None: the renderer's)")
        .def("save_session", &PyRenderer::saveSession, py::arg("path"),
             "the picture as a session file (amrvk view --session, amrvk render --session)")
        .def("_snapshot", &PyRenderer::snapshot, py::arg("legend") = py::none(),
             "(spp, png bytes, mean standard error or None) of one state of the image (the widget's status); "
             "(0, None, None) without a sample")
        .def("_shown", &PyRenderer::shown, py::arg("limit"), py::arg("hold") = true, py::arg("legend") = py::none(),
             "what the widget shows: the first frame until the estimate is as clean (or at limit spp), then the "
             "estimate; a dict: spp, png, error, noise, shown, first_frame_noise")
        .def("png", &PyRenderer::png, py::arg("legend") = py::none(),
             "the image so far as PNG bytes (what save writes to a .png)")
        .def("close", &PyRenderer::close, "free the device memory; every later call raises ValueError")
        .def_property_readonly("closed", &PyRenderer::closed)
        .def("__repr__", &PyRenderer::repr);
}

// Renderer: the colour legend's settings (the session's, as --legend, --legend-place, ...).
void bindRendererLegend(py::class_<PyRenderer, std::shared_ptr<PyRenderer>>& c) {
    c.def_property(
         "legend", [](const PyRenderer& r) { return r.legend().show; },
         [](PyRenderer& r, const py::object& o) {
             const bool show = keywordArg<bool>(o, "legend", "True or False");
             r.editLegend([&](session::Legend& l) { l.show = show; });
         },
         "the colour legend in PNGs and inline pictures (as --legend)")
        .def_property(
            "legend_place", [](const PyRenderer& r) { return std::string(session::legendPlaceName(r.legend().place)); },
            [](PyRenderer& r, const py::object& o) {
                const auto place = forKeyword("legend_place", [&] {
                    return session::parseLegendPlace(keywordArg<std::string>(o, "legend_place", "'side' or 'overlay'"));
                });
                r.editLegend([&](session::Legend& l) { l.place = place; });
            },
            "'side' (a strip right of the picture) or 'overlay' (over its lower right corner)")
        .def_property(
            "legend_title", [](const PyRenderer& r) { return r.legend().title; },
            [](PyRenderer& r, const py::object& o) {
                const std::string t = keywordArg<std::string>(o, "legend_title", kText);
                r.editLegend([&](session::Legend& l) { l.title = t; });
            },
            "the legend's title; '' = the field's name")
        .def_property(
            "legend_units", [](const PyRenderer& r) { return r.legend().units; },
            [](PyRenderer& r, const py::object& o) {
                const std::string u = keywordArg<std::string>(o, "legend_units", kText);
                r.editLegend([&](session::Legend& l) { l.units = u; });
            },
            "the units line under the legend's title; '' = the volume's own (Volume.units)");
}

}  // namespace

void bindRendererClass(py::module_& m) {
    auto renderer = bindRenderer(m);
    bindRendererSettings(renderer);
    bindRendererOutput(renderer);
    bindRendererLegend(renderer);
}

}  // namespace amrvk::python
