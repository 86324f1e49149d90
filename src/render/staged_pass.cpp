#include "render/staged_pass.h"

#include <array>
#include <utility>
#include <vector>

#include "core/stats.h"
#include "gpu/paced_submit.h"

namespace amrvk::render {

namespace {
// The paths whose entry is `inside` (t >= 0: a live path's hit; >= 0: a waiting shadow ray).
template <class T, class Inside>
void gather(const std::vector<T>& all, Inside inside, std::vector<uint32_t>& live, std::vector<T>& values) {
    live.clear();
    values.clear();
    for (uint32_t i = 0; i < all.size(); ++i)
        if (inside(all[i])) {
            live.push_back(i);
            values.push_back(all[i]);
        }
}
}  // namespace

StagedPass::StagedPass(gpu::Context& ctx, gpu::ComputePipeline pipeline, uint32_t paths)
    : mCtx(ctx),
      mPipeline(std::move(pipeline)),
      mPaths(ctx, uint64_t(paths) * sizeof(shared::PathStateGpu), gpu::MemoryKind::Device, "stagedPaths"),
      mHits(ctx, uint64_t(paths) * sizeof(shared::DataParallelHitGpu), gpu::MemoryKind::HostRead, "stagedHits"),
      mShadow(ctx, uint64_t(paths) * sizeof(float), gpu::MemoryKind::HostRead, "stagedShadow"),
      mCounters(ctx, (shared::kCounterCount + 1) * sizeof(uint32_t), gpu::MemoryKind::HostRead, "stagedCounters"),
      mHitsHost(paths),
      mShadowHost(paths) {
    mPush.paths = mPaths.address();
    mPush.hits = mHits.address();
    mPush.shadow = mShadow.address();
    mPush.counters = mCounters.address();
    mPush.count = paths;
}

void StagedPass::stage(uint32_t stage) {
    mPush.stage = stage;
    gpu::PacedWork work{.groups = (uint64_t(mPush.count) + 63) / 64,
                        .record = [&](VkCommandBuffer cmd, uint32_t first, uint32_t count, bool opening) {
                            if (opening) {
                                vkCmdFillBuffer(cmd, mCounters.handle(), 0, VK_WHOLE_SIZE, 0);
                                gpu::computeBarrier(cmd);
                            }
                            mPipeline.dispatchPart(cmd, &mPush, first, count);
                            gpu::computeBarrier(cmd);
                        },
                        .what = mPipeline.name()};
    // Tracking stages count density lookups as their workgroups finish (read while they run).
    if (mCounters.mapped())
        work.progress = [this] {
            std::array<uint32_t, shared::kCounterCount + 1> c{};
            mCounters.download(c.data(), sizeof c);
            uint64_t sum = 0;
            for (uint32_t v : c) sum += v;
            return sum;
        };
    work.stillText = "counting nothing";
    gpu::submitPaced(mCtx, mDeadlines.at(stage), work);
}

uint32_t StagedPass::addCounters(scene::RenderStats& stats) const {
    std::array<uint32_t, shared::kCounterCount + 1> c{};
    mCounters.download(c.data(), sizeof c);
    for (uint32_t k = 0; k < shared::kCounterCount; ++k) stats.counters[k] += c[k];
    return c[shared::kCounterCount];
}

// One collision step of every live path: local tracking, the agreed nearest collision, shading,
// then the shadow rays' local transmittances and their agreed product. Returns the paths still
// live (0 ends the sample).
uint64_t StagedPass::step(const StagedRender& staged, StagedStep at, StagedReport& report) {
    scene::RenderStats& stats = report.stats;
    std::vector<shared::DataParallelHitGpu>& hits = mHitsHost;
    std::vector<float>& shadow = mShadowHost;
    std::vector<uint32_t>& live = mLive;
    stage(shared::kDpStageTrack);
    addCounters(stats);
    mHits.download(hits.data(), hits.size() * sizeof(hits[0]));
    gather(hits, [](const shared::DataParallelHitGpu& h) { return h.t >= 0; }, live, mLiveHits);
    Timer exchange;
    staged.exchange.collisions(live, mLiveHits, at);
    report.exchangeSeconds += exchange.seconds();
    if (live.empty()) return 0;
    for (size_t k = 0; k < live.size(); ++k) hits[live[k]] = mLiveHits[k];
    mHits.upload(hits.data(), hits.size() * sizeof(hits[0]));
    stage(shared::kDpStageShade);
    const uint32_t stillLive = addCounters(stats);
    ++report.bounces;

    stage(shared::kDpStageShadow);
    addCounters(stats);
    mShadow.download(shadow.data(), shadow.size() * sizeof(float));
    gather(shadow, [](float t) { return t >= 0; }, live, mLiveShadow);
    exchange = Timer();
    staged.exchange.shadows(live, mLiveShadow, at);
    report.exchangeSeconds += exchange.seconds();
    if (!live.empty()) {
        for (size_t k = 0; k < live.size(); ++k) shadow[live[k]] = mLiveShadow[k];
        mShadow.upload(shadow.data(), shadow.size() * sizeof(float));
        stage(shared::kDpStageResolve);
    }
    return stillLive;
}

StagedReport StagedPass::run(uint64_t params, uint32_t first, uint32_t spp, const StagedRender& staged,
                             const std::function<void(uint32_t, uint32_t)>& progress) {
    mPush.params = params;
    mPush.ownedLo = staged.ownedLo;
    mPush.ownedHi = staged.ownedHi;
    mPush.rankSeed = staged.rankSeed;
    StagedReport report;
    const Timer wall;
    for (uint32_t s = 0; s < spp; ++s) {
        mPush.sampleIndex = first + s;
        stage(shared::kDpStageGenerate);
        StagedStep at{first + s, 0};
        while (step(staged, at, report) > 0) ++at.bounce;
        stage(shared::kDpStageAccumulate);
        addCounters(report.stats);
        report.stats.paths += mPush.count;
        if (progress) progress(s + 1, spp);
    }
    report.stats.gpuSeconds = wall.seconds() - report.exchangeSeconds;  // stages and transfers
    return report;
}

}  // namespace amrvk::render
