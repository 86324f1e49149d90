#pragma once
// The path-trace pass: one sample per pixel per dispatch of path_trace.comp (specialised for a
// mode and structure combination; path_trace_rq for the ray-query back-end) added to an
// accumulation buffer (double-float sum and sum of squares per pixel, shared::AccumPixelGpu;
// read() combines them in double), with the per-dispatch counters summed on the host in 64 bits.
// Samples continue from the accumulated count, so adding n samples to an image of k gives the
// same estimate as one run of k + n.
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <string>

#include "core/gpu_deadline.h"
#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu/context.h"
#include "gpu/shader_library.h"
#include "scene/render_output.h"
#include "scene/render_settings.h"
#include "scene/structure_config.h"

namespace amrvk::render {

// What a path tracer is specialised for besides the structures: the mode (constant kMode), the
// shadow rays' estimator (the shader variant ENTRY_ubrm: the default one holds no comb code) and
// the control extinction (constant kControlExtinction).
struct TracerVariant {
    scene::Mode mode = scene::Mode::Ms;
    scene::Transmittance transmittance = scene::Transmittance::Ratio;  // ss and ms only
    bool control = false;  // --control-extinction minorant (constant kControlExtinction); not dvr
    // The settings' variant; ae and dvr, which cast no shadow rays, always take the plain shader.
    static TracerVariant of(const scene::RenderSettings& s) {
        return {s.mode, scene::castsShadowRays(s.mode) ? s.transmittance : scene::Transmittance::Ratio,
                s.mode != scene::Mode::Dvr && s.controlExtinction == scene::ControlExtinction::Minorant};
    }
    bool operator==(const TracerVariant&) const = default;
};

// A path tracer's pipeline: shader `entry` (+ "_rq" for the ray-query back-end, + "_ubrm" for
// unbiased ray-marching shadows) from `shaders`, specialised for (variant, config) by constants
// 0-3, pushing `pushBytes`; named
// "ENTRY.MODE[.ubrm].LABEL" (plus where --shader-dir took it from). path_trace and path_trace_dp.
gpu::ComputePipeline compilePathTracer(gpu::Context& ctx, const std::string& entry, uint32_t pushBytes,
                                       TracerVariant variant, const scene::StructureConfig& config,
                                       const gpu::ShaderLibrary& shaders);

class PathTracePass {
public:
    explicit PathTracePass(gpu::Context& ctx);

    // The pipeline for (variant, config), compiled from `shaders` on first use and kept until
    // dropPipelines().
    const gpu::ComputePipeline& pipeline(TracerVariant variant, const scene::StructureConfig& config,
                                         const gpu::ShaderLibrary& shaders);
    // Keeps `compiled` (compilePathTracer of the same variant, config and shaders, made elsewhere,
    // e.g. on another thread while the structures were built) as the pipeline for (variant,
    // config), unless one is already there.
    void adopt(TracerVariant variant, const scene::StructureConfig& config, gpu::ComputePipeline compiled);
    // Forgets every pipeline (structure or shader change); the next pipeline() compiles again.
    void dropPipelines();
    // Compiles the pipeline for (variant, config) from `shaders` and only then replaces every old
    // one: on a compile error it throws and the previous pipelines keep running.
    void recompile(TracerVariant variant, const scene::StructureConfig& config, const gpu::ShaderLibrary& shaders);
    uint64_t pipelinesCompiled() const { return mCompiled; }

    // (Re)allocates the accumulation buffer for width x height pixels when the size changes;
    // returns whether it did.
    bool resize(int width, int height);
    // Zeroes the accumulation: the image holds no sample afterwards.
    void reset();
    // Samples are numbered (and seeded) from `first` on (sample-parallel ranks take disjoint
    // ranges); resets the accumulation. Kept by reset().
    void setFirstSample(uint32_t first) {
        mFirstSample = first;
        reset();
    }
    uint32_t firstSample() const { return mFirstSample; }
    uint64_t accumAddress() const { return mAccum.address(); }
    uint64_t countersAddress() const { return mCounters.address(); }
    uint64_t pathStatsAddress() const { return mPathStats.address(); }
    uint32_t spp() const { return mSpp; }          // complete samples per pixel
    uint32_t rowsDone() const { return mRowsDone; }  // rows of the image that have sample spp() + 1
    const scene::RenderStats& stats() const { return mStats; }

    // Adds n samples per pixel with `pipeline` (first completing a sample that rows() began);
    // paramsAddress holds RenderParams for this pass. Batches of dispatches grow while the 32-bit
    // counters stay far from overflowing; afterBatch(spp so far) runs after each batch.
    void accumulate(const gpu::ComputePipeline& pipeline, uint64_t paramsAddress, uint32_t n,
                    const std::function<void(uint32_t)>& afterBatch = {}, uint32_t maxBatch = 64);
    // Traces the next `rows` rows of the current sample (a time-budgeted tile; the sample is
    // complete when the last row is done). Returns the GPU seconds it took.
    double rows(const gpu::ComputePipeline& pipeline, uint64_t paramsAddress, uint32_t rows);
    // Counts n samples per pixel that another pass added to the accumulation (render/staged_pass.h)
    // with their statistics.
    void addSamples(uint32_t n, const scene::RenderStats& stats);
    // Adds sums another process traced at this size (n samples per pixel; the caller keeps their
    // sample indices apart from this accumulation's) and their statistics: what rank 0 of the MPI
    // viewer adds of the other ranks' samples. Between whole samples only.
    void addSums(const scene::AccumulatedSums& add, uint32_t n, const scene::RenderStats& stats);
    // The mean so far (downloads the accumulation buffer).
    scene::RenderOutput read() const;
    // The sums behind it, in double (downloads the accumulation buffer).
    scene::AccumulatedSums readSums() const;

private:
    // One submit: the counters zeroed, then each dispatch timed and followed by a barrier; adds the
    // counters, GPU seconds and `paths` to the statistics. Returns the GPU seconds and the largest counter.
    // Under the adaptive --gpu-timeout it is held to mDeadline's limit and measures the pace.
    std::pair<double, uint32_t> submit(const gpu::ComputePipeline& pipeline,
                                       const std::vector<shared::PushConstants>& dispatches, uint64_t paths);
    // The adaptive --gpu-timeout of a submission of `paths` paths: mDeadline's limit, and past it
    // the floor's time without a path finished (read from the mapped path statistics).
    gpu::AdaptiveWait adaptiveWait(uint64_t paths) const;
    // One whole sample: first every stride-th row (about kProbePaths paths spread over the image)
    // alone, which measures the pace with only the floor as its limit; then the bands of rows
    // between them, held to that pace.
    void probedSample(const gpu::ComputePipeline& pipeline, uint64_t paramsAddress);
    static constexpr uint64_t kProbePaths = 4096;

    gpu::Context& mCtx;
    std::map<std::string, gpu::ComputePipeline> mPipelines;  // key: mode + structure label
    gpu::Buffer mAccum, mCounters, mPathStats;
    gpu::GpuTimer mTimer{mCtx, 64};  // at most 64 dispatches per submit
    int mWidth = 0, mHeight = 0;
    uint32_t mSpp = 0, mRowsDone = 0, mFirstSample = 0;
    uint64_t mCompiled = 0;
    scene::RenderStats mStats;
    GpuDeadline mDeadline;  // the adaptive --gpu-timeout; reset with the accumulation
};

}  // namespace amrvk::render
