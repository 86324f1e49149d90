#pragma once
// The benchmark protocol of `amrvk bench` (the paper's, extended with error): per data set x TF
// preset x mode x structure combination, 1 sample per pixel per frame, `warmup` frames, then
// `frames` timed frames on the GPU timer -> frames/s, M paths/s, per-path counters, the majorant
// update time after a TF edit, structure build time and device memory (after build, peak). Each
// timed run also measures its error against a cached high-spp reference at 1, 2, 4, ... spp:
// RMSE and relMSE (reference noise subtracted) against GPU time, the log-log slope and the time
// to a target RMSE. Extras: the dense sampler (cost floor; every run reports its cost per path as
// a ratio to it), the dvr baseline over step sizes, a macrocell grid sweep for grid-dda and
// grid-bvh, and --auto's pick compared with the best measured combination.
#include <array>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "amr/readers.h"
#include "bench/convergence.h"
#include "gpu/context.h"
#include "gpu/shader_library.h"
#include "render/auto_select.h"
#include "render/renderer.h"
#include "scene/tf_colors.h"

namespace amrvk::bench {

struct BenchDataset {
    std::string input;  // path as given
    std::string field;  // empty: the default field
    std::string tag;    // short name for tables and file names
};

struct BenchOptions {
    std::vector<BenchDataset> datasets;
    amr::ReadOptions read;                 // format, NaN policy, raw options (the field is per data set)
    std::vector<std::string> tfs = {"spiky", "foggy"};  // presets or files
    // Map every TF onto [lo, hi], presets in their range-fixed shape (default: presets fitted to
    // each data set, spiky and foggy over its percentiles; scene::makePreset).
    std::optional<std::pair<float, float>> tfRange;
    scene::TfColors tfColors = scene::TfColors::Srgb;  // what every TF's colours mean (--tf-colors)
    std::vector<scene::Mode> modes = {scene::Mode::Ms};  // unbiased modes of the matrix
    std::vector<scene::TraversalKind> traversals = scene::allTraversals();
    std::vector<scene::SamplerKind> samplers = scene::allSamplers();
    std::vector<scene::Backend> backends;  // empty: sw, and rq where the device has it
    // Sub-majorant settings (StructureConfig::subMajorants) of the rows with a grid traversal and an
    // AMR sampler: each such combination runs once per entry, the others once.
    std::vector<uint32_t> subMajorants = {0, 8};
    // Shadow-ray estimators (RenderSettings::transmittance): in ss and ms every combination of the
    // matrix runs once per entry; ae and dvr, which cast no shadow rays, once.
    std::vector<scene::Transmittance> transmittances = {scene::Transmittance::Ratio};
    // Control extinctions (RenderSettings::controlExtinction): in ae, ss and ms the grid-dda and
    // grid-bvh combinations run once per entry (minorant is theirs alone), the others with none.
    std::vector<scene::ControlExtinction> controls = {scene::ControlExtinction::None};
    int width = 0, height = 0;             // 0: 1024^2 on a GPU, 256^2 on a CPU device
    uint32_t frames = 100, warmup = 10;
    uint32_t referenceSpp = 0;              // 0: 4096 on a GPU, 512 on a CPU device
    double targetRmse = 0;                  // 0: half the 1-spp RMSE of the first combination per group
    std::vector<double> dvrSteps = {2, 1, 0.5, 0.25, 0.125};  // empty: no dvr baseline
    std::vector<std::string> gridSweep = {"16", "32", "64", "128", "256"};  // empty: no sweep
    bool dense = true;
    bool autoSelect = true;
    std::string grid = "auto";
    uint32_t kdLeaves = 4096;
    uint64_t denseMaxBytes = uint64_t(2) << 30;
    scene::RenderSettings base;            // lights, ambient, density scale, seed, fov
    std::optional<scene::Camera> camera;   // default: each data set's three-quarter view
    double fovDegrees = 40;
    std::filesystem::path outDir;
    std::string commandLine;
    std::string amrvkPath = "amrvk";        // for the reference command lines
    gpu::ShaderLibrary shaders;             // --shader-dir (default: the embedded shaders)

