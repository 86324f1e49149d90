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

SampleParallelResult renderSampleParallel(World& world, picture::Picture& p, nlohmann::ordered_json rankInfo,
                                          const std::function<void(uint32_t, uint32_t)>& progress) {
    render::Renderer& renderer = *p.renderer;
    const SampleRange range = sampleRange(p.session.spp, world.rank(), world.size());
    const Timer wall;
    renderer.setSettings(renderer.settings());
    renderer.setFirstSample(range.first);
    renderer.accumulate(range.count, [&](uint32_t done, uint32_t) {
        if (progress) progress(done, range.count);
    });
    const double renderSeconds = wall.seconds();
    scene::AccumulatedSums sums = renderer.sums();
    const scene::RenderStats mine = renderer.stats();

    world.checkpoint();  // every rank rendered (or one failed: all stop here, nothing written)
    world.requireSame(pictureFingerprint(p.session), "the picture (data, options or fitted choices)");
    world.requireSame(p.volume->model.cellCount(), "the data set (cell count)");
    const Timer reduceTimer;
    uint64_t sent = world.sumToRoot(sums.values);
    const scene::RenderStats all = statsOverRanks(world, mine, sent);

    rankInfo["firstSample"] = range.first;
    rankInfo["samples"] = range.count;
    rankInfo["paths"] = mine.paths;
    rankInfo["gpuSeconds"] = mine.gpuSeconds;
    rankInfo["renderSeconds"] = renderSeconds;
    rankInfo["reduceSeconds"] = reduceTimer.seconds();
    rankInfo["bytesSent"] = sent;
    uint64_t moved = 0;
    nlohmann::ordered_json ranks = gatherRankReports(world, std::move(rankInfo), renderer.context(), moved);

    SampleParallelResult result;
    if (world.rank() != 0) {
        result.out = scene::outputFromSums(sums, range.count, mine);
        return result;
    }
    result.out = scene::outputFromSums(sums, p.session.spp, all);
    result.mpi = {{"ranks", world.size()},
                  {"distribute", "samples"},
                  {"bytesMoved", moved},
                  {"bytesMovedPerPath", all.paths > 0 ? double(moved) / double(all.paths) : 0.0},
                  {"perRank", std::move(ranks)}};
    return result;
}

scene::RenderOutput renderSamplesShared(World& world, render::Renderer& renderer, const scene::RenderSettings& settings,
                                        uint32_t spp, const std::function<void(uint32_t, uint32_t)>& progress,
                                        const std::vector<uint32_t>& snapshotSpp,
                                        const std::function<void(const scene::RenderOutput&)>& snapshot) {
    AMRVK_CHECK(spp >= 1, "--spp must be at least 1");
    std::vector<uint32_t> marks;
    for (uint32_t s : snapshotSpp)
        if (s > 0 && s < spp && (marks.empty() || s > marks.back())) marks.push_back(s);
    marks.push_back(spp);
    scene::AccumulatedSums total;
    scene::RenderStats mine;
    uint32_t done = 0;
    scene::RenderOutput out;
    for (uint32_t mark : marks) {
        const SampleRange share = sampleRange(mark - done, world.rank(), world.size());
        std::string error;
        try {
            renderer.setSettings(settings);
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
            mine.paths += s.paths;
            mine.gpuSeconds += s.gpuSeconds;
            for (size_t k = 0; k < s.counters.size(); ++k) mine.counters[k] += s.counters[k];
        } catch (const std::exception& e) {
            error = e.what();
        }
        Failure f = world.agree(error, {}, 20, false);
        if (f.fatal) throw PeerFailed(std::move(f));
        AMRVK_CHECK(f.rank < 0, "rank ", f.rank, " of ", world.size(), ": ",
                    f.message.empty() ? std::string("failed") : f.message);
        std::vector<double> sums = total.values;
        uint64_t sent = world.sumEverywhere(sums);
        const scene::RenderStats all = statsOverRanks(world, mine, sent);
        out =
            scene::outputFromSums({.width = total.width, .height = total.height, .values = std::move(sums)}, mark, all);
        done = mark;
        if (snapshot && std::find(snapshotSpp.begin(), snapshotSpp.end(), mark) != snapshotSpp.end()) snapshot(out);
    }
    return out;
}

}  // namespace amrvk::mpi
