// amrvk bench: the paper's benchmark protocol with speed against error (bench/bench_runner.h),
// reports in an output directory (bench/report.h).
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <sstream>

#include "bench/bench_runner.h"
#include "bench/report.h"
#include "cli/args.h"
#include "cli/commands.h"
#include "core/error.h"
#include "core/progress.h"
#include "gpu/context.h"
#include "gpu/shader_library.h"

namespace amrvk::cli {

namespace {

const char* kBenchHelp =
    "usage: amrvk bench <input[:field]>... -o DIR [options]\n"
    "\n"
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
    "(matplotlib; next to the amrvk binary). Tests never assert speed; neither\n"
    "should you compare numbers from different devices.\n"
    "\n"
    "options:\n";

std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream s(text);
    std::string item;
    while (std::getline(s, item, ','))
        if (!item.empty()) out.push_back(item);
    return out;
}

}  // namespace

int runBench(const std::vector<std::string>& argv) {
    std::vector<OptionSpec> specs = {
        {"output", 1, "DIR", "output directory (created; references are cached in DIR/references)"},
        {"tfs", 1, "LIST", "TF presets or files, comma-separated (default spiky,foggy)"},
        {"tf-range", 2, "LO HI", "map every TF onto [LO, HI] (default: each field's range)"},
        {"modes", 1, "LIST", "unbiased modes of the matrix: ae,ss,ms (default ms)"},
        {"traversals", 1, "LIST", "subset of grid-dda,grid-bvh,abr,brick,ext-brick,kdtree (default all)"},
        {"samplers", 1, "LIST", "subset of ext-brick,abr (default both)"},
        {"backends", 1, "LIST", "subset of sw,rq (default sw, and rq where the device has ray queries)"},
        {"size", 1, "WxH", "image size (default 1024x1024 on a GPU, 256x256 on a CPU device)"},
        {"frames", 1, "N", "timed frames of 1 spp each (default 100)"},
        {"warmup", 1, "N", "untimed frames first (default 10)"},
        {"reference-spp", 1, "N", "samples per pixel of the references (default 4096 on a GPU, 512 on a CPU device)"},
        {"target-rmse", 1, "E", "RMSE whose time is reported (default: half the first combination's 1-spp RMSE)"},
        {"dvr-steps", 1, "LIST|none", "dvr step sizes (fractions of the finest cell width; default 2,1,0.5,0.25,0.125)"},
        {"grid-sweep", 1, "LIST|none", "macrocells on the longest axis for the grid sweep (default 16,32,64,128,256)"},
        {"grid", 1, "auto|N|NxMxK", "macrocell grid of the matrix runs (default auto)"},
        {"kd-leaves", 1, "N", "kdtree leaves (default 4096)"},
        {"no-dense", 0, "", "skip the dense-sampler cost floor"},
        {"dense-max-mib", 1, "MIB", "largest dense grid (default 2048); larger data sets report it as failed"},
        {"auto", 0, "", "also run the automatic choice and compare it with the best measured combination"},
        {"density-scale", 1, "S", "multiplies extinction (default 1)"},
        {"ambient", 3, "R G B", "environment radiance (default 1 1 1)"},
        {"light-dir", 6, "X Y Z R G B", "directional light (repeatable)", true},
        {"camera", 9, "EX EY EZ TX TY TZ UX UY UZ", "eye, target, up in world space (default: each data set's three-quarter view)"},
        {"fov", 1, "DEG", "vertical field of view (default 40)"},
        {"seed", 1, "S", "random seed (default 1)"},
        {"device", 1, "INDEX|NAME", "Vulkan device (default: the first discrete GPU, else any)"},
        {"shader-dir", 1, "DIR", "load shaders from DIR instead of the embedded ones"},
        {"validation", 0, "", "enable the Vulkan validation layer"},
        {"help", 0, "", "show this help"},
    };
    for (const auto& a : argv)
        if (a == "--help" || a == "-h") {
            std::printf("%s%s", kBenchHelp, formatOptions(specs).c_str());
            return 0;
        }
    Args args("bench", argv, specs, 1, 64);
    AMRVK_CHECK(args.has("output"), "-o DIR is required (the reports go there)");
    bench::BenchOptions o;
    o.outDir = args.get("output");
    std::filesystem::create_directories(o.outDir);
    AMRVK_CHECK(::access(o.outDir.c_str(), W_OK) == 0, "-o ", o.outDir.string(), ": directory is not writable");
    for (const std::string& p : args.positional()) {
        bench::BenchDataset ds;
        ds.input = p;
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
    if (args.has("tfs")) o.tfs = splitList(args.get("tfs"));
    AMRVK_CHECK(!o.tfs.empty(), "--tfs: empty list");
    if (args.has("tf-range")) {
        auto v = args.values("tf-range");
        const float lo = float(parseDouble("--tf-range", v[0])), hi = float(parseDouble("--tf-range", v[1]));
        AMRVK_CHECK(lo < hi, "--tf-range ", lo, " ", hi, ": LO must be below HI");
        o.tfRange = std::make_pair(lo, hi);
    }
    if (args.has("modes")) {
        o.modes.clear();
        for (const auto& m : splitList(args.get("modes"))) {
            scene::Mode mode = scene::parseMode(m);
            AMRVK_CHECK(mode != scene::Mode::Dvr, "--modes: dvr is the baseline of --dvr-steps, not a matrix mode");
            o.modes.push_back(mode);
        }
    }
    if (args.has("traversals")) {
        o.traversals.clear();
        for (const auto& t : splitList(args.get("traversals"))) o.traversals.push_back(scene::parseTraversal(t));
    }
    if (args.has("samplers")) {
        o.samplers.clear();
        for (const auto& s : splitList(args.get("samplers"))) {
            scene::SamplerKind k = scene::parseSampler(s);
            AMRVK_CHECK(k != scene::SamplerKind::Dense, "--samplers: dense runs by itself (see --no-dense)");
            o.samplers.push_back(k);
        }
    }
    if (args.has("backends"))
        for (const auto& b : splitList(args.get("backends"))) {
            scene::Backend k = scene::parseBackend(b);
            AMRVK_CHECK(k != scene::Backend::Auto, "--backends: name sw and/or rq");
            o.backends.push_back(k);
        }
    if (args.has("size")) parseSize("--size", args.get("size"), o.width, o.height);
    const int64_t frames = args.getInt("frames", 100), warmup = args.getInt("warmup", 10);
    AMRVK_CHECK(frames >= 2 && frames <= 1 << 20, "--frames ", frames, " is outside [2, 2^20]");
    AMRVK_CHECK(warmup >= 0 && warmup <= 1 << 20, "--warmup ", warmup, " is outside [0, 2^20]");
    o.frames = uint32_t(frames);
    o.warmup = uint32_t(warmup);
    const int64_t refSpp = args.getInt("reference-spp", 0);
    AMRVK_CHECK(refSpp == 0 || (refSpp >= 2 && refSpp <= 1 << 24), "--reference-spp ", refSpp, " is outside [2, 2^24]");
    o.referenceSpp = uint32_t(refSpp);
    o.targetRmse = args.getDouble("target-rmse", 0.0);
    AMRVK_CHECK(o.targetRmse >= 0 && std::isfinite(o.targetRmse), "--target-rmse must be finite and >= 0");
    if (args.has("dvr-steps")) {
        o.dvrSteps.clear();
        if (args.get("dvr-steps") != "none")
            for (const auto& s : splitList(args.get("dvr-steps"))) {
                const double dt = parseDouble("--dvr-steps", s);
                AMRVK_CHECK(dt > 0 && dt <= 64, "--dvr-steps: ", dt, " is outside (0, 64]");
                o.dvrSteps.push_back(dt);
            }
    }
    if (args.has("grid-sweep")) {
        o.gridSweep.clear();
        if (args.get("grid-sweep") != "none")
            for (const auto& g : splitList(args.get("grid-sweep"))) {
                const int64_t n = parseInt("--grid-sweep", g);
                AMRVK_CHECK(n >= 1 && n <= 4096, "--grid-sweep: ", n, " is outside [1, 4096]");
                o.gridSweep.push_back(g);
            }
    }
    o.grid = args.get("grid", "auto");
    const int64_t kd = args.getInt("kd-leaves", 4096);
    AMRVK_CHECK(kd >= 1 && kd <= (int64_t(1) << 24), "--kd-leaves ", kd, " is outside [1, 2^24]");
    o.kdLeaves = uint32_t(kd);
    o.dense = !args.has("no-dense");
    const int64_t denseMiB = args.getInt("dense-max-mib", 2048);
    AMRVK_CHECK(denseMiB >= 1 && denseMiB <= (int64_t(1) << 20), "--dense-max-mib ", denseMiB, " is outside [1, 2^20]");
    o.denseMaxBytes = uint64_t(denseMiB) << 20;
    o.autoSelect = args.has("auto");
    o.base.densityScale = args.getDouble("density-scale", 1.0);
    AMRVK_CHECK(o.base.densityScale >= 0 && std::isfinite(o.base.densityScale), "--density-scale must be finite and >= 0");
    if (args.has("ambient")) o.base.ambient = parseVec3("--ambient", args.values("ambient"), 0);
    auto lights = args.values("light-dir");
    for (size_t i = 0; i + 5 < lights.size(); i += 6)
        o.base.lights.push_back({false, parseVec3("--light-dir", lights, i), parseVec3("--light-dir", lights, i + 3)});
    o.base.seed = uint32_t(args.getInt("seed", 1));
    o.fovDegrees = args.getDouble("fov", 40.0);
    AMRVK_CHECK(o.fovDegrees > 0 && o.fovDegrees < 180, "--fov ", o.fovDegrees, " is outside (0, 180)");
    if (args.has("camera")) {
        auto v = args.values("camera");
        scene::Camera c;
        c.eye = parseVec3("--camera", v, 0);
        c.target = parseVec3("--camera", v, 3);
        c.up = parseVec3("--camera", v, 6);
        c.fovYDegrees = o.fovDegrees;
        o.camera = c;
    }
    o.commandLine = "amrvk bench";
    for (const auto& a : argv) o.commandLine += " " + a;
    {
        std::error_code ec;
        std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
        if (!ec) o.amrvkPath = self.string();
    }
    if (args.has("shader-dir")) gpu::setShaderDirectory(args.get("shader-dir"));
    gpu::ContextOptions co;
    co.device = args.get("device");
    co.validation = args.has("validation");
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
