// amrvk render: path-trace an AMR data set on a Vulkan device; amrvk devices: list devices.
#include <unistd.h>

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
    "frames already written (docs/movies.md).";

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
    std::vector<std::string> inputs;
    std::string output = "amrvk.png", jsonFile;
    ReadArgs read;
    PictureArgs pic;
    DeviceArgs dev;
    SeriesArgs series;
    app.add_option("input", inputs,
                   "the data set: ExaBrick .cells, AMReX plotfile, Enzo parameter file, Chombo .hdf5, "
                   "RAMSES output directory, raw .raw (optional with --session); several, or a quoted glob pattern, "
                   "make a series")
        ->type_name("INPUT...");
    addReadOptions(app, read, false);
    addPictureOptions(app, pic);
    addSeriesOptions(app, series);
    app.add_option("-o,--output", output,
                   "out.png (tone-mapped sRGB), out.exr or out.pfm (linear float); a series: frames/f_%04d.png, "
                   "frames/ or movie.mp4")
        ->capture_default_str()
        ->type_name("FILE");
    app.add_option("--json", jsonFile, "write render statistics as JSON")->type_name("FILE");
    std::string varianceFile;
    app.add_option("--variance", varianceFile,
                   "also write the per-pixel variance of the mean (rgb, from the samples' squares; needs --spp >= 2) "
                   "as .exr or .pfm: error bars for the image")
        ->type_name("FILE");
    std::string distribute = "samples";
    app.add_option("--distribute", distribute,
                   "under mpirun: samples (every rank holds the data and renders a share of the samples) or "
                   "data (every rank reads and tracks only its box of space; ae, ss, ms; docs/mpi.md)")
        ->check(CLI::IsMember({"samples", "data"}))
        ->capture_default_str();
    addDeviceOptions(app, dev);
    if (!parseCommandLine(app, argv)) return 0;
    AMRVK_CHECK(world || app.count("--distribute") == 0,
                "--distribute: only under an MPI launcher (mpirun -n N amrvk render ...; docs/mpi.md)");
    [[maybe_unused]] const bool byData = distribute == "data";
    if (isSeries(app, inputs, output))
        return renderSeries(app, {.inputs = inputs, .output = output, .jsonFile = jsonFile, .varianceFile = varianceFile},
                            read, pic, series, dev, world);
    const std::string input = inputs.empty() ? std::string() : inputs.front();

    const std::string ext = fs::path(output).extension().string();
    AMRVK_CHECK(ext == ".png" || ext == ".exr" || ext == ".pfm", "-o ", output,
                ": unknown image type (use .png, .exr or .pfm)");
    // Every output checked before any work: writable, distinct, none of them an input.
    const std::string varianceExt = fs::path(varianceFile).extension().string();
    AMRVK_CHECK(varianceFile.empty() || varianceExt == ".exr" || varianceExt == ".pfm", "--variance ", varianceFile,
                ": use .exr or .pfm (linear float)");
    const std::vector<NamedPath> outputs = {{"-o", output}, {"--json", jsonFile}, {"--variance", varianceFile}};
    checkOutputs(outputs, pictureInputs(app, input, pic));
    session::PictureDescription description = describePicture(app, input, read, pic);
    AMRVK_CHECK(varianceFile.empty() || description.session.spp >= 2, "--variance needs --spp of at least 2 (got ",
                description.session.spp, ")");
    // The legend's font is read before any work (a missing font is one line, not a lost render).
    std::unique_ptr<Font> legendFont;
    if (description.session.legend.show) {
        AMRVK_CHECK(ext == ".png" || app.count("--legend") == 0, "--legend: only PNG images get a legend (-o ", output,
                    " keeps the linear radiance)");
        if (ext == ".png") legendFont = session::openLegendFont(description.session.legend);
        else if (speaks) std::fprintf(stderr, "amrvk: the session's legend is drawn into PNG images only\n");
    }
    Timer readTimer;
    std::shared_ptr<const scene::Volume> loaded;
