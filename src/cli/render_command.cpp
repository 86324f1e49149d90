// amrvk render: path-trace an AMR data set on a Vulkan device; amrvk devices: list devices.
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <cmath>
#include <cstdio>

#include "amr/readers.h"
#include "render/auto_select.h"
#include "cli/args.h"
#include "cli/commands.h"
#include "cli/read_options.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/progress.h"
#include "core/stats.h"
#include "gpu/context.h"
#include "gpu/shader_library.h"
#include "core/image_io.h"
#include "render/renderer.h"

namespace amrvk::cli {

namespace {

const char* kRenderHelp =
    "usage: amrvk render <input> [options]\n"
    "\n"
    "Unbiased volumetric path tracing of the input's field on a Vulkan device (1 sample per pixel\n"
    "per dispatch, accumulated). Extinction = TF alpha x density scale per finest cell width;\n"
    "albedo = TF colour. Every majorant traversal x sample reconstruction structure of the paper is\n"
    "selectable; box hierarchies run as software BVHs (sw) or through VK_KHR_ray_query (rq).\n"
    "\n"
    "options:\n";

}  // namespace

int runDevices(const std::vector<std::string>& argv) {
    std::vector<OptionSpec> specs = {{"json", 0, "", "print a JSON array"}, {"help", 0, "", "show this help"}};
    for (const auto& a : argv)
        if (a == "--help" || a == "-h") {
            std::printf("usage: amrvk devices [--json]\n\nLists every Vulkan device: index, name, type, driver, "
                        "device-local memory, ray-query support, and why an unusable one is rejected.\n\n%s",
                        formatOptions(specs).c_str());
            return 0;
        }
    Args args("devices", argv, specs, 0, 0);
    auto devices = gpu::listDevices();
    if (args.has("json")) {
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
    std::vector<OptionSpec> specs = readOptionSpecs(false);
    auto add = [&](OptionSpec s) { specs.push_back(std::move(s)); };
    add({"tf", 1, "FILE|PRESET", "transfer function: ParaView preset JSON, .xf, or a preset (ramp, grey, spiky, foggy, constant, empty); default ramp over the field's range"});
    add({"tf-preset", 1, "NAME", "preset name inside a ParaView JSON file (default: the first)"});
    add({"tf-range", 2, "LO HI", "map the TF's node range onto [LO, HI] (presets: default the field's range)"});
    add({"mode", 1, "ae|ss|ms|dvr", "absorption+emission, single or multiple scattering, or the ray-marching baseline dvr (biased by --dt; default ms)"});
    add({"dt", 1, "DT", "dvr: step as a fraction of the finest cell width at the sample (default 0.5)"});
    add({"dvr-shading", 0, "", "dvr: gradient shading by the first --light-dir (else a headlight)"});
    add({"sampler", 1, "ext-brick|abr|dense", "sample reconstruction: brick domains, ABRs, or dense = the field resampled to the finest uniform grid (trilinear; the cost floor; needs a grid traversal) (default ext-brick)"});
    add({"dense-max-mib", 1, "MIB", "dense: largest dense grid to build (default 2048)"});
    add({"traversal", 1, "grid-dda|grid-bvh|abr|brick|ext-brick|kdtree|auto",
         "majorant traversal: macrocell DDA, BVH over non-empty macrocells, ABRs, brick bounds, brick domains, or the TF-specific kd-tree (default grid-dda); auto = probe every combination briefly and take the most efficient traversal, sampler, back-end and grid (those given explicitly stay fixed)"});
    add({"backend", 1, "sw|rq|auto", "box hierarchies: software BVH, VK_KHR_ray_query, or rq where the device has it (default auto)"});
    add({"grid", 1, "auto|N|NxMxK", "macrocell grid of grid-dda and grid-bvh (default auto: 128 on the longest axis)"});
    add({"kd-leaves", 1, "N", "kdtree: leaves of the kd-tree, rebuilt per TF (default 4096)"});
    add({"spp", 1, "N", "samples per pixel (default 64)"});
    add({"size", 1, "WxH", "image size (default 512x512)"});
    add({"camera", 9, "EX EY EZ TX TY TZ UX UY UZ", "eye, target and up in world space (default: three-quarter view)"});
    add({"fov", 1, "DEG", "vertical field of view (default 40)"});
    add({"seed", 1, "S", "random seed (default 1)"});
    add({"density-scale", 1, "S", "multiplies extinction (default 1)"});
    add({"g", 1, "G", "Henyey-Greenstein asymmetry in [-0.999, 0.999] (default 0)"});
    add({"ambient", 3, "R G B", "uniform environment radiance (default 1 1 1)"});
    add({"background", 3, "R G B", "radiance seen by primary rays that escape (default: the ambient)"});
    add({"light-dir", 6, "X Y Z R G B", "directional light towards X Y Z (world) with radiance R G B (repeatable)", true});
    add({"light-point", 6, "X Y Z R G B", "point light at X Y Z (world) with intensity R G B (repeatable)", true});
    add({"output", 1, "FILE", "out.png (tone-mapped sRGB), out.exr or out.pfm (linear float); default amrvk.png"});
    add({"json", 1, "FILE", "write render statistics as JSON"});
    add({"device", 1, "INDEX|NAME", "Vulkan device (default: the first discrete GPU, else any)"});
    add({"shader-dir", 1, "DIR", "load shaders (.spv or .comp) from DIR instead of the embedded ones"});
    add({"validation", 0, "", "enable the Vulkan validation layer"});
    add({"help", 0, "", "show this help"});
    for (const auto& a : argv)
        if (a == "--help" || a == "-h") {
            std::printf("%s%s", kRenderHelp, formatOptions(specs).c_str());
            return 0;
        }
    Args args("render", argv, specs, 1, 1);
    const std::string output = args.get("output", "amrvk.png");
    {
        std::string ext = std::filesystem::path(output).extension().string();
        AMRVK_CHECK(ext == ".png" || ext == ".exr" || ext == ".pfm", "-o ", output,
                    ": unknown image type (use .png, .exr or .pfm)");
        // Fail before the render, not after it, when the outputs cannot be written.
        for (const std::string& file : {output, args.get("json")}) {
            if (file.empty()) continue;
            std::filesystem::path dir = std::filesystem::path(file).parent_path();
            if (dir.empty()) dir = ".";
            AMRVK_CHECK(::access(dir.c_str(), W_OK) == 0, file, ": cannot write (directory ", dir.string(),
                        " is missing or not writable)");
        }
    }
    scene::StructureConfig config;
    const bool autoChoice = args.get("traversal") == "auto";
    if (!autoChoice) config.traversal = scene::parseTraversal(args.get("traversal", "grid-dda"));
    config.sampler = scene::parseSampler(args.get("sampler", "ext-brick"));
    config.backend = scene::parseBackend(args.get("backend", "auto"));
    config.grid = args.get("grid", "auto");
    const int64_t kdLeaves = args.getInt("kd-leaves", 4096);
    AMRVK_CHECK(kdLeaves >= 1 && kdLeaves <= (int64_t(1) << 24), "--kd-leaves ", kdLeaves, " is outside [1, 2^24]");
    config.kdLeaves = uint32_t(kdLeaves);
    const int64_t denseMiB = args.getInt("dense-max-mib", 2048);
    AMRVK_CHECK(denseMiB >= 1 && denseMiB <= (int64_t(1) << 20), "--dense-max-mib ", denseMiB, " is outside [1, 2^20]");
    config.denseMaxBytes = uint64_t(denseMiB) << 20;
    if (!autoChoice) config.validate();
    scene::RenderSettings rs;
    rs.mode = scene::parseMode(args.get("mode", "ms"));
    parseSize("--size", args.get("size", "512x512"), rs.width, rs.height);
    const int64_t spp = args.getInt("spp", 64);
    AMRVK_CHECK(spp >= 1 && spp <= (1 << 24), "--spp ", spp, " is outside [1, 2^24]");
    rs.seed = uint32_t(args.getInt("seed", 1));
    rs.dvrStep = args.getDouble("dt", 0.5);
    AMRVK_CHECK(rs.dvrStep > 0 && rs.dvrStep <= 64, "--dt ", rs.dvrStep, " is outside (0, 64]");
    rs.dvrShading = args.has("dvr-shading");
    rs.densityScale = args.getDouble("density-scale", 1.0);
    AMRVK_CHECK(rs.densityScale >= 0 && std::isfinite(rs.densityScale), "--density-scale must be finite and >= 0");
    rs.g = args.getDouble("g", 0.0);
    AMRVK_CHECK(rs.g >= -1 && rs.g <= 1, "--g ", rs.g, " is outside [-1, 1]");
    if (args.has("ambient")) rs.ambient = parseVec3("--ambient", args.values("ambient"), 0);
    if (args.has("background")) rs.background = parseVec3("--background", args.values("background"), 0);
    for (const char* kind : {"light-dir", "light-point"}) {
        auto v = args.values(kind);
        for (size_t i = 0; i + 5 < v.size(); i += 6)
            rs.lights.push_back({std::string(kind) == "light-point", parseVec3(std::string("--") + kind, v, i),
                                 parseVec3(std::string("--") + kind, v, i + 3)});
    }

    amr::ReadOptions ro = readOptionsFrom(args);
    amr::Model model;
    {
        ProgressStage stage("reading " + args.positional()[0]);
        model = amr::readModel(args.positional()[0], ro);
    }
    const amr::Field& field = ro.fields.empty() ? model.defaultField() : model.field(ro.fields[0]);
    if (args.has("shader-dir")) gpu::setShaderDirectory(args.get("shader-dir"));
    gpu::ContextOptions co;
    co.device = args.get("device");
    co.validation = args.has("validation");
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
    rs.camera = scene::defaultCamera(worldLo, worldHi, args.getDouble("fov", 40.0));
    if (args.has("camera")) {
        auto v = args.values("camera");
        rs.camera.eye = parseVec3("--camera", v, 0);
        rs.camera.target = parseVec3("--camera", v, 3);
        rs.camera.up = parseVec3("--camera", v, 6);
    }
    float tfLo = scene.valueLo, tfHi = scene.valueHi;
    if (args.has("tf-range")) {
        auto v = args.values("tf-range");
        tfLo = float(parseDouble("--tf-range", v[0]));
        tfHi = float(parseDouble("--tf-range", v[1]));
    }
    scene::TransferFunction tf = scene::loadTransferFunction(args.get("tf", "ramp"), tfLo, tfHi, args.get("tf-preset"));
    if (args.has("tf-range")) tf = tf.rescaled(tfLo, tfHi);
    if (autoChoice) {
        render::AutoConstraints constraints;
        if (args.has("sampler")) constraints.sampler = config.sampler;
        if (args.has("backend") && args.get("backend") != "auto") constraints.backend = config.backend;
        if (args.has("grid")) constraints.grid = config.grid;
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
    if (args.has("json")) {
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
        writeFileAtomic(args.get("json"), j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n");
    }
    return 0;
}

}  // namespace amrvk::cli
