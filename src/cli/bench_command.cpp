// amrvk bench: the paper's benchmark protocol with speed against error (bench/bench_runner.h),
// reports in an output directory (bench/report.h).
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <limits>

#include "bench/bench_runner.h"
#include "bench/report.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "core/error.h"
#include "core/progress.h"
#include "gpu/context.h"

namespace amrvk::cli {

namespace {

const char* kBenchHelp =
    "The paper's benchmark protocol on a Vulkan device, with speed against error. For every data set\n"
    "x TF preset x mode x traversal x sampler x back-end: 1 sample per pixel per frame, --warmup\n"
    "frames, then --frames timed frames (GPU timer) -> frames/s, M paths/s, density lookups, traversal\n"
    "steps and real/null collisions per path, majorant update time after a TF edit, structure build\n"
    "time, device memory after build and peak. Each run's RMSE and relMSE against a cached high-spp\n"
    "reference (DIR/references, with the command that made it) at 1, 2, 4, ... spp against GPU time,\n"
    "its log-log slope (-1/2 for unbiased estimators) and the time to --target-rmse. Also: the dense\n"
    "sampler as the cost floor of sampling, the dvr ray marcher over step sizes against ae tracking,\n"
    "frames/s against macrocell resolution for grid-dda and grid-bvh, and with --auto the automatic\n"
    "choice against the best measured combination. Writes DIR/results.json, results.csv, results.md\n"
    "(paper layout, best three and worst marked), and PNG and PDF plots drawn by plot_bench.py\n"
    "(matplotlib; next to the amrvk binary). Tests never assert speed; neither should you compare\n"
    "numbers from different devices.";

// A comma-separated list option, one value per use: CLI11 splits at the commas.
CLI::Option* addListOption(CLI::App& app, const std::string& name, std::vector<std::string>& items,
                           const std::string& help) {
    return app.add_option(name, items, help)
        ->type_name("LIST")
        ->delimiter(',')
        ->allow_extra_args(false)
        ->default_str(CLI::detail::join(items, ","))
        ->group("protocol");
}

// `item`, or the word none (an empty list).
CLI::Validator itemOrNone(const CLI::Validator& item) {
    return CLI::Validator([item](std::string& text) { return text == "none" ? std::string() : item(text); },
                          item.get_description());
}

}  // namespace

int runBench(const std::vector<std::string>& argv) {
    CLI::App app(kBenchHelp, "amrvk bench");
    setUpCommand(app);
    bench::BenchOptions o;
    std::vector<std::string> inputs, modes, traversals, samplers, backends, dvrSteps, gridSweep;
    std::string field, outDir;
    for (scene::Mode m : o.modes) modes.push_back(scene::modeName(m));
    for (scene::TraversalKind t : o.traversals) traversals.push_back(scene::traversalName(t));
    for (scene::SamplerKind k : o.samplers) samplers.push_back(scene::samplerName(k));
    for (double dt : o.dvrSteps) dvrSteps.push_back(strCat(dt));
    gridSweep = o.gridSweep;
    int64_t referenceSpp = o.referenceSpp;
    o.autoSelect = false;  // the command runs --auto only when asked
    scene::StructureConfig config;
    CameraChoice camera;
    gpu::ContextOptions co;
    bool noDense = false;
    app.add_option("inputs", inputs, "AMR data sets; INPUT:FIELD names the field of one")
        ->type_name("INPUT")
        ->required();
    addFieldOption(app, field);
    app.add_option("-o,--output", outDir, "output directory (created; references are cached in DIR/references)")
        ->type_name("DIR")
        ->required()
        ->group("output");
    addListOption(app, "--tfs", o.tfs, "TF presets or files");
    addTfRangeOption(app, o.tfRange);
    addListOption(app, "--modes", modes, "unbiased modes of the matrix: ae, ss, ms");
    addListOption(app, "--traversals", traversals, "traversals of the matrix");
    addListOption(app, "--samplers", samplers, "samplers of the matrix: ext-brick, abr");
    addListOption(app, "--backends", backends, "back-ends of the matrix: sw, rq")
        ->default_str("sw, and rq where the device has ray queries");
    addImageOptions(app, o.base)->default_str("1024x1024 on a GPU, 256x256 on a CPU device");
    app.add_option("--frames", o.frames, "timed frames of 1 spp each")
        ->type_name("N")
        ->transform(integerIn(2, 1 << 20))
        ->default_str(strCat(o.frames))
        ->group("protocol");
    app.add_option("--warmup", o.warmup, "untimed frames first")
        ->type_name("N")
        ->transform(integerIn(0, 1 << 20))
        ->default_str(strCat(o.warmup))
        ->group("protocol");
    app.add_option("--reference-spp", referenceSpp, "samples per pixel of the references")
        ->type_name("N")
        ->transform(integerIn(2, 1 << 24))
        ->default_str("4096 on a GPU, 512 on a CPU device")
        ->group("protocol");
    app.add_option("--target-rmse", o.targetRmse, "RMSE whose time is reported")
        ->type_name("E")
        ->check(numberIn(0, std::numeric_limits<double>::infinity(), Open::High))
        ->default_str("half the first combination's 1-spp RMSE")
        ->group("protocol");
    addListOption(app, "--dvr-steps", dvrSteps, "dvr step sizes (fractions of the finest cell width)")
        ->type_name("LIST|none")
        ->check(itemOrNone(numberIn(0, 64, Open::Low)));
    addListOption(app, "--grid-sweep", gridSweep, "macrocells on the longest axis for the grid sweep")
        ->type_name("LIST|none")
        ->check(itemOrNone(integerIn(1, 4096)));
    app.add_flag("--no-dense", noDense, "skip the dense-sampler cost floor")->group("protocol");
    app.add_flag("--auto", o.autoSelect, "also run the automatic choice and compare it with the best measured one")
        ->group("protocol");
    addStructureSizeOptions(app, config);
    addLightingOptions(app, o.base);
    addCameraOptions(app, camera);
    addDeviceOptions(app, co);
    if (!parseCommandLine(app, argv)) return 0;

    o.outDir = outDir;
    std::filesystem::create_directories(o.outDir);
    AMRVK_CHECK(::access(o.outDir.c_str(), W_OK) == 0, "-o ", o.outDir.string(), ": directory is not writable");
    for (const std::string& p : inputs) {
        bench::BenchDataset ds;
        ds.input = p;
        ds.field = field;
        const size_t colon = p.rfind(':');
        if (!std::filesystem::exists(p) && colon != std::string::npos && colon > 0) {
            ds.input = p.substr(0, colon);
            ds.field = p.substr(colon + 1);
        }
        AMRVK_CHECK(std::filesystem::exists(ds.input), ds.input, ": no such file or directory");
        std::filesystem::path path(ds.input);
        ds.tag = path.filename().empty() ? path.parent_path().filename().string() : path.filename().string();
        if (!ds.field.empty()) ds.tag += ":" + ds.field;
        o.datasets.push_back(ds);
    }
    o.modes.clear();
    for (const std::string& m : modes) {
        const scene::Mode mode = scene::parseMode(m);
        AMRVK_CHECK(mode != scene::Mode::Dvr, "--modes: dvr is the baseline of --dvr-steps, not a matrix mode");
        o.modes.push_back(mode);
    }
    o.traversals.clear();
    for (const std::string& t : traversals) o.traversals.push_back(scene::parseTraversal(t));
    o.samplers.clear();
    for (const std::string& k : samplers) {
        const scene::SamplerKind sampler = scene::parseSampler(k);
        AMRVK_CHECK(sampler != scene::SamplerKind::Dense, "--samplers: dense runs by itself (see --no-dense)");
        o.samplers.push_back(sampler);
    }
    for (const std::string& b : backends) {
        const scene::Backend backend = scene::parseBackend(b);
        AMRVK_CHECK(backend != scene::Backend::Auto, "--backends: name sw and/or rq");
        o.backends.push_back(backend);
    }
    o.dvrSteps.clear();
    for (const std::string& dt : dvrSteps)
        if (dt != "none") o.dvrSteps.push_back(std::stod(dt));
    o.gridSweep.clear();
    for (const std::string& g : gridSweep)
        if (g != "none") o.gridSweep.push_back(g);
    AMRVK_CHECK(!o.tfs.empty() && !o.modes.empty() && !o.traversals.empty() && !o.samplers.empty(),
                "--tfs, --modes, --traversals and --samplers need at least one item each");
    if (app.count("--size")) {
        o.width = o.base.width;
        o.height = o.base.height;
    }
    o.referenceSpp = uint32_t(referenceSpp);
    o.dense = !noDense;
    o.grid = config.grid;
    o.kdLeaves = config.kdLeaves;
    o.denseMaxBytes = config.denseMaxBytes;
    o.camera = camera.explicitCamera();
    o.fovDegrees = camera.fovDegrees;
    o.commandLine = "amrvk bench";
    for (const auto& a : argv) o.commandLine += " " + a;
    {
        std::error_code ec;
        std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
        if (!ec) o.amrvkPath = self.string();
    }
    gpu::Context ctx(co);

    ProgressBar bar("bench", "runs");
    bench::BenchResults results =
        bench::runBench(ctx, o, [&](size_t d, size_t t, const std::string& what) { bar.update(d, t, what); });
    bar.finish();
    const bench::PlotOutcome plots = bench::writeReports(results, o.outDir);
    size_t failed = 0;
    for (const auto& r : results.runs) failed += !r.error.empty();
    std::printf("wrote %s/results.{json,csv,md} and %zu plot files (PNG, PDF): %zu runs (%zu failed) on %s\n",
                o.outDir.string().c_str(), plots.files.size(), results.runs.size(), failed, results.device.c_str());
    if (!plots.note.empty()) std::fprintf(stderr, "amrvk bench: %s\n", plots.note.c_str());
    return 0;
}

}  // namespace amrvk::cli
