#include "mpi/data_parallel.h"

#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"
#include "core/progress.h"
#include "core/stats.h"
#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "mpi/sample_parallel.h"
#include "render/path_trace_pass.h"
#include "scene/camera.h"
#include "shared/data_parallel_gpu.h"

namespace amrvk::mpi {

DataPart loadPart(World& world, session::PictureDescription& d) {
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
        ro.logFloor = part.census.logFloor;  // found once by the census
        model = amr::readPart(s.input, ro, mine);
    }
    part.readSeconds = timer.seconds();
    AMRVK_CHECK(!model.cells.empty(), s.input, ": rank ", world.rank(), "'s part holds no cells (use fewer ranks)");
    // The whole field's percentiles (the presets are fitted to them): each rank counts the values of
    // the cells it owns, so every cell counts once, and the counts are summed over the ranks.
    std::vector<float> owned;
    const std::vector<float>& values = model.fields.at(0).values;
    for (size_t i = 0; i < model.cells.size(); ++i)
        if (amr::ownsCell(mine, model.cells[i])) owned.push_back(values[i]);
    part.ownedCells = owned.size();
    world.checkpoint();  // every rank read its part: the sums below are collective
    amr::PercentileSelection selection;
    while (!selection.done()) {
        std::vector<uint64_t> counts = selection.count(owned);
        world.sumEverywhere(counts);
        selection.advance(counts);
    }
    owned = {};
    const amr::CellCensus& whole = part.census;
    part.volume = scene::makeVolume(std::move(model), s.field,
                                    scene::VolumeFrame{.localOrigin = whole.bounds.lower,
                                                       .minLevel = whole.minLevel,
                                                       .valueLo = whole.valueLo,
                                                       .valueHi = whole.valueHi,
                                                       .percentiles = selection.result()});
    // The camera frames the whole data set, not this part.
    if (d.fitCamera) {
        const amr::Transform& t = whole.head.voxelToWorld;
        d.session.settings.camera =
            scene::defaultCamera(t.toWorld(glm::dvec3(whole.bounds.lower)), t.toWorld(glm::dvec3(whole.bounds.upper)),
                                 d.session.settings.camera.fovYDegrees);
        d.fitCamera = false;
    }
    return part;
}

namespace {

// The buffers and pipeline of one data-parallel render.
struct Batch {
    gpu::Context& ctx;
    gpu::ComputePipeline pipeline;
    gpu::Buffer paths, hits, shadow, counters;
    shared::DataParallelPush push{};

    // One stage over every path, its counters zeroed first (one submission).
    void run(uint32_t stage) {
        push.stage = stage;
        ctx.submitAndWait(
            [&](VkCommandBuffer cmd) {
                vkCmdFillBuffer(cmd, counters.handle(), 0, VK_WHOLE_SIZE, 0);
                gpu::computeBarrier(cmd);
                pipeline.dispatch(cmd, &push, (push.count + 63) / 64);
            },
            pipeline.name());
    }
    std::array<uint32_t, shared::kCounterCount + 1> readCounters() const {
        std::array<uint32_t, shared::kCounterCount + 1> c{};
        counters.download(c.data(), sizeof c);
        return c;
    }
};

// The replicated paths must be the same on every rank before a reduction combines them: ranks that
// diverged (different drivers, devices or --shader-dir) would otherwise hang on different counts or
// reduce other paths' values. One collective of two words: the live count and an FNV-1a hash of
// the live indices.
void requireSameLive(World& world, const std::vector<uint32_t>& live, uint32_t sample, uint64_t bounce,
                     const char* stage) {
    uint64_t h = 1469598103934665603ull ^ live.size();
    for (uint32_t i : live) h = (h ^ i) * 1099511628211ull;
    world.requireSame(h, strCat("the paths alive before the ", stage, " reduction of sample ", sample, ", bounce ", bounce),
                      "the ranks' paths diverged: run every rank with the same driver, device kind and shaders");
}

}  // namespace

