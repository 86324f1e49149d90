#include "mpi/sample_parallel.h"

#include "core/error.h"
#include "core/stats.h"

namespace amrvk::mpi {

SampleRange sampleRange(uint32_t spp, int rank, int size) {
    AMRVK_CHECK(size >= 1 && rank >= 0 && rank < size, "internal: rank ", rank, " of ", size);
    const auto at = [&](int r) { return uint32_t(uint64_t(spp) * uint64_t(r) / uint64_t(size)); };
    return {at(rank), at(rank + 1) - at(rank)};
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
    const Timer reduceTimer;
    uint64_t sent = world.sumToRoot(sums.values);
    std::vector<uint64_t> counts(mine.counters.begin(), mine.counters.end());
    counts.push_back(mine.paths);
    sent += world.sumToRoot(counts);
    const double gpuSecondsMax = world.maxOverRanks(mine.gpuSeconds);
    sent += sizeof(double);

    rankInfo["rank"] = world.rank();
    rankInfo["host"] = world.host();
    rankInfo["localRank"] = world.localRank();
    rankInfo["device"] = renderer.context().deviceReport().name;
    rankInfo["firstSample"] = range.first;
    rankInfo["samples"] = range.count;
    rankInfo["paths"] = mine.paths;
    rankInfo["gpuSeconds"] = mine.gpuSeconds;
    rankInfo["renderSeconds"] = renderSeconds;
    rankInfo["reduceSeconds"] = reduceTimer.seconds();
    rankInfo["bytesSent"] = sent;
    rankInfo["hostPeakBytes"] = peakResidentBytes();
    rankInfo["deviceMemoryPeakBytes"] = renderer.context().memory().peakBytes();
    const std::vector<std::string> reports = world.gatherToRoot(rankInfo.dump());

    SampleParallelResult result;
    if (world.rank() != 0) {
        result.out = scene::outputFromSums(sums, range.count, mine);
        return result;
    }
    scene::RenderStats all;
    for (size_t k = 0; k < all.counters.size(); ++k) all.counters[k] = counts[k];
    all.paths = counts.back();
    all.gpuSeconds = gpuSecondsMax;  // the ranks run at once: the job's GPU time is the slowest rank's
    result.out = scene::outputFromSums(sums, p.session.spp, all);
    nlohmann::ordered_json ranks = nlohmann::ordered_json::array();
    uint64_t moved = 0;
    for (size_t r = 0; r < reports.size(); ++r) {
        ranks.push_back(nlohmann::ordered_json::parse(reports[r]));
        // the sums and counters, and (ranks > 0) this report itself
        moved += ranks.back()["bytesSent"].get<uint64_t>() + (r > 0 ? reports[r].size() : 0);
    }
    result.mpi = {{"ranks", world.size()},
                  {"distribute", "samples"},
                  {"bytesMoved", moved},
                  {"bytesMovedPerPath", all.paths > 0 ? double(moved) / double(all.paths) : 0.0},
                  {"perRank", ranks}};
    return result;
}

}  // namespace amrvk::mpi
