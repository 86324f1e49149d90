// amrvk render: path-trace an AMR data set on a Vulkan device; amrvk devices: list devices.
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <nlohmann/json.hpp>

#include "amr/readers.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "cli/ranks.h"
#include "cli/render_series.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/image_io.h"
#include "core/progress.h"
#include "core/stats.h"
#include "gpu/context.h"
#include "gpu/shader_library.h"
#include "picture/first_frame.h"
#include "picture/picture.h"
#include "render/renderer.h"
#include "session/legend_image.h"

#if AMRVK_MPI
#include "mpi/data_parallel.h"
#include "mpi/sample_parallel.h"
#endif

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace amrvk::cli {

namespace {

const char* kRenderHelp =
    "Unbiased volumetric path tracing of the input's field on a Vulkan device (samples per pixel "
    "accumulated over dispatches; --samples-per-invocation per GPU thread). Extinction = TF alpha "
    "x density scale per finest cell width; albedo = TF colour. Every majorant traversal x sample "
    "reconstruction structure of the paper is selectable; box hierarchies run as software BVHs "
    "(sw) or through VK_KHR_ray_query (rq). --session FILE renders a picture saved by the viewer "
    "(amrvk view), with any option given here on top. Several inputs (or a quoted glob pattern such as "
    "'plt*', expanded by amrvk, in natural order), --frames N --orbit 360 (a turntable of one input), a "
    "numbered -o (frames/f_%04d.png), a directory -o (frames/) or -o movie.mp4 (through ffmpeg) render a "
    "series of frames with one camera, TF range and settings; a re-run of the same command skips the "
    "frames already written (docs/movies.md). One picture with none of --mode, --spp, --dt, --until-error or --session "
    "is its first frame (see --first-frame: ray-marched, clean, seconds); any of them path-traces it (defaults below: "
    "ms, 64 spp). Series and mpirun path-trace by default.";

}  // namespace

int runDevices(const std::vector<std::string>& argv) {
    CLI::App app(
        "Lists every Vulkan device: index, name, type, driver, device-local memory, ray-query support, and why an "
        "unusable one is rejected.",
        "amrvk devices");
    setUpCommand(app);
    bool json = false;
    app.add_flag("--json", json, "print a JSON array");
    if (!parseCommandLine(app, argv)) return 0;
    auto devices = gpu::listDevices();
    if (json) {
        Json j = Json::array();
        for (const auto& d : devices)
            j.push_back({{"index", d.index},
                         {"name", d.name},
                         {"type", d.type},
                         {"driver", d.driver},
                         {"apiVersion", d.apiVersion},
                         {"deviceLocalBytes", d.deviceLocalBytes},
                         {"rayQuery", d.rayQuery},
                         {"shaderRoundingModeRTEFloat32", d.roundingModeRTEFloat32},
                         {"usable", d.usable},
                         {"rejectReason", d.rejectReason}});
        std::printf("%s\n", j.dump(2).c_str());
        return 0;
    }
    for (const auto& d : devices)
        std::printf("%u: %s (%s), driver %s, Vulkan %s, %.1f GiB device-local, ray query %s%s\n", d.index,
                    d.name.c_str(), d.type.c_str(), d.driver.c_str(), d.apiVersion.c_str(),
                    double(d.deviceLocalBytes) / (1 << 30), d.rayQuery ? "yes" : "no",
                    d.usable ? "" : (", unusable: " + d.rejectReason).c_str());
    if (devices.empty()) std::printf("no Vulkan devices\n");
    return 0;
}

namespace {

// The noise above which `render` says the picture is grainy (mean relative standard error of the
// visible pixels; the first frame's target, picture::kFirstFrameNoise, is 0.05).
constexpr double kGrainyNoise = 0.1;

// The options that choose the estimator: --first-frame chooses them itself, and with none of them
// (nor --session) one picture is its first frame.
constexpr std::array<const char*, 4> kEstimatorOptions = {"--mode", "--spp", "--dt", "--until-error"};

// The render command's options, bound by addRenderOptions.
struct RenderArgs {
    std::vector<std::string> inputs;
    std::string output = "amrvk.png", jsonFile, varianceFile, distribute = "samples";
    double untilError = 0;  // > 0: stop at this noise (--spp is the cap)
    bool firstFrame = false;  // the first frame instead of path tracing (picture/first_frame.h)
    bool firstFrameByDefault = false;  // nothing said how the picture is made: its first frame
    ReadArgs read;
    PictureArgs pic;
    DeviceArgs dev;
    SeriesArgs series;
};

// Registers render's options on `app`, bound to `a`, in --help's order.
void addRenderOptions(CLI::App& app, RenderArgs& a) {
    app.add_option("input", a.inputs,
                   "the data set: ExaBrick .cells, AMReX plotfile, Enzo parameter file, Chombo .hdf5, "
                   "Carpet .h5, RAMSES output directory, raw .raw (optional with --session); several, or a quoted glob pattern, "
                   "make a series")
        ->type_name("INPUT...");
    addReadOptions(app, a.read, false);
    addPictureOptions(app, a.pic);
    addSeriesOptions(app, a.series);
    app.add_option("-o,--output", a.output,
                   "out.png (tone-mapped sRGB), out.exr or out.pfm (linear float); a series: frames/f_%04d.png, "
                   "frames/ or movie.mp4")
        ->capture_default_str()
        ->type_name("FILE");
    app.add_option("--json", a.jsonFile, "write render statistics as JSON")->type_name("FILE");
    app.add_option("--variance", a.varianceFile,
                   "also write the per-pixel variance of the mean (rgb, from the samples' squares; needs --spp >= 2) "
                   "as .exr or .pfm: error bars for the image")
        ->type_name("FILE");
    app.add_option("--until-error", a.untilError,
                   "stop once the image's noise is at most E: the mean, over the visible pixels, of each pixel's "
                   "standard error over its value (0.02 = 2%); checked at 16 spp and at each doubling, --spp is the cap; "
                   "the spp reached and the noise are printed and in --json (spp, meanRelativeError)")
        ->check(interval(0, 1, true, false))
        ->type_name("E");
    app.add_flag("--first-frame", a.firstFrame,
                 "render the first frame Python and the viewer show before path tracing: the picture ray-marched "
                 "(dvr, 2 spp), its step made finer while its noise is above 0.05, within 1 s of GPU time; it "
                 "chooses the mode, samples and step (not with --mode, --spp, --dt or --until-error); the default "
                 "for one picture when none of those nor --session is given");
    app.add_option("--distribute", a.distribute,
                   "under mpirun: samples (every rank holds the data and renders a share of the samples) or "
                   "data (every rank reads and tracks only its box of space; ae, ss, ms; docs/mpi.md)")
        ->check(CLI::IsMember({"samples", "data"}))
        ->capture_default_str();
    addDeviceOptions(app, a.dev);
}

// One picture, checked before any work: its outputs (known image types, writable, distinct, none
// of them an input), its description and the legend's font (a missing font is one line, not a
// lost render).
struct PicturePlan {
    std::string input;  // empty with --session alone
    std::string ext;    // -o's extension
    std::vector<NamedPath> outputs;
    session::PictureDescription description;
    std::unique_ptr<Font> legendFont;  // null: no legend drawn
};

PicturePlan planPicture(const CLI::App& app, const RenderArgs& a, bool speaks) {
    PicturePlan p;
    p.input = a.inputs.empty() ? std::string() : a.inputs.front();
    p.ext = fs::path(a.output).extension().string();
    AMRVK_CHECK(p.ext == ".png" || p.ext == ".exr" || p.ext == ".pfm", "-o ", a.output,
                ": unknown image type (use .png, .exr or .pfm)");
    // Every output checked before any work: writable, distinct, none of them an input.
    const std::string varianceExt = fs::path(a.varianceFile).extension().string();
    AMRVK_CHECK(a.varianceFile.empty() || varianceExt == ".exr" || varianceExt == ".pfm", "--variance ", a.varianceFile,
                ": use .exr or .pfm (linear float)");
    p.outputs = {{"-o", a.output}, {"--json", a.jsonFile}, {"--variance", a.varianceFile}};
    checkOutputs(p.outputs, pictureInputs(app, p.input, a.pic));
    p.description = describePicture(app, p.input, a.read, a.pic);
    // A session's camera path describes a movie: one picture is its frame 0 (--camera: that camera).
    const session::CameraPath& path = p.description.session.cameraPath;
    if (!path.empty() && app.count("--camera") == 0) {
        p.description.session.settings.camera = path.cameraAt(0);
        if (speaks)
            std::fprintf(stderr,
                         "amrvk: the session's camera path has %u frames: rendering its frame 0 (-o movie.mp4 or "
                         "-o frames/f_%%04d.png renders them all)\n",
                         path.frameCount());
    }
    AMRVK_CHECK(a.varianceFile.empty() || p.description.session.spp >= 2, "--variance needs --spp of at least 2 (got ",
                p.description.session.spp, ")");
    // The legend's own options draw nothing without a legend (issue 52, point 9: they were ignored).
    if (!p.description.session.legend.show)
        for (const char* name : {"--legend-place", "--legend-title", "--legend-units", "--legend-font"})
            AMRVK_CHECK(app.count(name) == 0, name, " applies only with --legend (or a session whose legend is on)");
    // The legend's font is read before any work (a missing font is one line, not a lost render).
    if (p.description.session.legend.show) {
        AMRVK_CHECK(p.ext == ".png" || app.count("--legend") == 0, "--legend: only PNG images get a legend (-o ",
                    a.output, " keeps the linear radiance)");
        if (p.ext == ".png")
            p.legendFont = session::openLegendFont(p.description.session.legend);
        else if (speaks) std::fprintf(stderr, "amrvk: the session's legend is drawn into PNG images only\n");
    }
    return p;
}

// The data set as read: all of it, or (--distribute data under mpirun) this rank's part.
struct LoadedData {
    std::shared_ptr<const scene::Volume> volume;
#if AMRVK_MPI
    std::optional<mpi::DataPart> part;  // set with --distribute data
#endif
    double readSeconds = 0;  // reading alone, without the bricks' build
};

LoadedData loadData(const session::PictureDescription& description, [[maybe_unused]] mpi::World* world,
                    [[maybe_unused]] bool byData) {
    LoadedData data;
    Timer readTimer;
#if AMRVK_MPI
    if (byData) {
        data.part = mpi::loadPart(*world, description);
        data.volume = data.part->volume;
    } else
#endif
    {
        // One picture and nothing after it that reads the cells: they go once the bricks exist
        // (issue 31, point 7). Under mpirun the ranks compare cell counts; the dense sampler
        // rasterises the cells.
        const bool release = !world && description.session.structure.sampler != scene::SamplerKind::Dense;
        data.volume = session::loadVolume(description.session, {.releaseCells = release});
    }
    data.readSeconds = readTimer.seconds() - data.volume->bricks.buildSeconds;
    return data;
}

// The rendered image and, under mpirun, the ranks' report (null otherwise).
struct Rendered {
    scene::RenderOutput out;
    Json mpiReport;
    std::optional<picture::FirstFrame> firstFrame;  // --first-frame: how it was made
};

// Renders the picture alone, or this rank's share of a data- or sample-parallel render.
Rendered renderImage(picture::Picture& picture, [[maybe_unused]] const LoadedData& data,
                     [[maybe_unused]] mpi::World* world, double untilError, bool firstFrame,
                     const std::function<void(uint32_t, uint32_t)>& progress) {
    Rendered r;
    if (firstFrame) {  // one process (checked with the options)
        r.firstFrame = picture::renderFirstFrame(*picture.renderer, picture::AfterFirstFrame::Keep);
        r.out = picture.renderer->output();
        return r;
    }
#if AMRVK_MPI
    if (data.part) {
        world->checkpoint();  // every rank has its part and structures
        mpi::DataParallelResult d = mpi::renderDataParallel(
            *world, picture, *data.part,
            {{"readSeconds", data.readSeconds}, {"buildSeconds", picture.report.buildSeconds}}, progress);
        r.out = std::move(d.out);
        r.mpiReport = std::move(d.mpi);
    } else if (world) {
        mpi::SampleParallelResult share = mpi::renderSampleParallel(
            *world, picture, {{"readSeconds", data.readSeconds}, {"buildSeconds", picture.report.buildSeconds}},
            progress);
        r.out = std::move(share.out);
        r.mpiReport = std::move(share.mpi);
    } else
#endif
        r.out = untilError > 0 ? picture.renderUntil(untilError, progress) : picture.render(progress);
    return r;
}

// --json's statistics, the summary on stdout, and a warning on stderr when the image may be biased.
void reportRender(const RenderArgs& a, const picture::Picture& picture, const gpu::Context& ctx, const Rendered& r,
                  const picture::RenderTimes& times) {
    const scene::RenderOutput& out = r.out;
    // The statistics first: a --json that cannot be written ends the command before the summary
    // says "wrote" (the outputs are committed together after this).
    if (!a.jsonFile.empty()) {
        Json j = picture::renderStats(picture, out, times);
        if (!r.mpiReport.is_null()) j["mpi"] = r.mpiReport;
        if (r.firstFrame)  // how the first frame was made; "seconds" is its last frame's GPU time
            j["firstFrame"] = {{"dt", r.firstFrame->dt},
                               {"frames", r.firstFrame->frames},
                               {"gpuSeconds", r.firstFrame->gpuSeconds},
                               {"noiseTarget", picture::kFirstFrameNoise},
                               {"byDefault", a.firstFrameByDefault}};
        writeFileAtomic(a.jsonFile, j.dump(2) + "\n");
    }
    const scene::StructureConfig& config = picture.renderer->config();
    const scene::RenderSettings& rs = picture.renderer->settings();
    const auto& c = out.stats.counters;
    const double paths = double(out.stats.paths);
    // The noise of the picture (scene::meanRelativeError), with a hint where it shows as grain.
    std::string noiseNote;
    if (out.spp >= 2 && a.untilError == 0) {
        const double e = scene::meanRelativeError(out);
        char text[32];
        std::snprintf(text, sizeof text, "%.2g", e);
        noiseNote = strCat(", noise ", text);
        if (e > kGrainyNoise && rs.mode != scene::Mode::Dvr)
            noiseNote += ": grainy; more --spp, --until-error E, or --first-frame (ray-marched) for less";
    }
    std::printf("wrote %s (%dx%d, %u spp, %s, %s on %s) in %.2f s GPU, %.2f M paths/s%s\n", a.output.c_str(), rs.width,
                rs.height, out.spp, scene::modeName(rs.mode), config.labelWithSub().c_str(), ctx.deviceReport().name.c_str(),
                out.stats.gpuSeconds, out.stats.gpuSeconds > 0 ? paths / out.stats.gpuSeconds * 1e-6 : 0.0,
                noiseNote.c_str());
    if (r.firstFrame)
        std::printf("first frame: dvr at dt %g after %u frame%s (%.2f s GPU in all; its step is made finer while the "
                    "noise is above %g)\n",
                    r.firstFrame->dt, r.firstFrame->frames, r.firstFrame->frames == 1 ? "" : "s",
                    r.firstFrame->gpuSeconds, picture::kFirstFrameNoise);
    if (r.firstFrame && r.firstFrame->noise > picture::kFirstFrameNoise)
        std::printf(
            "first frame: stopped at noise %.2g, above %g, by its GPU budget (%g times its first frame, "
            "%g-%g s) or its finest step %g; --mode dvr --dt %g --spp 8 is finer and less noisy\n",
            r.firstFrame->noise, picture::kFirstFrameNoise, picture::kFirstFrameBudgetFactor,
            picture::kFirstFrameGpuSeconds, picture::kFirstFrameMaxGpuSeconds, picture::kFirstFrameMinDt,
            r.firstFrame->dt / 2);
    if (a.firstFrameByDefault)
        std::printf("the default picture is this first frame; path-trace it with --mode ms (or ae, ss), --spp N or "
                    "--until-error E\n");
    if (a.untilError > 0) {
        const double noise = scene::meanRelativeError(out);
        std::printf("noise %.4g (mean relative standard error of the visible pixels) at %u spp: %s\n", noise, out.spp,
                    noise <= a.untilError ? "at or below --until-error" : "above --until-error; --spp capped it");
    }
    if (c[shared::kCounterMajorantViolations] || c[shared::kCounterNanSamples] || c[shared::kCounterBounceLimitHits] ||
        c[shared::kCounterTrackingCapHits])
        std::fprintf(stderr,
                     "amrvk: warning: %llu majorant violations, %llu NaN samples, %llu paths hit the bounce "
                     "limit, "
                     "%llu tracking calls stopped at the step cap or below float resolution (biased: lower "
                     "--density-scale)\n",
                     (unsigned long long)c[shared::kCounterMajorantViolations],
                     (unsigned long long)c[shared::kCounterNanSamples],
                     (unsigned long long)c[shared::kCounterBounceLimitHits],
                     (unsigned long long)c[shared::kCounterTrackingCapHits]);
}

// One picture (not a series): planned, read, built on the device, rendered, written and reported.
int renderPicture(const CLI::App& app, const RenderArgs& a, mpi::World* world, bool speaks, const Timer& sinceStart) {
    PicturePlan plan = planPicture(app, a, speaks);
    LoadedData data = loadData(plan.description, world, a.distribute == "data");
    checkOutputs(plan.outputs, inputFilesRead());  // and none is a file the data set was read from
    gpu::ContextOptions co = a.dev.context;
#if AMRVK_MPI
    if (world) co.spread = uint32_t(world->localRank());  // one device per rank where a node has several
#endif
    co.requireRayQuery = plan.description.session.structure.backend == scene::Backend::Rq;
    gpu::Context ctx(co);
    picture::Picture picture = picture::makePicture(
        ctx, std::move(data.volume), plan.description,
        {.shaders = gpu::ShaderLibrary(a.dev.shaderDir),
         .note = [speaks](const std::string& line) {
             if (speaks) std::fprintf(stderr, "amrvk: %s\n", oneLineMessage(line).c_str());
         },
         // The first frame is dvr; else the estimator's mode (the session's, as fitted).
         .warmTracer = a.firstFrame || a.firstFrameByDefault
                           ? render::TracerVariant{scene::Mode::Dvr}
                           : render::TracerVariant::of(plan.description.session.settings)});
    picture.report.readSeconds = data.readSeconds;
    if (plan.legendFont)  // before the render
        session::checkLegendFits(picture.session(), picture.volume->field().units, *plan.legendFont);
    ProgressBar bar("render", "spp");
    Timer wall;
    double firstSampleSeconds = 0;
    auto progress = [&](uint32_t d, uint32_t t) {
        if (firstSampleSeconds == 0) firstSampleSeconds = sinceStart.seconds();
        bar.update(d, t);
    };
    const Rendered r =
        renderImage(picture, data, world, a.untilError, a.firstFrame || a.firstFrameByDefault, progress);
    bar.finish();
    const double wallSeconds = wall.seconds();
    AMRVK_CHECK(ctx.validationErrors() == 0, "Vulkan validation reported ", ctx.validationErrors(),
                " error(s); last: ", ctx.lastValidationMessage());
    if (!speaks) return 0;  // rank 0 writes the outputs of the job
    OutputTransaction outputs;  // -o, --variance and --json: all of them or none (issue 52, point 18)
    session::writePicture(a.output, r.out.mean, picture.session(), picture.volume->field().units,
                          plan.legendFont.get());
    if (!a.varianceFile.empty())
        writeImage(a.varianceFile,
                   scene::varianceImage(scene::varianceOfMean(r.out), r.out.mean.width, r.out.mean.height));
    reportRender(a, picture, ctx, r, {.wallSeconds = wallSeconds, .firstSampleSeconds = firstSampleSeconds});
    outputs.commit();
    return 0;
}

// One render; with `world` (mpirun) this rank's part of a sample- or data-parallel one: rank 0
// alone speaks and writes.
int renderOn(const std::vector<std::string>& argv, mpi::World* world) {
    const Timer sinceStart;  // time to the first sample: reading, validating, structures, device set-up
#if AMRVK_MPI
    const bool speaks = !world || world->rank() == 0;
#else
    const bool speaks = true;
#endif
    CLI::App app(kRenderHelp, "amrvk render");
    setUpCommand(app);
    RenderArgs a;
    addRenderOptions(app, a);
    if (!parseCommandLine(app, argv)) return 0;
    AMRVK_CHECK(world || app.count("--distribute") == 0,
                "--distribute: only under an MPI launcher (mpirun -n N amrvk render ...; docs/mpi.md)");
    AMRVK_CHECK(!world || a.untilError == 0,
                "--until-error: not under mpirun (the ranks would each stop at their own share's noise); give --spp");
    // The default picture (issue 33): one picture, made by one process, with nothing said about how
    // it is made (no --mode, --spp, --dt, --until-error or --session), is its first frame, the clean
    // picture Python and the viewer show first; any of those asks for the estimator as before.
    const bool series = isSeries(app, a.inputs, a.output);
    if (!series && app.count("--series-range") > 0 && speaks)
        std::fprintf(stderr,
                     "amrvk: --series-range: one input has one range; the option fixes a series' range "
                     "(several inputs, a pattern, --frames or --orbit) and changes nothing here\n");
    a.firstFrameByDefault = !a.firstFrame && !world && !series && app.count("--session") == 0 &&
                            std::none_of(kEstimatorOptions.begin(), kEstimatorOptions.end(),
                                         [&](const char* o) { return app.count(o) > 0; });
    if (a.firstFrame) {
        for (const char* given : kEstimatorOptions)
            AMRVK_CHECK(app.count(given) == 0, "--first-frame chooses the mode (dvr), the samples (2) and the step; "
                        "leave out ", given);
        AMRVK_CHECK(!world, "--first-frame: one process, not under mpirun");
    }
    if (series) {
        AMRVK_CHECK(a.untilError == 0, "--until-error renders one picture, not a series or a turntable; give --spp");
        AMRVK_CHECK(!a.firstFrame, "--first-frame renders one picture, not a series or a turntable");
        return renderSeries(
            app, {.inputs = a.inputs, .output = a.output, .jsonFile = a.jsonFile, .varianceFile = a.varianceFile},
            a.read, a.pic, a.series, a.dev, world);
    }
    return renderPicture(app, a, world, speaks, sinceStart);
}

}  // namespace

int runRender(const std::vector<std::string>& argv) {
    return runOnRanks("render", [&](mpi::World* world) { return renderOn(argv, world); });
}

}  // namespace amrvk::cli
