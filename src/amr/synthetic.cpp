#include "amr/synthetic.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <type_traits>
#include <utility>

#include "amr/cell_sinks.h"
#include "amr/octree_refine.h"
#include "amr/synthetic_fields.h"
#include "amr/threshold_search.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/stats.h"

namespace fs = std::filesystem;

namespace amrvk::amr {

namespace {

constexpr int kMaxBlockCells = 32;            // largest block edge B
// B is halved until N >= minBlocks * B^3: 64 blocks, 512 for the teapot, whose stadium alone
// takes a few hundred leaves (with fewer its object stays unresolved).
constexpr uint64_t kMinBlocks = 64, kMinTeapotBlocks = 512;

constexpr std::pair<SyntheticKind, std::string_view> kKindNames[] = {
    {SyntheticKind::Cloud, "cloud"}, {SyntheticKind::Shells, "shells"}, {SyntheticKind::Teapot, "teapot"}};

}  // namespace

SyntheticKind parseSyntheticKind(std::string_view name) {
    for (const auto& [kind, kindName] : kKindNames)
        if (kindName == name) return kind;
    AMRVK_CHECK(false, "unknown synthetic kind '", name, "' (expected cloud, shells or teapot)");
    return SyntheticKind::Cloud;
}

std::string_view syntheticKindName(SyntheticKind kind) {
    for (const auto& [k, kindName] : kKindNames)
        if (k == kind) return kindName;
    return "?";
}

int syntheticBlockCells(const SyntheticParams& params) {
    const int requested = params.blockCells;
    AMRVK_CHECK(requested >= 1 && requested <= kMaxBlockCells && (requested & (requested - 1)) == 0,
                "--block ", requested, " is not a power of two in [1, ", kMaxBlockCells, "]");
    const uint64_t minBlocks = params.kind == SyntheticKind::Teapot ? kMinTeapotBlocks : kMinBlocks;
    uint64_t b = static_cast<uint64_t>(requested);
    while (b > 1 && params.cells < minBlocks * b * b * b) b /= 2;
    return static_cast<int>(b);
}

namespace {

int log2Exact(int powerOfTwo) { return std::countr_zero(static_cast<unsigned>(powerOfTwo)); }

// Depth of the node octree in node levels (finest nodes = blocks), before adding blockShift.
// `leaves`: the target count in blocks.
int nodeRootLevel(SyntheticKind kind, double leaves, int blockShift) {
    const double n = std::max(leaves, 8.0);
    int root = 0;
    switch (kind) {
        // Cloud and shells scores are scale-free, so the depth only caps the refinement; these
        // put the finest nodes at the finest or next level (measured for N = 1e3..1e7 with B = 1).
        // Cloud: volume-filling, most cells on the two finest levels.
        case SyntheticKind::Cloud: root = static_cast<int>(std::ceil(std::log2(n) / 3.0)) + 3; break;
        // Shells: surfaces, cells grow as 4^depth; at least 1.5 N possible cells.
        case SyntheticKind::Shells:
            root = std::max(static_cast<int>(std::lround(std::log2(n) / 2.0 - 0.75)),
                            static_cast<int>(std::ceil(std::log2(1.5 * n) / 3.0)));
            break;
        // A stadium at least 2^20 cells and 2^12 object sizes wide around an object of radius
        // ~sqrt(leaves) nodes.
        case SyntheticKind::Teapot:
            root = std::max(20 - blockShift,
                            static_cast<int>(std::ceil(std::log2(4.0 * teapotMajorRadius(leaves, 30)))) + 12);
            break;
    }
    return std::clamp(root, 3, kMaxLevel - blockShift);
}

// Target count in blocks of `blockCells`^3 cells.
double targetLeaves(const SyntheticParams& params, int blockCells) {
    return static_cast<double>(params.cells) / std::ldexp(1.0, 3 * log2Exact(blockCells));
}

}  // namespace

int syntheticRootLevel(const SyntheticParams& params) {
    const int block = syntheticBlockCells(params);
    const int shift = log2Exact(block);
    if (params.levels != 0) {
        AMRVK_CHECK(params.levels >= 1 && params.levels <= kMaxLevel + 1 - shift, "--levels ", params.levels,
                    " is outside [1, ", kMaxLevel + 1 - shift, "] for blocks of ", block, "^3 cells");
        return params.levels - 1 + shift;
    }
    return nodeRootLevel(params.kind, targetLeaves(params, block), shift) + shift;
}

namespace {

// Calls fn(field, blockShift) with the concrete field object (amr/synthetic_fields.h) for `params`.
template <class Fn>
void withField(const SyntheticParams& params, Fn&& fn) {
    const int block = syntheticBlockCells(params);
    const int shift = log2Exact(block);
    const int root = syntheticRootLevel(params);
    switch (params.kind) {
        case SyntheticKind::Cloud: fn(CloudField(params.seed, root, params.time), shift); break;
        case SyntheticKind::Shells: fn(ShellsField(params.seed, root, params.time), shift); break;
        case SyntheticKind::Teapot:
            fn(TeapotField(params.seed, root, teapotMajorRadius(targetLeaves(params, block), root - shift) * block,
                           params.time),
               shift);
            break;
    }
}

void checkParams(const SyntheticParams& params) {
    AMRVK_CHECK(std::isfinite(params.time) && std::abs(params.time) <= 1e6, "--time ", params.time,
                " is outside [-1e6, 1e6]");
    AMRVK_CHECK(params.cells >= 1 && params.cells <= 100'000'000'000ull, "--cells ", params.cells,
                " is outside [1, 1e11]");
    syntheticRootLevel(params);
}

std::string fieldName(const SyntheticParams& params) {
    return params.field.empty() ? "scalars" : params.field;
}

// Fills stats for `params` (already checked): the threshold search over the field of `params`,
// whose writing pass runs into makeSink(cap) and, when its count is accepted, calls keep(sink)
// and takes the cell statistics from the sink.
template <class MakeSink, class Keep>
void runSynthetic(const SyntheticParams& params, SyntheticStats& stats, MakeSink&& makeSink, Keep&& keep) {
    stats.blockCells = syntheticBlockCells(params);
    stats.rootLevel = syntheticRootLevel(params);
    withField(params, [&](const auto& field, int blockShift) {
        RefinementPasses passes;
        passes.bestFirst = [&](uint64_t maxLeaves, bool& exhausted) {
            return bestFirstScores(field, blockShift, maxLeaves, exhausted);
        };
        passes.count = [&](double t, uint64_t cap, uint64_t expected, const std::string& phase) {
            CountSink counter(cap, expected, &params.progress, phase);
            runDepthFirst(field, blockShift, static_cast<float>(t), counter);
            return ThresholdSample{t, counter.count(), counter.stopped()};
        };
        passes.write = [&](float t, uint64_t cap, uint64_t minAccept) {
            auto sink = makeSink(cap);
            runDepthFirst(field, blockShift, t, sink);
            if (sink.stopped() || sink.count() < minAccept) return FinalPass{sink.count(), sink.stopped(), false};
            keep(sink);
            sink.fillStats(stats);
            return FinalPass{sink.count(), false, true};
        };
        searchAndGenerate(passes, blockShift, params, stats);
    });
    stats.targetReached = static_cast<double>(stats.cells) * kCountTolerance >= static_cast<double>(params.cells);
}

}  // namespace

SyntheticStats generateSynthetic(const SyntheticParams& params, const fs::path& base) {
    const Timer timer;
    checkParams(params);
    fs::path cellsPath = base, scalarsPath = base;
    cellsPath += ".cells";
    scalarsPath += params.field.empty() ? ".scalars" : "." + params.field + ".scalars";
    { AtomicFileWriter probe(cellsPath); }  // fail before the search when BASE is not writable

    SyntheticStats stats;
    runSynthetic(
        params, stats,
        [&](uint64_t cap) { return FileSink(cellsPath, scalarsPath, cap, params.cells, &params.progress); },
        [&](FileSink& sink) { stats.bytes = sink.commit(); });
    stats.seconds = timer.seconds();
    return stats;
}

Model makeSyntheticModel(const SyntheticParams& params, SyntheticStats* statsOut) {
    const Timer timer;
    checkParams(params);
    SyntheticStats stats;
    Model model{.format = "synthetic",
                .source = strCat("synthetic ", syntheticKindName(params.kind), " (seed ", params.seed, ", ",
                                 params.cells, " cells)"),
                .availableFields = {fieldName(params)}};
    runSynthetic(
        params, stats, [&](uint64_t cap) { return MemorySink(cap, params.cells, &params.progress); },
        [&](MemorySink& sink) {
            model.cells = sink.takeCells();
            model.fields = {Field{fieldName(params), sink.takeValues()}};
        });
    model.attributes = {{"kind", std::string(syntheticKindName(params.kind))},
                        {"seed", std::to_string(params.seed)},
                        {"rootLevel", std::to_string(stats.rootLevel)},
                        {"blockCells", std::to_string(stats.blockCells)},
                        {"threshold", strCat(stats.threshold)}};
    if (params.time != 0) model.attributes.emplace_back("time", strCat(params.time));
    stats.seconds = timer.seconds();
    if (statsOut) *statsOut = stats;
    return model;
}

}  // namespace amrvk::amr
