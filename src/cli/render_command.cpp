// amrvk render: path-trace an AMR data set on a Vulkan device; amrvk devices: list devices.
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <cmath>
#include <cstdio>

#include "amr/readers.h"
#include "render/auto_select.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/progress.h"
#include "core/stats.h"
#include "gpu/context.h"
#include "core/image_io.h"
#include "render/renderer.h"

namespace amrvk::cli {

namespace {

const char* kRenderHelp =
    "Unbiased volumetric path tracing of the input's field on a Vulkan device (1 sample per pixel\n"
    "per dispatch, accumulated). Extinction = TF alpha x density scale per finest cell width;\n"
    "albedo = TF colour. Every majorant traversal x sample reconstruction structure of the paper is\n"
    "selectable; box hierarchies run as software BVHs (sw) or through VK_KHR_ray_query (rq).";

}  // namespace

int runDevices(const std::vector<std::string>& argv) {
    CLI::App app("Lists every Vulkan device: index, name, type, driver, device-local memory, ray-query support,\n"
                 "and why an unusable one is rejected.",
                 "amrvk devices");
    setUpCommand(app);
    bool json = false;
    app.add_flag("--json", json, "print a JSON array");
    if (!parseCommandLine(app, argv)) return 0;
    auto devices = gpu::listDevices();
    if (json) {
        nlohmann::ordered_json j = nlohmann::ordered_json::array();
        for (const auto& d : devices)
            j.push_back({{"index", d.index}, {"name", d.name}, {"type", d.type}, {"driver", d.driver},
                         {"apiVersion", d.apiVersion}, {"deviceLocalBytes", d.deviceLocalBytes},
                         {"rayQuery", d.rayQuery}, {"usable", d.usable}, {"rejectReason", d.rejectReason}});
        std::printf("%s\n", j.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace).c_str());
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
    CLI::App app(kRenderHelp, "amrvk render");
    setUpCommand(app);
    std::string input, output = "amrvk.png", jsonFile;
    int64_t spp = 64;
    amr::ReadOptions ro;
    scene::RenderSettings rs;
    rs.width = rs.height = 512;
    scene::StructureConfig config;
    config.backend = scene::Backend::Auto;
    bool autoChoice = false;
    TfChoice tfChoice;
    CameraChoice camera;
    gpu::ContextOptions co;
    app.add_option("input", input, "the AMR data set (see amrvk --help for the formats)")->type_name("PATH")->required();
    addReadOptions(app, ro, false);
    addModeOptions(app, rs);
    addImageOptions(app, rs);
    app.add_option("--spp", spp, "samples per pixel")
        ->type_name("N")
        ->transform(integerIn(1, 1 << 24))
        ->default_str(strCat(spp))
        ->group("picture");
    addTransferFunctionOptions(app, tfChoice);
    addStructureOptions(app, config, &autoChoice);
    addStructureSizeOptions(app, config);
    addLightingOptions(app, rs);
    addCameraOptions(app, camera);
    app.add_option("-o,--output", output, "out.png (tone-mapped sRGB), out.exr or out.pfm (linear float)")
        ->type_name("FILE")
        ->default_str(output)
        ->group("output");
    app.add_option("--json", jsonFile, "write render statistics as JSON")->type_name("FILE")->group("output");
    addDeviceOptions(app, co);
    if (!parseCommandLine(app, argv)) return 0;
    {
        std::string ext = std::filesystem::path(output).extension().string();
        AMRVK_CHECK(ext == ".png" || ext == ".exr" || ext == ".pfm", "-o ", output,
                    ": unknown image type (use .png, .exr or .pfm)");
        // Fail before the render, not after it, when the outputs cannot be written.
        for (const std::string& file : {output, jsonFile}) {
            if (file.empty()) continue;
            std::filesystem::path dir = std::filesystem::path(file).parent_path();
            if (dir.empty()) dir = ".";
            AMRVK_CHECK(::access(dir.c_str(), W_OK) == 0, file, ": cannot write (directory ", dir.string(),
                        " is missing or not writable)");
        }
    }
    if (!autoChoice) config.validate();

    amr::Model model;
    {
        ProgressStage stage("reading " + input);
        model = amr::readModel(input, ro);
    }
    const amr::Field& field = ro.fields.empty() ? model.defaultField() : model.field(ro.fields[0]);
    co.requireRayQuery = config.backend == scene::Backend::Rq;
    gpu::Context ctx(co);
    config.backend = scene::resolveBackend(config.backend, ctx.hasRayQuery(), ctx.deviceReport().name);
    Timer buildTimer;
    scene::VolumeScene scene =
        autoChoice ? scene::makeVolumeScene(model, field) : scene::buildVolumeScene(model, field, config);
    double buildSeconds = buildTimer.seconds();

    const amr::ModelSummary summary = amr::summarize(model);
    const glm::dvec3 worldLo = model.voxelToWorld.toWorld(glm::dvec3(summary.bounds.lower));
    const glm::dvec3 worldHi = model.voxelToWorld.toWorld(glm::dvec3(summary.bounds.upper));
    rs.camera = camera.cameraFor(worldLo, worldHi);
    const float tfLo = tfChoice.range ? tfChoice.range->first : scene.valueLo;
    const float tfHi = tfChoice.range ? tfChoice.range->second : scene.valueHi;
    scene::TransferFunction tf = scene::loadTransferFunction(tfChoice.spec, tfLo, tfHi, tfChoice.preset);
    if (tfChoice.range) tf = tf.rescaled(tfLo, tfHi);
    if (autoChoice) {
        render::AutoConstraints constraints;
        if (app.count("--sampler")) constraints.sampler = config.sampler;
        if (config.backend != scene::Backend::Auto) constraints.backend = config.backend;
        if (app.count("--grid")) constraints.grid = config.grid;
        render::AutoChoice choice;
        {
            ProgressStage stage("--traversal auto: probing structure combinations");
            choice = render::autoSelect(ctx, scene, tf, rs, constraints);
        }
        const uint32_t kdLeavesChosen = config.kdLeaves;
        config = choice.config;
        config.kdLeaves = kdLeavesChosen;
        Timer t;
        scene.configure(config);
        buildSeconds = t.seconds();
        std::fprintf(stderr, "amrvk: --traversal auto picked %s%s from %zu probes in %.1f s\n", config.label().c_str(),
                     config.usesGrid() ? (" grid " + config.grid).c_str() : "", choice.probes.size(), choice.seconds);
    }

    render::Renderer renderer(ctx, scene);
    renderer.setTransferFunction(tf);
    ProgressBar bar("render", "spp");
    Timer wall;
    scene::RenderOutput out = renderer.render(rs, uint32_t(spp), [&](uint32_t d, uint32_t t) { bar.update(d, t); });
    bar.finish();
    const double wallSeconds = wall.seconds();
    writeImage(output, out.mean);
    AMRVK_CHECK(ctx.validationErrors() == 0, "Vulkan validation reported ", ctx.validationErrors(),
                " error(s); last: ", ctx.lastValidationMessage());

    glm::dvec3 meanRgb(0.0);
    for (const auto& p : out.mean.pixels) meanRgb += glm::dvec3(p);
    meanRgb /= double(out.mean.pixels.size());
    const auto& c = out.stats.counters;
    const double paths = double(out.stats.paths);
    std::printf("wrote %s (%dx%d, %lld spp, %s, %s on %s) in %.2f s GPU, %.2f M paths/s\n", output.c_str(),
                rs.width, rs.height, (long long)spp, scene::modeName(rs.mode), config.label().c_str(),
                ctx.deviceReport().name.c_str(), out.stats.gpuSeconds,
                out.stats.gpuSeconds > 0 ? paths / out.stats.gpuSeconds * 1e-6 : 0.0);
    if (c[shared::kCounterMajorantViolations] || c[shared::kCounterNanSamples] || c[shared::kCounterBounceLimitHits])
        std::fprintf(stderr, "amrvk: warning: %llu majorant violations, %llu NaN samples, %llu paths hit the bounce limit\n",
                     (unsigned long long)c[shared::kCounterMajorantViolations],
                     (unsigned long long)c[shared::kCounterNanSamples],
                     (unsigned long long)c[shared::kCounterBounceLimitHits]);
    if (!jsonFile.empty()) {
        using Json = nlohmann::ordered_json;
        Json j = {{"input", model.source}, {"field", field.name}, {"device", ctx.deviceReport().name},
                  {"width", rs.width}, {"height", rs.height}, {"spp", spp}, {"mode", scene::modeName(rs.mode)},
                  {"traversal", scene::traversalName(config.traversal)},
                  {"sampler", scene::samplerName(config.sampler)}, {"backend", scene::backendName(config.backend)},
                  {"tf", tf.name()}, {"seconds", out.stats.gpuSeconds}, {"wallSeconds", wallSeconds},
                  {"pathsPerSecond", out.stats.gpuSeconds > 0 ? paths / out.stats.gpuSeconds : 0.0},
                  {"paths", out.stats.paths}, {"densityLookups", c[shared::kCounterDensityLookups]},
                  {"realCollisions", c[shared::kCounterRealCollisions]},
                  {"nullCollisions", c[shared::kCounterNullCollisions]},
                  {"traversalSteps", c[shared::kCounterTraversalSteps]},
                  {"majorantViolations", c[shared::kCounterMajorantViolations]},
                  {"nanSamples", c[shared::kCounterNanSamples]},
                  {"bounceLimitHits", c[shared::kCounterBounceLimitHits]},
                  {"majorantSeconds", renderer.majorantSeconds()},
                  {"tfStructureUpdateSeconds", renderer.structureUpdateSeconds()},
                  {"activeTraversalBoxes", renderer.activeTraversalBoxes()}, {"structureBuildSeconds", buildSeconds}};
        j["structureBuildSecondsPer"] = {
            {"bricks", scene.buildSeconds.bricks},     {"abrs", scene.buildSeconds.abrs},
            {"samplerBvh", scene.buildSeconds.samplerBvh}, {"macrocells", scene.buildSeconds.grid},
            {"traversalRanges", scene.buildSeconds.domains}, {"kdTree", scene.buildSeconds.kdTree},
            {"denseGrid", scene.buildSeconds.dense}};
        Json& host = j["hostMemoryPerStructure"] = Json::object();
        for (const auto& [name, bytes] : scene.hostBytes()) host[name] = bytes;
        j["deviceMemoryBytes"] = ctx.memory().currentBytes();
        j["deviceMemoryPeakBytes"] = ctx.memory().peakBytes();
        Json& device = j["deviceMemoryPerResource"] = Json::object();
        for (const auto& [name, usage] : ctx.memory().perResource())
            device[name] = {{"current", usage.current}, {"peak", usage.peak}};
        if (scene.grid) j["macrocellDims"] = Json::array({scene.grid->dims.x, scene.grid->dims.y, scene.grid->dims.z});
        j["meanRGB"] = Json::array({meanRgb.x, meanRgb.y, meanRgb.z});
        // Non-finite numbers are written as null, bytes that are not UTF-8 as U+FFFD.
        writeFileAtomic(jsonFile, j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n");
    }
    return 0;
}

}  // namespace amrvk::cli