#if AMRVK_MPI
    std::optional<mpi::DataPart> part;
    if (byData) {
        part = mpi::loadPart(*world, description);
        loaded = part->volume;
    } else
#endif
        loaded = session::loadVolume(description.session);
    const double readSeconds = readTimer.seconds() - loaded->bricks.buildSeconds;
    checkOutputs(outputs, inputFilesRead());  // and none is a file the data set was read from
    gpu::ContextOptions co = dev.context;
#if AMRVK_MPI
    if (world) co.spread = uint32_t(world->localRank());  // one device per rank where a node has several
#endif
    co.requireRayQuery = description.session.structure.backend == scene::Backend::Rq;
    gpu::Context ctx(co);
    picture::Picture picture =
        picture::makePicture(ctx, std::move(loaded), description,
                             {.shaders = gpu::ShaderLibrary(dev.shaderDir),
                              .note = [speaks](const std::string& line) {
                                  if (speaks) std::fprintf(stderr, "amrvk: %s\n", line.c_str());
                              }});
    picture.report.readSeconds = readSeconds;
    const session::Session& s = picture.session;
    if (legendFont) session::checkLegendFits(s, *legendFont);  // before the render
    render::Renderer& renderer = *picture.renderer;
    const scene::StructureConfig& config = renderer.config();
    const scene::RenderSettings& rs = renderer.settings();
    ProgressBar bar("render", "spp");
    Timer wall;
    double firstSampleSeconds = 0;
    auto progress = [&](uint32_t d, uint32_t t) {
        if (firstSampleSeconds == 0) firstSampleSeconds = sinceStart.seconds();
        bar.update(d, t);
    };
    scene::RenderOutput out;
    Json mpiReport;
#if AMRVK_MPI
    if (part) {
        world->checkpoint();  // every rank has its part and structures
        mpi::DataParallelResult r = mpi::renderDataParallel(
            *world, picture, *part, {{"readSeconds", readSeconds}, {"buildSeconds", picture.report.buildSeconds}},
            progress);
        out = std::move(r.out);
        mpiReport = std::move(r.mpi);
    } else if (world) {
        mpi::SampleParallelResult share = mpi::renderSampleParallel(
            *world, picture,
            {{"readSeconds", readSeconds}, {"buildSeconds", picture.report.buildSeconds}},
            progress);
        out = std::move(share.out);
        mpiReport = std::move(share.mpi);
    } else
#endif
        out = picture.render(progress);
    bar.finish();
    const double wallSeconds = wall.seconds();
    AMRVK_CHECK(ctx.validationErrors() == 0, "Vulkan validation reported ", ctx.validationErrors(),
                " error(s); last: ", ctx.lastValidationMessage());
    if (!speaks) return 0;  // rank 0 writes the outputs of the job
    session::writePicture(output, out.mean, s, legendFont.get());
    if (!varianceFile.empty())
        writeImage(varianceFile, scene::varianceImage(scene::varianceOfMean(out), out.mean.width, out.mean.height));

    const auto& c = out.stats.counters;
    const double paths = double(out.stats.paths);
    std::printf("wrote %s (%dx%d, %u spp, %s, %s on %s) in %.2f s GPU, %.2f M paths/s\n", output.c_str(), rs.width,
                rs.height, s.spp, scene::modeName(rs.mode), config.label().c_str(), ctx.deviceReport().name.c_str(),
                out.stats.gpuSeconds, out.stats.gpuSeconds > 0 ? paths / out.stats.gpuSeconds * 1e-6 : 0.0);
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
    if (!jsonFile.empty()) {
        Json j = picture::renderStats(picture, out, {.wallSeconds = wallSeconds, .firstSampleSeconds = firstSampleSeconds});
        if (!mpiReport.is_null()) j["mpi"] = mpiReport;
        writeFileAtomic(jsonFile, j.dump(2) + "\n");
    }
    return 0;
}

}  // namespace

int runRender(const std::vector<std::string>& argv) {
    return runOnRanks("render", [&](mpi::World* world) { return renderOn(argv, world); });
}

}  // namespace amrvk::cli
