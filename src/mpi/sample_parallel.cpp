#include "mpi/sample_parallel.h"

#include <algorithm>

#include "core/error.h"
#include "core/stats.h"

namespace amrvk::mpi {

uint64_t pictureFingerprint(const session::Session& s) {
    session::Session what = s;
    what.structure = {};  // ranks may build different structures for the same picture (auto, per-part fits)
    return std::hash<std::string>{}(session::sessionJson(what));
}

SampleRange sampleRange(uint32_t spp, int rank, int size) {
    AMRVK_CHECK(size >= 1 && rank >= 0 && rank < size, "internal: rank ", rank, " of ", size);
    const auto at = [&](int r) { return uint32_t(uint64_t(spp) * uint64_t(r) / uint64_t(size)); };
    return {at(rank), at(rank + 1) - at(rank)};
}

scene::RenderStats statsOverRanks(World& world, const scene::RenderStats& mine, uint64_t& sent) {
    std::vector<uint64_t> counts(mine.counters.begin(), mine.counters.end());
    counts.push_back(mine.paths);
    sent += world.sumEverywhere(counts);
    scene::RenderStats all;
    for (size_t k = 0; k < all.counters.size(); ++k) all.counters[k] = counts[k];
    all.paths = counts.back();
    all.gpuSeconds = world.maxOverRanks(mine.gpuSeconds);
    sent += sizeof(double);
    return all;
}

nlohmann::ordered_json gatherRankReports(World& world, nlohmann::ordered_json rankInfo, gpu::Context& ctx,
                                         uint64_t& moved) {
    rankInfo["rank"] = world.rank();
    rankInfo["host"] = world.host();
    rankInfo["localRank"] = world.localRank();
    rankInfo["device"] = ctx.deviceReport().name;
    rankInfo["hostPeakBytes"] = peakResidentBytes();
    rankInfo["deviceMemoryPeakBytes"] = ctx.memory().peakBytes();
    const std::vector<std::string> reports = world.gatherToRoot(rankInfo.dump());
    if (world.rank() != 0) return nullptr;
    nlohmann::ordered_json ranks = nlohmann::ordered_json::array();
    for (size_t r = 0; r < reports.size(); ++r) {
        ranks.push_back(nlohmann::ordered_json::parse(reports[r]));
        // what the rank sent while rendering, and (ranks > 0) this report itself
        moved += ranks.back()["bytesSent"].get<uint64_t>() + (r > 0 ? reports[r].size() : 0);
    }
    return ranks;
}

SampleShare renderSamples(World& world, render::Renderer& renderer, uint32_t spp,
                          const std::function<void(uint32_t, uint32_t)>& progress,
                          const std::vector<uint32_t>& snapshotSpp,
                          const std::function<void(const scene::RenderOutput&)>& snapshot) {
    AMRVK_CHECK(spp >= 1, "--spp must be at least 1");
    std::vector<uint32_t> marks;
    for (uint32_t s : snapshotSpp)
        if (s > 0 && s < spp && (marks.empty() || s > marks.back())) marks.push_back(s);
    marks.push_back(spp);
    scene::AccumulatedSums total;
    SampleShare result;
    uint32_t done = 0;
    for (uint32_t mark : marks) {
        const SampleRange share = sampleRange(mark - done, world.rank(), world.size());
        if (done == 0) result.firstSample = share.first;
        result.samples += share.count;
        std::string error;
        const Timer render;
        try {
            renderer.setFirstSample(done + share.first);
            renderer.accumulate(share.count, [&](uint32_t d, uint32_t) {
                if (progress) progress(std::min(mark, done + d * uint32_t(world.size())), spp);
            });
            const scene::AccumulatedSums part = renderer.sums();
            if (total.values.empty())
                total = part;
            else
                for (size_t i = 0; i < part.values.size(); ++i) total.values[i] += part.values[i];
            const scene::RenderStats& s = renderer.stats();
            result.mine.paths += s.paths;
            result.mine.gpuSeconds += s.gpuSeconds;
            for (size_t k = 0; k < s.counters.size(); ++k) result.mine.counters[k] += s.counters[k];
        } catch (const std::exception& e) {
            error = e.what();
        }
        result.renderSeconds += render.seconds();
        Failure f = world.agree(error, {}, 20, false);
        if (f.fatal) throw PeerFailed(std::move(f));
        AMRVK_CHECK(f.rank < 0, "rank ", f.rank, " of ", world.size(), ": ",
                    f.message.empty() ? std::string("failed") : f.message);
        const Timer reduce;
        std::vector<double> sums = total.values;
        result.bytesSent += world.sumEverywhere(sums);
        const scene::RenderStats all = statsOverRanks(world, result.mine, result.bytesSent);
        result.out =
            scene::outputFromSums({.width = total.width, .height = total.height, .values = std::move(sums)}, mark, all);
        result.reduceSeconds += reduce.seconds();
        done = mark;
        if (snapshot && std::find(snapshotSpp.begin(), snapshotSpp.end(), mark) != snapshotSpp.end()) snapshot(result.out);
    }
    return result;
}

SampleParallelResult renderSampleParallel(World& world, picture::Picture& p, nlohmann::ordered_json rankInfo,
                                          const std::function<void(uint32_t, uint32_t)>& progress) {
    world.checkpoint();  // every rank has its picture (or one failed: all stop here, nothing written)
    world.requireSame(pictureFingerprint(p.session()), "the picture (data, options or fitted choices)");
    world.requireSame(p.volume->model.cellCount(), "the data set (cell count)");
    render::Renderer& renderer = *p.renderer;
    SampleShare share = renderSamples(world, renderer, p.described.spp, progress);
    rankInfo["firstSample"] = share.firstSample;
    rankInfo["samples"] = share.samples;
    rankInfo["paths"] = share.mine.paths;
    rankInfo["gpuSeconds"] = share.mine.gpuSeconds;
    rankInfo["renderSeconds"] = share.renderSeconds;
    rankInfo["reduceSeconds"] = share.reduceSeconds;
    rankInfo["bytesSent"] = share.bytesSent;
    uint64_t moved = 0;
    nlohmann::ordered_json ranks = gatherRankReports(world, std::move(rankInfo), renderer.context(), moved);
    SampleParallelResult result;
    result.out = std::move(share.out);
    if (world.rank() == 0)
        result.mpi = {{"ranks", world.size()},
                      {"distribute", "samples"},
                      {"bytesMoved", moved},
                      {"bytesMovedPerPath", result.out.stats.paths > 0 ? double(moved) / double(result.out.stats.paths) : 0.0},
                      {"perRank", std::move(ranks)}};
    return result;
}

}  // namespace amrvk::mpi
