// amrvk render: path-trace an AMR data set on a Vulkan device; amrvk devices: list devices.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "amr/readers.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/image_io.h"
#include "core/progress.h"
#include "core/stats.h"
#include "gpu/context.h"
#include "gpu/shader_library.h"
#include "picture/picture.h"
#include "render/renderer.h"

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
    "(amrvk view), with any option given here on top.";

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

int runRender(const std::vector<std::string>& argv) {
    const Timer sinceStart;  // time to the first sample: reading, validating, structures, device set-up
    CLI::App app(kRenderHelp, "amrvk render");
    setUpCommand(app);
    std::string input, output = "amrvk.png", jsonFile;
    ReadArgs read;
    PictureArgs pic;
    DeviceArgs dev;
    app.add_option("input", input,
                   "the data set: ExaBrick .cells, AMReX plotfile, Enzo parameter file, Chombo .hdf5, "
                   "raw .raw (optional with --session)")
        ->type_name("INPUT");
    addReadOptions(app, read, false);
    addPictureOptions(app, pic);
    app.add_option("-o,--output", output, "out.png (tone-mapped sRGB), out.exr or out.pfm (linear float)")
        ->capture_default_str()
        ->type_name("FILE");
    app.add_option("--json", jsonFile, "write render statistics as JSON")->type_name("FILE");
    addDeviceOptions(app, dev);
    if (!parseCommandLine(app, argv)) return 0;

    const std::string ext = fs::path(output).extension().string();
    AMRVK_CHECK(ext == ".png" || ext == ".exr" || ext == ".pfm", "-o ", output,
                ": unknown image type (use .png, .exr or .pfm)");
    // Every output checked before any work: writable, distinct, none of them an input.
    const std::vector<NamedPath> outputs = {{"-o", output}, {"--json", jsonFile}};
    checkOutputs(outputs, pictureInputs(app, input, pic));
    const session::PictureDescription description = describePicture(app, input, read, pic);
    Timer readTimer;
    std::shared_ptr<const scene::Volume> loaded = session::loadVolume(description.session);
    const double readSeconds = readTimer.seconds() - loaded->bricks.buildSeconds;
    checkOutputs(outputs, inputFilesRead());  // and none is a file the data set was read from
    gpu::ContextOptions co = dev.context;
    co.requireRayQuery = description.session.structure.backend == scene::Backend::Rq;
    gpu::Context ctx(co);
    picture::Picture picture =
        picture::makePicture(ctx, std::move(loaded), description,
                             {.shaders = gpu::ShaderLibrary(dev.shaderDir),
                              .note = [](const std::string& line) { std::fprintf(stderr, "amrvk: %s\n", line.c_str()); }});
    picture.report.readSeconds = readSeconds;
    const session::Session& s = picture.session;
    render::Renderer& renderer = *picture.renderer;
    const scene::StructureConfig& config = renderer.config();
    const scene::RenderSettings& rs = renderer.settings();
    ProgressBar bar("render", "spp");
    Timer wall;
    double firstSampleSeconds = 0;
    scene::RenderOutput out = picture.render([&](uint32_t d, uint32_t t) {
        if (firstSampleSeconds == 0) firstSampleSeconds = sinceStart.seconds();
        bar.update(d, t);
    });
    bar.finish();
    const double wallSeconds = wall.seconds();
    writeImage(output, out.mean);
    AMRVK_CHECK(ctx.validationErrors() == 0, "Vulkan validation reported ", ctx.validationErrors(),
                " error(s); last: ", ctx.lastValidationMessage());

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
        writeFileAtomic(jsonFile, j.dump(2) + "\n");
    }
    return 0;
}

}  // namespace amrvk::cli