    // Sample-parallel MPI (mpi::sampleParallelBench): every rank runs the same protocol and these
    // hooks make its renders shared. `render` renders spp samples of the picture the renderer holds
    // (committed by the runner) from scratch as Renderer::render does (snapshots at snapshotSpp), with
    // the samples split over the ranks; `agree` is called by
    // every rank once per run, between building and rendering, with this rank's error (empty: none)
    // and returns the first failing rank's; `all` is a logical and over the ranks (a reference is
    // taken from the cache only when every rank has it); only a process with `writesFiles` writes
    // the reference cache. Empty hooks: one process.
    using RenderFn = std::function<scene::RenderOutput(
        render::Renderer&, uint32_t spp, const std::function<void(uint32_t, uint32_t)>& progress,
        const std::vector<uint32_t>& snapshotSpp, const std::function<void(const scene::RenderOutput&)>& snapshot)>;
    RenderFn render;
    std::function<std::string(const std::string&)> agree;
    std::function<bool(bool)> all;
    bool writesFiles = true;
};

// " ubrm", " minorant", " ubrm minorant" or "": the estimators of a run that are not the default,
// as its label and its progress line name them.
std::string estimatorLabel(scene::Transmittance transmittance, scene::ControlExtinction control);

// One timed configuration.
struct RunResult {
    std::string dataset, tf, mode, kind;  // kind: matrix | dense | dvr | grid-sweep
    scene::StructureConfig config;
    scene::Transmittance transmittance = scene::Transmittance::Ratio;  // ss and ms shadow rays
    scene::ControlExtinction control = scene::ControlExtinction::None;  // ae, ss, ms trackers
    std::string gridDims;                 // e.g. "128x128x64" for grid traversals
    double dvrStep = 0;                   // dvr only
    int width = 0, height = 0;
    uint32_t frames = 0;
    double gpuSeconds = 0, fps = 0, mPathsPerSecond = 0;
    double lookupsPerPath = 0, stepsPerPath = 0, realPerPath = 0, nullPerReal = 0;
    // Where the time goes, per path (shared::kPath*: lookups, null and real collisions, traversal
    // steps), the share of lookups made by shadow rays, and the SIMD lanes' share of useful lookup
    // work (1: no divergence).
    std::array<scene::PathDistribution, shared::kPathQuantities> perPath{};
    double shadowLookupShare = 0, laneUse = 0;
    double subMajorantSkipsPerPath = 0;  // collisions sub-majorants decided without a lookup
    uint64_t violations = 0, nanSamples = 0;
    double buildSeconds = 0;               // host build of the structures this combination uses (bricks incl.)
    double majorantSeconds = 0;            // GPU: majorant passes (+ BLAS) after a TF edit
    double tfStructureSeconds = 0;         // host: TF-dependent structures after the edit
    double tfUpdateWallSeconds = 0;        // the whole setTransferFunction call
    uint64_t deviceBytesAfterBuild = 0, deviceBytesPeak = 0;
    std::vector<std::pair<std::string, uint64_t>> deviceBytesPerResource;  // after build
    std::vector<std::pair<std::string, uint64_t>> hostBytes;
    std::vector<ErrorSample> curve;
    std::optional<double> slope;           // log-log slope of RMSE against spp
    std::optional<TimeToTarget> toTarget;
    double targetRmse = 0;
    double costRatioToDense = 0;           // seconds per path / dense's; 0 when no dense run
    std::string error;                     // non-empty: the run failed with this message
};

struct ReferenceInfo {
    std::string dataset, tf, mode, file, command;
    uint32_t spp = 0;
    double seconds = 0, rmseOfReference = 0;  // the reference's own noise (sqrt of mean variance)
    bool cached = false;
};

struct AutoResult {
    std::string dataset, tf, mode;
    render::AutoChoice choice;
    std::string bestLabel;        // best measured matrix combination (by efficiency)
    double pickEfficiency = 0, bestEfficiency = 0;  // 1 / (final MSE x seconds), from the timed runs
    double pickFps = 0, bestFps = 0;
};

struct DatasetInfo {
    std::string tag, input, field;
    uint64_t cells = 0;
    int levels = 0;
    std::string bounds;
};

struct BenchResults {
    std::string device, driver, deviceType, commandLine, date;
    std::string tfColors;  // scene::tfColorsName of BenchOptions::tfColors
    int width = 0, height = 0;
    uint32_t frames = 0, warmup = 0, referenceSpp = 0;
    uint32_t samplesPerInvocation = 1;  // frames one GPU thread takes per dispatch (gpu::Context)
    std::vector<DatasetInfo> datasets;
    std::vector<ReferenceInfo> references;
    std::vector<RunResult> runs;
    std::vector<AutoResult> autos;
};

// Progress: (runs done, runs total, what runs now).
using BenchProgress = std::function<void(size_t, size_t, const std::string&)>;

// Runs everything `options` selects on `ctx`. Failing combinations are recorded, not fatal.
BenchResults runBench(gpu::Context& ctx, const BenchOptions& options, const BenchProgress& progress = {});

}  // namespace amrvk::bench
