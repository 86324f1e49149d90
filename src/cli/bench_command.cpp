// amrvk bench: the paper's benchmark protocol with speed against error (bench/bench_runner.h),
// reports in an output directory (bench/report.h).
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "bench/bench_runner.h"
#include "bench/report.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "cli/ranks.h"
#include "core/error.h"
#include "core/progress.h"
#include "core/strings.h"
#include "gpu/context.h"
#include "gpu/shader_library.h"
#include "scene/limits.h"
#include "scene/tf_colors.h"

#if AMRVK_MPI
#include "mpi/sample_parallel.h"
#endif

namespace amrvk::cli {

namespace {

const char* kBenchHelp =
    "The paper's benchmark protocol on a Vulkan device, with speed against error. For every data "
    "set\n"
    "x TF preset x mode x traversal x sampler x back-end: 1 sample per pixel per frame, --warmup\n"
    "frames, then --frames timed frames (GPU timer) -> frames/s, M paths/s, density lookups, "
    "traversal\n"
    "steps and real/null collisions per path, majorant update time after a TF edit, structure "
    "build\n"
    "time, device memory after build and peak. Each run's RMSE and relMSE against a cached "
    "high-spp\n"
    "reference (DIR/references, with the command that made it) at 1, 2, 4, ... spp against GPU "
    "time,\n"
    "its log-log slope (-1/2 for unbiased estimators) and the time to --target-rmse. Also: the "
    "dense\n"
    "sampler as the cost floor of sampling, the dvr ray marcher over step sizes against ae "
    "tracking,\n"
    "frames/s against macrocell resolution for grid-dda and grid-bvh, and with --auto the "
    "automatic\n"
    "choice against the best measured combination. Writes DIR/results.json, results.csv, "
    "results.md\n"
    "(paper layout, best three and worst marked), and PNG and PDF plots drawn by plot_bench.py\n"
    "(matplotlib; next to the amrvk binary). Tests never assert speed; neither\n"
    "should you compare numbers from different devices.";

// A comma-separated list of names, each through `parse`; an empty list is an error naming the option.
template <typename T>
std::vector<T> parseList(const char* option, const std::string& text, T (*parse)(const std::string&)) {
    std::vector<T> out;
    for (const std::string& item : splitList(text)) out.push_back(parse(item));
    AMRVK_CHECK(!out.empty(), option, ": empty list");
    return out;
}

}  // namespace

namespace {

// The bench command's options, bound by addBenchOptions.
struct BenchArgs {
    std::vector<std::string> inputs;
    std::string outDir, tfs = "spiky,foggy", modes = "ms", traversals, samplers, backends, dvrSteps, gridSweep;
    std::string subMajorants = "off,8", transmittances = "ratio", controls = "none";
    int64_t frames = 100, warmup = 10, refSpp = 0;
    double targetRmse = 0;
    bool noDense = false, autoSelect = false;
    ReadArgs read;
    PictureArgs pic;
    DeviceArgs dev;
};

// Registers the protocol's own options on `app`, bound to `a`, in --help's order.
void addProtocolOptions(CLI::App& app, BenchArgs& a) {
    app.add_option("--tfs", a.tfs,
                   "TF presets or files, comma-separated; presets are fitted to each data set (spiky and foggy "
                   "over its percentiles, as render fits them) unless --tf-range fixes them")
        ->capture_default_str()
        ->type_name("LIST");
    app.add_option("--modes", a.modes, "unbiased modes of the matrix: ae,ss,ms")
        ->capture_default_str()
        ->type_name("LIST");
    app.add_option("--traversals", a.traversals, "subset of grid-dda,grid-bvh,abr,brick,ext-brick,kdtree (default all)")
        ->type_name("LIST");
    app.add_option("--samplers", a.samplers, "subset of ext-brick,abr,grid (default all three)")->type_name("LIST");
    app.add_option("--backends", a.backends, "subset of sw,rq (default sw, and rq where the device has ray queries)")
        ->type_name("LIST");
    app.add_option("--sub-majorants", a.subMajorants,
                   "sub-majorant settings of the grid traversals' rows (as render's --sub-majorants: off, 2, 4, 8, "
                   "16); every combination with a grid traversal and an AMR sampler runs once per entry")
        ->capture_default_str()
        ->type_name("LIST");
    app.add_option("--transmittances", a.transmittances,
                   "shadow-ray estimators of the ss and ms rows (as render's --transmittance: ratio, ubrm); every "
                   "combination runs once per entry")
        ->capture_default_str()
        ->type_name("LIST");
    app.add_option("--control-extinctions", a.controls,
                   "control extinctions of the ae, ss and ms rows (as render's --control-extinction: none, "
                   "minorant); every grid-dda and grid-bvh combination runs once per entry, the others with none")
        ->capture_default_str()
        ->type_name("LIST");
    app.add_option("--frames", a.frames, "timed frames of 1 spp each")
        ->check(interval(2, 1 << 20))
        ->capture_default_str()
        ->type_name("N");
    app.add_option("--warmup", a.warmup, "untimed frames first")
        ->check(interval(0, 1 << 20))
        ->capture_default_str()
        ->type_name("N");
    app.add_option("--reference-spp", a.refSpp,
                   "samples per pixel of the references (default 4096 on a GPU, 512 on a CPU device)")
        ->check(interval(2, scene::kMaxSpp))
        ->type_name("N");
    app.add_option("--target-rmse", a.targetRmse,
                   "RMSE whose time is reported (default: half the first combination's 1-spp RMSE)")
        ->check(interval(0, INFINITY, false, true))
        ->type_name("E");
    app.add_option("--dvr-steps", a.dvrSteps,
                   "dvr step sizes (fractions of the finest cell width; default 2,1,0.5,0.25,0.125)")
        ->type_name("LIST|none");
    app.add_option("--grid-sweep", a.gridSweep,
                   "macrocells on the longest axis for the grid sweep (default 16,32,64,128,256)")
        ->type_name("LIST|none");
    app.add_flag("--no-dense", a.noDense, "skip the dense-sampler cost floor");
    app.add_flag("--auto", a.autoSelect,
                 "also run the automatic choice and compare it with the best measured combination");
}

// Registers every bench option on `app`, bound to `a`, in --help's order.
void addBenchOptions(CLI::App& app, BenchArgs& a) {
    app.add_option("inputs", a.inputs, "data sets; INPUT:FIELD picks a field per data set (--field for all)")
        ->required()
        ->type_name("INPUT[:FIELD]...");
    app.add_option("-o,--output", a.outDir, "output directory (created; references are cached in DIR/references)")
        ->required()
        ->type_name("DIR");
    a.read.scale = "linear";  // the protocol's data as the paper takes it unless asked
    addReadOptions(app, a.read, false);
    addProtocolOptions(app, a);
    addPictureOptions(app, a.pic, true);
    app.get_option("--size")
        ->description("image size (default 1024x1024 on a GPU, 256x256 on a CPU device)")
        ->default_str("");
    addDeviceOptions(app, a.dev);
}

// The data sets, each existing: INPUT or INPUT:FIELD (a colon read as a field only when INPUT
// itself does not exist), the field --field's otherwise, tagged with its file name and field.
std::vector<bench::BenchDataset> benchDatasets(const std::vector<std::string>& inputs, const ReadArgs& read) {
    std::vector<bench::BenchDataset> out;
    for (const std::string& p : inputs) {
        bench::BenchDataset ds;
        ds.input = p;
        const size_t colon = p.rfind(':');
        if (!std::filesystem::exists(p) && colon != std::string::npos && colon > 0) {
            ds.input = p.substr(0, colon);
            ds.field = p.substr(colon + 1);
        }
        if (ds.field.empty() && !read.fields.empty()) ds.field = read.fields.front();
        AMRVK_CHECK(std::filesystem::exists(ds.input), ds.input, ": no such file or directory");
        std::filesystem::path path(ds.input);
        ds.tag = path.filename().empty() ? path.parent_path().filename().string() : path.filename().string();
        if (!ds.field.empty()) ds.tag += ":" + ds.field;
        out.push_back(ds);
    }
    return out;
}

// The matrix into `o`: TFs (and a fixed --tf-range), modes, traversals, samplers and back-ends,
// each list checked in that order.
void parseMatrix(const CLI::App& app, const BenchArgs& a, bench::BenchOptions& o) {
    o.tfs = splitList(a.tfs);
    AMRVK_CHECK(!o.tfs.empty(), "--tfs: empty list");
    if (app.count("--tf-range")) {
        const float lo = float(a.pic.tfRange[0]), hi = float(a.pic.tfRange[1]);
        AMRVK_CHECK(lo < hi, "--tf-range ", lo, " ", hi, ": LO must be below HI");
        o.tfRange = std::make_pair(lo, hi);
    }
    o.modes = parseList("--modes", a.modes, scene::parseMode);
    AMRVK_CHECK(std::ranges::count(o.modes, scene::Mode::Dvr) == 0,
                "--modes: dvr is the baseline of --dvr-steps, not a matrix mode");
    if (app.count("--traversals")) o.traversals = parseList("--traversals", a.traversals, scene::parseTraversal);
    if (app.count("--samplers")) {
        o.samplers = parseList("--samplers", a.samplers, scene::parseSampler);
        AMRVK_CHECK(std::ranges::count(o.samplers, scene::SamplerKind::Dense) == 0,
                    "--samplers: dense runs by itself (see --no-dense)");
    }
    o.subMajorants.clear();
    for (uint32_t n : parseList<uint32_t>("--sub-majorants", a.subMajorants,
                                          +[](const std::string& t) { return scene::parseSubMajorants(t); }))
        if (std::ranges::count(o.subMajorants, n) == 0) o.subMajorants.push_back(n);
    o.transmittances.clear();
    for (scene::Transmittance t : parseList("--transmittances", a.transmittances, scene::parseTransmittance))
        if (std::ranges::count(o.transmittances, t) == 0) o.transmittances.push_back(t);
    o.controls.clear();
    for (scene::ControlExtinction k : parseList("--control-extinctions", a.controls, scene::parseControlExtinction))
        if (std::ranges::count(o.controls, k) == 0) o.controls.push_back(k);
    if (app.count("--backends")) {
        o.backends = parseList("--backends", a.backends, scene::parseBackend);
        AMRVK_CHECK(std::ranges::count(o.backends, scene::Backend::Auto) == 0, "--backends: name sw and/or rq");
    }
}

// The sweeps into `o` when given: --dvr-steps (each in (0, 64]) and --grid-sweep (each in
// [1, 4096]); "none" empties one.
void parseSweeps(const CLI::App& app, const BenchArgs& a, bench::BenchOptions& o) {
    if (app.count("--dvr-steps")) {
        o.dvrSteps.clear();
        if (a.dvrSteps != "none")
            for (const auto& t : splitList(a.dvrSteps)) {
                char* end = nullptr;
                const double dt = std::strtod(t.c_str(), &end);
                AMRVK_CHECK(end && *end == '\0' && dt > 0 && dt <= 64, "--dvr-steps: '", t, "' is not in (0, 64]");
                o.dvrSteps.push_back(dt);
            }
        // "," named no step: an empty list, not "none" said by mistake.
        AMRVK_CHECK(a.dvrSteps == "none" || !o.dvrSteps.empty(), "--dvr-steps: empty list (give steps, or none)");
    }
    if (app.count("--grid-sweep")) {
        o.gridSweep.clear();
        if (a.gridSweep != "none")
            for (const auto& g : splitList(a.gridSweep)) {
                char* end = nullptr;
                const long n = std::strtol(g.c_str(), &end, 10);
                AMRVK_CHECK(end && *end == '\0' && n >= 1 && n <= 4096, "--grid-sweep: '", g, "' is not in [1, 4096]");
                o.gridSweep.push_back(g);
            }
        AMRVK_CHECK(a.gridSweep == "none" || !o.gridSweep.empty(), "--grid-sweep: empty list (give sizes, or none)");
    }
}

// The protocol's options from the parsed command line, every one checked; nothing is written yet.
bench::BenchOptions benchOptions(const CLI::App& app, BenchArgs& a, const std::vector<std::string>& argv,
                                 mpi::World* world) {
    bench::BenchOptions o;
    o.outDir = a.outDir;
    o.datasets = benchDatasets(a.inputs, a.read);
    o.read = readOptions(a.read);
    parseMatrix(app, a, o);
    if (app.count("--size")) parseSize("--size", a.pic.size, o.width, o.height);
    o.frames = uint32_t(a.frames);
    o.warmup = uint32_t(a.warmup);
    o.referenceSpp = uint32_t(a.refSpp);
    o.targetRmse = a.targetRmse;
    parseSweeps(app, a, o);
    session::Session given;  // the table's settings bench takes (session/setting_table.h)
    applySettingTable(app, a.pic, given, true);
    o.tfColors = given.tfColors;  // the references are keyed by it
    o.grid = given.structure.grid;
    o.kdLeaves = given.structure.kdLeaves;
    o.dense = !a.noDense;
    o.denseMaxBytes = given.structure.denseMaxBytes;
    o.autoSelect = a.autoSelect;
    AMRVK_CHECK(!world || !a.autoSelect, "--auto: not under mpirun (its timed pick can differ between ranks)");
    o.base = pictureSettings(app, a.pic, given.settings);
    o.fovDegrees = o.base.camera.fovYDegrees;
    if (app.count("--camera")) o.camera = o.base.camera;
    o.commandLine = "amrvk bench";
    for (const auto& arg : argv) o.commandLine += " " + arg;
    {
        std::error_code ec;
        std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
        if (!ec) o.amrvkPath = self.string();
    }
    return o;
}

// The output directory, made (every option is valid by now) and writable; its reports are none of
// the data sets.
void makeOutputDirectory(const bench::BenchOptions& o) {
    std::vector<NamedPath> dataInputs;
    for (const bench::BenchDataset& ds : o.datasets) dataInputs.push_back({"input", ds.input});
    std::error_code ec;
    AMRVK_CHECK(!std::filesystem::exists(o.outDir, ec) || std::filesystem::is_directory(o.outDir, ec), "-o ",
                o.outDir.string(), ": exists and is not a directory");
    std::filesystem::create_directories(o.outDir, ec);
    AMRVK_CHECK(!ec, "-o ", o.outDir.string(), ": cannot create (", ec.message(), ")");
    AMRVK_CHECK(::access(o.outDir.c_str(), W_OK) == 0, "-o ", o.outDir.string(), ": directory is not writable");
    checkOutputs({{"-o", o.outDir / "results.json"}, {"-o", o.outDir / "results.csv"}, {"-o", o.outDir / "results.md"}},
                 dataInputs);
}

#if AMRVK_MPI
// Under mpirun: this rank's device, and the hooks that split each render's samples over the ranks
// and agree on failures; only rank 0 (`speaks`) writes files.
void shareOverRanks(mpi::World* world, bool speaks, bench::BenchOptions& o, gpu::ContextOptions& co) {
    co.spread = uint32_t(world->localRank());
    o.writesFiles = speaks;
    o.render = [world](render::Renderer& r, uint32_t spp, const std::function<void(uint32_t, uint32_t)>& progress,
                       const std::vector<uint32_t>& marks,
                       const std::function<void(const scene::RenderOutput&)>& snapshot) {
        return mpi::renderSamples(*world, r, spp, progress, marks, snapshot).out;
    };
    o.agree = [world](const std::string& error) {
        mpi::Failure f = world->agree(error, {}, 20, false);
        if (f.fatal) throw mpi::PeerFailed(std::move(f));
        if (f.rank < 0) return std::string();
        return "rank " + std::to_string(f.rank) + " of " + std::to_string(world->size()) + ": " +
               (f.message.empty() ? std::string("failed") : f.message);
    };
    o.all = [world](bool mine) {
        mpi::Failure f = world->agree(mine ? "" : "no", {}, 20, false);
        if (f.fatal) throw mpi::PeerFailed(std::move(f));
        return f.rank < 0;
    };
}
#endif

// The reports (results, plots) and the summary line; a note on stderr when plots were not drawn.
void writeBenchReports(const bench::BenchResults& results, const bench::BenchOptions& o) {
    const bench::PlotOutcome plots = bench::writeReports(results, o.outDir);
    size_t failed = 0;
    for (const auto& r : results.runs) failed += !r.error.empty();
    std::printf(
        "wrote %s/results.{json,csv,md} and %zu plot files (PNG, PDF): %zu runs (%zu failed) on "
        "%s\n",
        o.outDir.string().c_str(), plots.files.size(), results.runs.size(), failed, results.device.c_str());
    // A plot that could not be written (a full disk) fails the command; the reports stay.
    AMRVK_CHECK(!plots.failed, plots.note);
    if (!plots.note.empty()) std::fprintf(stderr, "amrvk bench: %s\n", plots.note.c_str());
}

// The bench; with `world` (mpirun) sample-parallel: every rank runs the protocol, each render's
// samples split over the ranks; rank 0 alone speaks and writes.
int benchOn(const std::vector<std::string>& argv, mpi::World* world) {
#if AMRVK_MPI
    const bool speaks = !world || world->rank() == 0;
#else
    const bool speaks = true;
#endif
    CLI::App app(kBenchHelp, "amrvk bench");
    setUpCommand(app);
    BenchArgs a;
    addBenchOptions(app, a);
    if (!parseCommandLine(app, argv)) return 0;

    bench::BenchOptions o = benchOptions(app, a, argv, world);
    // Every option is valid: only now the output directory is made, never inside a data set.
    makeOutputDirectory(o);
    o.shaders = gpu::ShaderLibrary(a.dev.shaderDir);
    gpu::ContextOptions co = a.dev.context;
#if AMRVK_MPI
    if (world) shareOverRanks(world, speaks, o, co);
#endif
    gpu::Context ctx(co);

    ProgressBar bar("bench", "runs");
    bench::BenchResults results =
        bench::runBench(ctx, o, [&](size_t d, size_t t, const std::string& what) { bar.update(d, t, what); });
    bar.finish();
    if (!speaks) return 0;  // rank 0 writes the reports of the job
    writeBenchReports(results, o);
    return 0;
}

}  // namespace

int runBench(const std::vector<std::string>& argv) {
    return runOnRanks("bench", [&](mpi::World* world) { return benchOn(argv, world); });
}

}  // namespace amrvk::cli
