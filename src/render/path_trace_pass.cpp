#include "render/path_trace_pass.h"

#include <algorithm>

#include "core/error.h"
#include "gpu/shader_library.h"

namespace amrvk::render {

namespace {

// "MODE[.ubrm][.minorant]": the variant's part of a pipeline's key and name.
std::string variantName(TracerVariant v) {
    std::string s = scene::modeName(v.mode);
    if (v.transmittance != scene::Transmittance::Ratio)
        s += std::string(".") + scene::transmittanceName(v.transmittance);
    if (v.control) s += ".minorant";
    return s;
}

std::string pipelineKey(TracerVariant variant, const scene::StructureConfig& config) {
    return "path_trace." + variantName(variant) + "." + config.label();
}

}  // namespace

gpu::ComputePipeline compilePathTracer(gpu::Context& ctx, const std::string& entry, uint32_t pushBytes,
                                       TracerVariant variant, const scene::StructureConfig& config,
                                       const gpu::ShaderLibrary& shaders) {
    // The ray-query variant is compiled only for rq: its SPIR-V needs the rayQuery feature. The
    // unbiased ray-marching shadows are a variant of their own: in the default one, their code
    // cost lavapipe 0.5 s a pipeline even where a specialization constant turned it off.
    const std::string shader = entry + (config.backend == scene::Backend::Rq ? "_rq" : "") +
                               (variant.transmittance == scene::Transmittance::Ubrm ? "_ubrm" : "");
    // Named with where its source came from: the name a runaway or crashing dispatch is reported by.
    return gpu::ComputePipeline(ctx, shaders.load(shader),
                                entry + "." + variantName(variant) + "." + config.label() + shaders.origin(), pushBytes,
                                {{0, uint32_t(variant.mode)},
                                 {1, uint32_t(config.sampler)},
                                 {2, uint32_t(config.traversal)},
                                 {3, uint32_t(config.backend)},
                                 {4, ctx.pathRegeneration() ? 1u : 0u},
                                 {5, variant.control ? 1u : 0u}});
}

PathTracePass::PathTracePass(gpu::Context& ctx) : mCtx(ctx) {
    mCounters = gpu::Buffer(ctx, shared::kCounterCount * sizeof(uint32_t), gpu::MemoryKind::HostRead, "counters");
    mPathStats = gpu::Buffer(ctx, shared::kPathStatsCount * sizeof(uint32_t), gpu::MemoryKind::HostRead, "pathStats");
}

const gpu::ComputePipeline& PathTracePass::pipeline(TracerVariant variant, const scene::StructureConfig& config,
                                                    const gpu::ShaderLibrary& shaders) {
    AMRVK_CHECK(config.backend != scene::Backend::Auto, "internal: pipeline needs a resolved back-end");
    const std::string key = pipelineKey(variant, config);
    auto it = mPipelines.find(key);
    if (it == mPipelines.end()) {
        it = mPipelines
                 .emplace(key, compilePathTracer(mCtx, "path_trace", sizeof(shared::PushConstants), variant, config,
                                                 shaders))
                 .first;
        ++mCompiled;
    }
    return it->second;
}

void PathTracePass::adopt(TracerVariant variant, const scene::StructureConfig& config, gpu::ComputePipeline compiled) {
    AMRVK_CHECK(compiled.valid(), "internal: adopting an empty pipeline");
    if (mPipelines.try_emplace(pipelineKey(variant, config), std::move(compiled)).second) ++mCompiled;
}

void PathTracePass::dropPipelines() {
    mPipelines.clear();
    mDeadline.reset();
}

void PathTracePass::recompile(TracerVariant variant, const scene::StructureConfig& config,
                              const gpu::ShaderLibrary& shaders) {
    gpu::ComputePipeline fresh = compilePathTracer(mCtx, "path_trace", sizeof(shared::PushConstants), variant, config,
                                                   shaders);  // throws before anything is replaced
    ++mCompiled;
    mPipelines.clear();
    mPipelines.emplace(pipelineKey(variant, config), std::move(fresh));
    mDeadline.reset();  // new shaders: their pace is not known
}

bool PathTracePass::resize(int width, int height) {
    if (mAccum.valid() && width == mWidth && height == mHeight) return false;
    const uint64_t pixels = uint64_t(width) * uint64_t(height);
    mAccum = gpu::Buffer();
    mAccum = gpu::Buffer(mCtx, pixels * sizeof(shared::AccumPixelGpu), gpu::MemoryKind::Device, "accumulation");
    mWidth = width;
    mHeight = height;
    reset();
    return true;
}

void PathTracePass::reset() {
    if (mAccum.valid()) mAccum.fillZero();
    mSpp = 0;
    mRowsDone = 0;
    mStats = {};
    mDeadline.reset();  // new settings or data: a new pace
}

void PathTracePass::addSamples(uint32_t n, const scene::RenderStats& stats) {
    mSpp += n;
    mStats.paths += stats.paths;
    mStats.gpuSeconds += stats.gpuSeconds;
    for (size_t k = 0; k < mStats.counters.size(); ++k) mStats.counters[k] += stats.counters[k];
}

void PathTracePass::addSums(const scene::AccumulatedSums& add, uint32_t n, const scene::RenderStats& stats) {
    const size_t pixels = size_t(mWidth) * size_t(mHeight);
    AMRVK_CHECK(add.width == mWidth && add.height == mHeight && add.values.size() == pixels * add.kPerPixel &&
                    mRowsDone == 0 && mAccum.valid(),
                "internal: adding ", add.width, "x", add.height, " sums to a ", mWidth, "x", mHeight, " accumulation (",
                mRowsDone, " rows of a sample traced)");
    std::vector<shared::AccumPixelGpu> accum(pixels);
    mAccum.download(accum.data(), accum.size() * sizeof(shared::AccumPixelGpu));
    // Each sum as hi + lo floats again (lo the rounding error of hi, as the shader keeps them).
    auto split = [](double v, float& hi, float& lo) {
        hi = float(v);
        lo = float(v - double(hi));
    };
    for (size_t i = 0; i < pixels; ++i) {
        shared::AccumPixelGpu& a = accum[i];
        const double* v = &add.values[i * scene::AccumulatedSums::kPerPixel];
        for (int c = 0; c < 4; ++c) split(double(a.sumHi[c]) + double(a.sumLo[c]) + v[c], a.sumHi[c], a.sumLo[c]);
        for (int c = 0; c < 3; ++c)
            split(double(a.sumSqHi[c]) + double(a.sumSqLo[c]) + v[4 + c], a.sumSqHi[c], a.sumSqLo[c]);
    }
    mAccum.upload(accum.data(), accum.size() * sizeof(shared::AccumPixelGpu));
    addSamples(n, stats);
}

double PathTracePass::rows(const gpu::ComputePipeline& pipeline, uint64_t paramsAddress, uint32_t rows) {
    AMRVK_CHECK(mAccum.valid(), "internal: rows() before resize()");
    const uint32_t first = mRowsDone, count = std::min(rows, uint32_t(mHeight) - first);
    if (count == 0) return 0.0;
    const double seconds = submit(pipeline, {{paramsAddress, mFirstSample + mSpp, first, first + count, 1u, 1u, 0u}},
                                  uint64_t(count) * uint64_t(mWidth)).first;
    mRowsDone += count;
    if (mRowsDone == uint32_t(mHeight)) {
        ++mSpp;
        mRowsDone = 0;
    }
    return seconds;
}

void PathTracePass::probedSample(const gpu::ComputePipeline& pipeline, uint64_t paramsAddress) {
    const uint32_t width = uint32_t(mWidth), height = uint32_t(mHeight);
    const uint32_t probeRows = uint32_t(std::max<uint64_t>(1, (kProbePaths + width - 1) / width));
    const uint32_t stride = std::max(1u, height / probeRows);  // the probe has >= probeRows rows
    const uint32_t sample = mFirstSample + mSpp;
    // The probe, alone: rows 0, stride, 2 stride, ... (spread over the image, so its pace is the
    // image's, sky and data alike).
    submit(pipeline, {{paramsAddress, sample, 0u, height, 1u, stride, 0u}},
           uint64_t((height + stride - 1) / stride) * width);
    // The rest: the bands of rows between the probe's, each one dispatch of whole contiguous rows
    // (coherent 8x8 tiles; the probe's strided rows cost llvmpipe about 2x per path), 4x more
    // bands per submission, each submission held to the pace measured so far.
    std::vector<std::pair<uint32_t, uint32_t>> bands;  // [first, end) rows
    for (uint32_t r = 0; r < height; r += stride)
        if (r + 1 < std::min(r + stride, height)) bands.emplace_back(r + 1, std::min(r + stride, height));
    size_t next = 0, perSubmit = 1;
    while (next < bands.size()) {
        const size_t count = std::min(perSubmit, bands.size() - next);
        std::vector<shared::PushConstants> dispatches;
        uint64_t paths = 0;
        for (size_t k = next; k < next + count; ++k) {
            dispatches.push_back({paramsAddress, sample, bands[k].first, bands[k].second, 1u, 1u, 0u});
            paths += uint64_t(bands[k].second - bands[k].first) * width;
        }
        submit(pipeline, dispatches, paths);
        next += count;
        perSubmit = std::min<size_t>(perSubmit * 4, 64);  // unbounded, it wrapped to 0 after 32 rounds: a hang
    }
    ++mSpp;
}

void PathTracePass::accumulate(const gpu::ComputePipeline& pipeline, uint64_t paramsAddress, uint32_t n,
                               const std::function<void(uint32_t)>& afterBatch, uint32_t maxBatch) {
    AMRVK_CHECK(mAccum.valid(), "internal: accumulate() before resize()");
    if (mRowsDone > 0 && n > 0) {  // finish the sample a tile began
        rows(pipeline, paramsAddress, uint32_t(mHeight) - mRowsDone);
        --n;
        if (afterBatch) afterBatch(mSpp);
    }
    if (n > 0 && mCtx.adaptiveTimeout() && !mDeadline.measured()) {  // no pace yet: probe it
        probedSample(pipeline, paramsAddress);
        --n;
        if (afterBatch) afterBatch(mSpp);
    }
    uint32_t done = 0, batch = 1;
    while (done < n) {
        const uint32_t count = std::min({batch, maxBatch, n - done});
        // Context::samplesPerInvocation() samples per invocation: fewer dispatches and one
        // accumulation write per pixel for several samples.
        std::vector<shared::PushConstants> dispatches;
        for (uint32_t i = 0; i < count; i += dispatches.back().samples)
            dispatches.push_back({paramsAddress, mFirstSample + mSpp + i, 0u, uint32_t(mHeight),
                                  std::min(mCtx.samplesPerInvocation(), count - i), 1u, 0u});
        const uint32_t largest =
            submit(pipeline, dispatches, uint64_t(count) * uint64_t(mWidth) * uint64_t(mHeight)).second;
        mSpp += count;
        done += count;
        // Grow batches while the 32-bit counters stay far from overflowing.
        if (largest < (1u << 28) && batch < 64) batch *= 2;
        else if (largest >= (1u << 30) && batch > 1) batch /= 2;
        if (afterBatch) afterBatch(mSpp);
    }
}

gpu::AdaptiveWait PathTracePass::adaptiveWait(uint64_t paths) const {
    gpu::AdaptiveWait wait{.limitSeconds = mDeadline.limit(paths), .quietSeconds = mDeadline.floorSeconds()};
    // Paths finished so far: every path adds one to a lookup-count bin (path_trace.comp).
    if (mPathStats.mapped())
        wait.progress = [this] {
            constexpr uint32_t kLookupBins = shared::kPathStatsBins + shared::kPathLookups * shared::kPathBins;
            std::array<uint32_t, kLookupBins + shared::kPathBins> bins{};
            mPathStats.download(bins.data(), sizeof bins);
            uint64_t finished = 0;
            for (uint32_t k = 0; k < shared::kPathBins; ++k) finished += bins[kLookupBins + k];
            return finished;
        };
    return wait;
}

std::pair<double, uint32_t> PathTracePass::submit(const gpu::ComputePipeline& pipeline,
                                                  const std::vector<shared::PushConstants>& dispatches,
                                                  uint64_t paths) {
    const double wall = mCtx.submitAndWait(
        [&](VkCommandBuffer cmd) {
        mTimer.reset(cmd);
        vkCmdFillBuffer(cmd, mCounters.handle(), 0, VK_WHOLE_SIZE, 0);
        vkCmdFillBuffer(cmd, mPathStats.handle(), 0, VK_WHOLE_SIZE, 0);
        gpu::computeBarrier(cmd);
        for (const shared::PushConstants& push : dispatches) {
            const uint32_t scope = mTimer.begin(cmd);
            const uint32_t stride = std::max(push.rowStride, 1u);
            const uint32_t rows = (push.rowEnd - push.rowOffset + stride - 1) / stride;
            pipeline.dispatch(cmd, &push, (uint32_t(mWidth) + 7) / 8, (rows + 7) / 8);
            mTimer.end(cmd, scope);
            gpu::computeBarrier(cmd);
        }
    },
        pipeline.name(), adaptiveWait(paths));
    mDeadline.record(wall, paths);
    std::array<uint32_t, shared::kCounterCount> counters{};
    mCounters.download(counters.data(), sizeof counters);
    for (uint32_t k = 0; k < shared::kCounterCount; ++k) mStats.counters[k] += counters[k];
    std::array<uint32_t, shared::kPathStatsCount> path{};
    mPathStats.download(path.data(), sizeof path);
    mStats.path.add(path);
    const double seconds = mTimer.seconds();
    mStats.gpuSeconds += seconds;
    mStats.paths += paths;
    return {seconds, *std::max_element(counters.begin(), counters.end())};
}

scene::AccumulatedSums PathTracePass::readSums() const {
    scene::AccumulatedSums sums{.width = mWidth, .height = mHeight};
    const size_t pixels = size_t(mWidth) * size_t(mHeight);
    sums.values.assign(pixels * scene::AccumulatedSums::kPerPixel, 0.0);
    if (!mAccum.valid()) return sums;
    std::vector<shared::AccumPixelGpu> accum(pixels);
    mAccum.download(accum.data(), accum.size() * sizeof(shared::AccumPixelGpu));
    for (size_t i = 0; i < pixels; ++i) {
        // hi + lo in double: exact (each is a float, |lo| <= ulp(hi) / 2).
        const shared::AccumPixelGpu& a = accum[i];
        const glm::dvec4 sum = glm::dvec4(a.sumHi) + glm::dvec4(a.sumLo);
        const glm::dvec4 sumSq = glm::dvec4(a.sumSqHi) + glm::dvec4(a.sumSqLo);
        double* v = &sums.values[i * scene::AccumulatedSums::kPerPixel];
        for (int c = 0; c < 4; ++c) v[c] = sum[c];
        for (int c = 0; c < 3; ++c) v[4 + c] = sumSq[c];
    }
    return sums;
}

scene::RenderOutput PathTracePass::read() const { return scene::outputFromSums(readSums(), mSpp, mStats); }

}  // namespace amrvk::render