DataParallelResult renderDataParallel(World& world, picture::Picture& p, const DataPart& part,
                                      nlohmann::ordered_json rankInfo,
                                      const std::function<void(uint32_t, uint32_t)>& progress) {
    render::Renderer& renderer = *p.renderer;
    gpu::Context& ctx = renderer.context();
    const scene::RenderSettings& rs = renderer.settings();
    const scene::StructureConfig& config = renderer.config();
    const uint32_t count = uint32_t(rs.width) * uint32_t(rs.height);
    // Every rank must cut the same data the same way and trace the same paths.
    std::string census = strCat(part.census.cells, "|", part.census.binWidth);
    for (const amr::Box3l& b : part.owned)
        for (int a = 0; a < 3; ++a) census += strCat("|", b.lower[a], ",", b.upper[a]);  // GCC 12: no false -Wrestrict
    world.requireSame(std::hash<std::string>{}(census), "the data set (census and partition)");
    world.requireSame(pictureFingerprint(p.session), "the picture (options or fitted choices)");
    renderer.setSettings(rs);
    renderer.resetAccumulation();
    const uint64_t params = renderer.paramsAddress();

    Batch b{ctx,
            render::compilePathTracer(ctx, "path_trace_dp", sizeof(shared::DataParallelPush), rs.mode, config,
                                      renderer.shaders()),
            gpu::Buffer(ctx, uint64_t(count) * sizeof(shared::PathStateGpu), gpu::MemoryKind::Device,
                        "dataParallelPaths"),
            gpu::Buffer(ctx, uint64_t(count) * sizeof(shared::DataParallelHitGpu), gpu::MemoryKind::HostRead,
                        "dataParallelHits"),
            gpu::Buffer(ctx, uint64_t(count) * sizeof(float), gpu::MemoryKind::HostRead, "dataParallelShadow"),
            gpu::Buffer(ctx, (shared::kCounterCount + 1) * sizeof(uint32_t), gpu::MemoryKind::HostRead,
                        "dataParallelCounters")};
    const scene::Volume& v = renderer.volume();
    const amr::Box3l& mine = part.owned[size_t(world.rank())];
    b.push.params = params;
    b.push.paths = b.paths.address();
    b.push.hits = b.hits.address();
    b.push.shadow = b.shadow.address();
    b.push.counters = b.counters.address();
    b.push.ownedLo = glm::vec3(v.toLocal(glm::dvec3(mine.lower)));
    b.push.ownedHi = glm::vec3(v.toLocal(glm::dvec3(mine.upper)));
    b.push.count = count;
    b.push.rankSeed = 0x9E3779B9u * uint32_t(world.rank() + 1);

    scene::RenderStats stats;
    std::vector<shared::DataParallelHitGpu> hits(count);
    std::vector<float> shadow(count);
    std::vector<uint32_t> live;  // indices of the paths in this reduction (the same on every rank)
    std::vector<World::FloatRank> nearest;
    std::vector<float> colors, transmittance;
    uint64_t bytes = 0, reductions = 0, bounces = 0;
    double mpiSeconds = 0;
    const Timer wall;
    auto addCounters = [&] {
        const auto c = b.readCounters();
        for (uint32_t k = 0; k < shared::kCounterCount; ++k) stats.counters[k] += c[k];
        return c[shared::kCounterCount];
    };
    const uint32_t spp = p.session.spp;
    for (uint32_t sample = 0; sample < spp; ++sample) {
        b.push.sampleIndex = sample;
        b.run(shared::kDpStageGenerate);
        for (;;) {
            // Local first collisions, then the nearest over ranks with its owner's colour.
            b.run(shared::kDpStageTrack);
            addCounters();
            b.hits.download(hits.data(), hits.size() * sizeof(hits[0]));
            live.clear();
            for (uint32_t i = 0; i < count; ++i)
                if (hits[i].t >= 0) live.push_back(i);
            requireSameLive(world, live, sample, bounces, "collision");
            if (live.empty()) break;
            nearest.resize(live.size());
            colors.assign(live.size() * 3, 0.0f);
            for (size_t k = 0; k < live.size(); ++k) nearest[k] = {hits[live[k]].t, world.rank()};
            Timer mpi;
            bytes += world.minLocEverywhere(nearest);
            for (size_t k = 0; k < live.size(); ++k)
                if (nearest[k].rank == world.rank())
                    for (int c = 0; c < 3; ++c) colors[3 * k + size_t(c)] = hits[live[k]].color[c];
            bytes += world.sumEverywhere(colors);
            mpiSeconds += mpi.seconds();
            reductions += 2;
            for (size_t k = 0; k < live.size(); ++k)
                hits[live[k]] = {nearest[k].value, glm::vec3(colors[3 * k], colors[3 * k + 1], colors[3 * k + 2])};
            b.hits.upload(hits.data(), hits.size() * sizeof(hits[0]));
            b.run(shared::kDpStageShade);
            const uint32_t stillLive = addCounters();
            ++bounces;
            // Shadow rays: the product of the local transmittances.
            b.run(shared::kDpStageShadow);
            addCounters();
            b.shadow.download(shadow.data(), shadow.size() * sizeof(float));
            live.clear();
            for (uint32_t i = 0; i < count; ++i)
                if (shadow[i] >= 0) live.push_back(i);
            requireSameLive(world, live, sample, bounces, "shadow");
            if (!live.empty()) {
                transmittance.resize(live.size());
                for (size_t k = 0; k < live.size(); ++k) transmittance[k] = shadow[live[k]];
                mpi = Timer();
                bytes += world.productEverywhere(transmittance);
                mpiSeconds += mpi.seconds();
                ++reductions;
                for (size_t k = 0; k < live.size(); ++k) shadow[live[k]] = transmittance[k];
                b.shadow.upload(shadow.data(), shadow.size() * sizeof(float));
                b.run(shared::kDpStageResolve);
            }
            if (stillLive == 0) break;
        }
        b.run(shared::kDpStageAccumulate);
        addCounters();
        stats.paths += count;
        if (progress) progress(sample + 1, spp);
    }
    stats.gpuSeconds = wall.seconds() - mpiSeconds;  // stages, downloads and uploads; MPI excluded

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
    rankInfo["mpiSeconds"] = mpiSeconds;
    rankInfo["reductions"] = reductions;
    rankInfo["bytesSent"] = bytes;
    rankInfo["hostModelBytes"] = v.modelBytes();
    uint64_t moved = 0;
    nlohmann::ordered_json ranks = gatherRankReports(world, std::move(rankInfo), ctx, moved);
    if (world.rank() == 0)
        result.mpi = {{"ranks", world.size()},
                      {"distribute", "data"},
                      {"cells", part.census.cells},
                      {"bounces", bounces},
                      {"bytesMoved", moved},
                      {"bytesMovedPerPath", all.paths > 0 ? double(moved) / double(all.paths) : 0.0},
                      {"perRank", std::move(ranks)}};
    return result;
}

}  // namespace amrvk::mpi
