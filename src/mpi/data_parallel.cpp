#include "mpi/data_parallel.h"

#include <cmath>
#include <span>
#include <limits>
#include <string>

#include "core/error.h"
#include "core/progress.h"
#include "core/stats.h"
#include "mpi/sample_parallel.h"
#include "render/staged_pass.h"
#include "scene/camera.h"
#include "shared/data_parallel_gpu.h"

namespace amrvk::mpi {

DataPart loadPart(World& world, const session::PictureDescription& d) {
    const session::Session& s = d.session;
    AMRVK_CHECK(!s.input.empty(), "no input data set (give one, or --session FILE)");
    AMRVK_CHECK(s.settings.mode != scene::Mode::Dvr, "--distribute data: mode dvr is not supported (use ae, ss or ms)");
    amr::ReadOptions ro = s.read;
    ro.fields = s.field.empty() ? std::vector<std::string>{} : std::vector<std::string>{s.field};
    DataPart part;
    Timer timer;
    {
        ProgressStage stage("census of " + s.input);
        part.census = amr::censusOf(s.input, ro);
    }
    part.censusSeconds = timer.seconds();
    part.owned = amr::partitionByCells(part.census, world.size());
    const amr::Box3l& mine = part.owned[size_t(world.rank())];
    timer = Timer();
    amr::Model model;
    {
        ProgressStage stage("reading this rank's part of " + s.input);
        ro.scale = part.census.scale;  // resolved once by the census
        ro.logFloor = part.census.logFloor;
        model = amr::readPart(s.input, ro, mine);
    }
    part.readSeconds = timer.seconds();
    AMRVK_CHECK(!model.cells.empty(), s.input, ": rank ", world.rank(), "'s part holds no cells (use fewer ranks)");
    // The whole field's percentiles (the presets are fitted to them): each rank counts the values of
    // the cells it owns, so every cell counts once, and the counts are summed over the ranks.
    std::vector<float> owned;
    amr::CellArray ownedCells;
    const std::vector<float>& values = model.fields.at(0).values;
    for (size_t i = 0; i < model.cells.size(); ++i)
        if (amr::ownsCell(mine, model.cells[i])) {
            owned.push_back(values[i]);
            ownedCells.push_back(model.cells[i]);
        }
    part.ownedCells = owned.size();
    world.checkpoint();  // every rank read its part: the sums below are collective
    amr::PercentileSelection selection;
    while (!selection.done()) {
        std::vector<uint64_t> counts = selection.count(owned);
        world.sumEverywhere(counts);
        selection.advance(counts);
    }
    const amr::CellCensus& whole = part.census;
    // The space each value fills, likewise: every rank bins the cells it owns over the whole range.
    amr::VolumeHistogram histogram = amr::volumeHistogramOf(ownedCells, owned, whole.valueLo, whole.valueHi,
                                                            whole.minLevel, whole.bounds.volume());
    world.sumEverywhere(histogram.volume);
    owned = {};
    ownedCells = {};
    part.volume = scene::makeVolume(std::move(model), s.field,
                                    scene::VolumeFrame{.bounds = whole.bounds,
                                                       .minLevel = whole.minLevel,
                                                       .valueLo = whole.valueLo,
                                                       .valueHi = whole.valueHi,
                                                       .percentiles = selection.result(),
                                                       .volumeHistogram = std::move(histogram)});
    return part;
}

namespace {

// The replicated paths must be the same on every rank before a reduction combines them: ranks that
// diverged (different drivers, devices or --shader-dir) would otherwise hang on different counts or
// reduce other paths' values. One collective of two words: the live count and an FNV-1a hash of
// the live indices.
void requireSameLive(World& world, std::span<const uint32_t> live, render::StagedStep at, const char* stage) {
    uint64_t h = 1469598103934665603ull ^ live.size();
    for (uint32_t i : live) h = (h ^ i) * 1099511628211ull;
    world.requireSame(h, strCat("the paths alive before the ", stage, " reduction of sample ", at.sample, ", bounce ", at.bounce),
                      "the ranks' paths diverged: run every rank with the same driver, device kind and shaders");
}

}  // namespace

DataParallelResult renderDataParallel(World& world, picture::Picture& p, const DataPart& part,
                                      nlohmann::ordered_json rankInfo,
                                      const std::function<void(uint32_t, uint32_t)>& progress) {
    render::Renderer& renderer = *p.renderer;
    gpu::Context& ctx = renderer.context();
    // Every rank must cut the same data the same way and trace the same paths.
    std::string census = strCat(part.census.cells, "|", part.census.binWidth);
    for (const amr::Box3l& b : part.owned)
        for (int a = 0; a < 3; ++a) census += strCat("|", b.lower[a], ",", b.upper[a]);  // GCC 12: no false -Wrestrict
    world.requireSame(std::hash<std::string>{}(census), "the data set (census and partition)");
    world.requireSame(pictureFingerprint(p.session()), "the picture (options or fitted choices)");
    renderer.resetAccumulation();

    // The exchange between the ranks: the nearest collision with its owner's colour, and the
    // product of the shadow transmittances, each after checking that the ranks hold the same paths.
    uint64_t bytes = 0, reductions = 0;
    std::vector<World::FloatRank> nearest;
    std::vector<float> colors;
    render::StagedRender staged;
    const scene::Volume& v = renderer.volume();
    const amr::Box3l& mine = part.owned[size_t(world.rank())];
    staged.ownedLo = glm::vec3(v.toLocal(glm::dvec3(mine.lower)));
    staged.ownedHi = glm::vec3(v.toLocal(glm::dvec3(mine.upper)));
    staged.rankSeed = 0x9E3779B9u * uint32_t(world.rank() + 1);
    staged.exchange.collisions = [&](std::span<const uint32_t> live, std::span<shared::DataParallelHitGpu> hits,
                                     render::StagedStep at) {
        requireSameLive(world, live, at, "collision");
        if (live.empty()) return;
        nearest.resize(live.size());
        colors.assign(live.size() * 3, 0.0f);
        for (size_t k = 0; k < live.size(); ++k) nearest[k] = {hits[k].t, world.rank()};
        bytes += world.minLocEverywhere(nearest);
        for (size_t k = 0; k < live.size(); ++k)
            if (nearest[k].rank == world.rank())
                for (int c = 0; c < 3; ++c) colors[3 * k + size_t(c)] = hits[k].color[c];
        bytes += world.sumEverywhere(colors);
        reductions += 2;
        for (size_t k = 0; k < live.size(); ++k)
            hits[k] = {nearest[k].value, glm::vec3(colors[3 * k], colors[3 * k + 1], colors[3 * k + 2])};
    };
    staged.exchange.shadows = [&](std::span<const uint32_t> live, std::span<float> transmittance,
                                  render::StagedStep at) {
        requireSameLive(world, live, at, "shadow");
        if (live.empty()) return;
        bytes += world.productEverywhere(transmittance);
        ++reductions;
    };
    const Timer wall;
    const render::StagedReport report = renderer.accumulateStaged(staged, p.described.spp, progress);
    const scene::RenderStats& stats = report.stats;
    const uint32_t spp = p.described.spp;

    // Tracking counters are sums over the ranks' boxes; the shading ones (bounce limit, NaN) were
    // counted alike on every rank, as were the paths.
    scene::RenderStats all = statsOverRanks(world, stats, bytes);
    for (uint32_t k : {shared::kCounterBounceLimitHits, shared::kCounterNanSamples})
        all.counters[k] = stats.counters[k];
    all.paths = stats.paths;
    DataParallelResult result;
    result.out = scene::outputFromSums(renderer.sums(), spp, all);

    const uint64_t held = v.model.cellCount();
    rankInfo["ownedBox"] = {{mine.lower.x, mine.lower.y, mine.lower.z}, {mine.upper.x, mine.upper.y, mine.upper.z}};
    rankInfo["ownedCells"] = part.ownedCells;
    rankInfo["heldCells"] = held;
    rankInfo["haloCells"] = held - part.ownedCells;
    rankInfo["censusSeconds"] = part.censusSeconds;
    rankInfo["readPartSeconds"] = part.readSeconds;
    rankInfo["densityLookups"] = stats.counters[shared::kCounterDensityLookups];
    rankInfo["renderSeconds"] = wall.seconds();
    rankInfo["mpiSeconds"] = report.exchangeSeconds;
    rankInfo["reductions"] = reductions;
    rankInfo["bytesSent"] = bytes;
    rankInfo["hostModelBytes"] = v.modelBytes();
    uint64_t moved = 0;
    nlohmann::ordered_json ranks = gatherRankReports(world, std::move(rankInfo), ctx, moved);
    if (world.rank() == 0)
        result.mpi = {{"ranks", world.size()},
                      {"distribute", "data"},
                      {"cells", part.census.cells},
                      {"bounces", report.bounces},
                      {"bytesMoved", moved},
                      {"bytesMovedPerPath", all.paths > 0 ? double(moved) / double(all.paths) : 0.0},
                      {"perRank", std::move(ranks)}};
    return result;
}

}  // namespace amrvk::mpi
