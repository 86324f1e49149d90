#pragma once
// A sample in stages (passes/path_trace_dp.comp, the estimators of lib/estimator.glsl): every
// pixel's path advances one event per dispatch, its tracking cut to a box of space that this
// process owns, and a caller's exchange agrees each tracking result with the owners of the rest
// of space before the paths go on. Data-parallel MPI ranks render with it through
// Renderer::accumulateStaged (mpi/data_parallel.cpp supplies the exchange over MPI); the samples
// are added to the renderer's accumulation like any other.
#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "core/gpu_deadline.h"
#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu/context.h"
#include "scene/render_output.h"
#include "shared/data_parallel_gpu.h"

namespace amrvk::render {

// Where a staged step stands: which sample, after how many collision steps of it.
struct StagedStep {
    uint32_t sample = 0;
    uint64_t bounce = 0;
};

// The agreement between the owners of space (collective where they are processes). Each is called
// at every step, also with no paths, with the indices of the paths in it (ascending; the same on
// every owner unless they diverged) and this owner's results for them, which it replaces by the
// agreed ones.
struct StagedExchange {
    // hits[k]: path live[k]'s nearest real collision inside the owned box (t = inf: none) and the
    // TF colour there; agreed: the nearest over every box, with its owner's colour.
    std::function<void(std::span<const uint32_t> live, std::span<shared::DataParallelHitGpu> hits, StagedStep)>
        collisions;
    // transmittance[k]: path live[k]'s shadow-ray transmittance inside the owned box; agreed: the
    // product over every box.
    std::function<void(std::span<const uint32_t> live, std::span<float> transmittance, StagedStep)> shadows;
};

struct StagedRender {
    glm::vec3 ownedLo{0.0f}, ownedHi{0.0f};  // the owned box (local voxel space)
    uint32_t rankSeed = 0;                   // differs per owner: its tracking's random numbers
    StagedExchange exchange;
};

struct StagedReport {
    scene::RenderStats stats;  // this owner's counters (tracking inside its box) and paths
    uint64_t bounces = 0;      // collision steps that shaded paths, over every sample
    double exchangeSeconds = 0;
};

class StagedPass {
public:
    // Buffers for `paths` paths (one per pixel) and the data-parallel pipeline (compiled by the caller).
    StagedPass(gpu::Context& ctx, gpu::ComputePipeline pipeline, uint32_t paths);

    // Samples [first, first + spp) of every pixel, added to the accumulation that the RenderParams
    // at `params` name; progress(done, spp) after each sample.
    StagedReport run(uint64_t params, uint32_t first, uint32_t spp, const StagedRender& staged,
                     const std::function<void(uint32_t, uint32_t)>& progress);

private:
    // One stage over every path, its counters zeroed first; under the adaptive --gpu-timeout held
    // to the pace measured for that stage (gpu/paced_submit.h).
    void stage(uint32_t stage);
    uint32_t addCounters(scene::RenderStats& stats) const;  // returns the live-path count
    uint64_t step(const StagedRender& staged, StagedStep at, StagedReport& report);

    gpu::Context& mCtx;
    gpu::ComputePipeline mPipeline;
    gpu::Buffer mPaths, mHits, mShadow, mCounters;
    shared::DataParallelPush mPush{};
    std::array<GpuDeadline, shared::kDpStageAccumulate + 1> mDeadlines;  // per stage; units: workgroups
    // Host copies of the hits and shadow buffers, and the live paths' entries: kept across steps.
    std::vector<shared::DataParallelHitGpu> mHitsHost, mLiveHits;
    std::vector<float> mShadowHost, mLiveShadow;
    std::vector<uint32_t> mLive;
};

}  // namespace amrvk::render
