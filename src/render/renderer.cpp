#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <span>

#include "core/error.h"
#include "core/progress.h"
#include "core/stats.h"
#include "gpu/shader_library.h"
#include "shared/amr_gpu.h"

namespace amrvk::shaders {
std::span<const gpu::EmbeddedShader> passShaders();
}

namespace amrvk::render {

using scene::Backend;
using scene::Mode;
using scene::StructureConfig;
using scene::TraversalKind;
using scene::SamplerKind;

namespace {
static_assert(sizeof(accel::BvhNode) == sizeof(shared::BvhNodeGpu));
static_assert(sizeof(accel::ValueRange) == 2 * sizeof(float));

glm::vec4 v4(glm::dvec3 v, double w = 0.0) { return glm::vec4(float(v.x), float(v.y), float(v.z), float(w)); }
}  // namespace

namespace {
constexpr VkBufferUsageFlags kAsInput = VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR;

std::string traversalResource(TraversalKind t, const char* what) {
    return std::string(scene::traversalName(t)) + "Traversal" + what;
}
}  // namespace

Renderer::Renderer(gpu::Context& ctx, scene::VolumeScene& volume) : mCtx(ctx), mScene(volume) {
    const StructureConfig& cfg = volume.config;
    AMRVK_CHECK(cfg.backend != Backend::Auto, "internal: Renderer needs a resolved back-end");
    AMRVK_CHECK(cfg.backend == Backend::Sw || ctx.hasRayQuery(), "--backend rq: device '", ctx.deviceReport().name,
                "' has no VK_KHR_ray_query");
    gpu::registerShaders(shaders::passShaders());
    const glm::ivec3 origin(volume.localOrigin);
    if (cfg.usesBricks()) {
        std::vector<shared::BrickGpu> bricks;
        bricks.reserve(volume.bricks.bricks.size());
        for (const accel::Brick& b : volume.bricks.bricks)
            bricks.push_back({glm::ivec4(b.lower - origin, b.level), glm::ivec4(b.size, int32_t(b.begin))});
        mBricks = gpu::makeBuffer<shared::BrickGpu>(ctx, bricks, "bricks");
        mBrickValues = gpu::makeBuffer<float>(ctx, volume.brickValues, "brickValues");
    }
    const char* samplerStructure = cfg.sampler == SamplerKind::Abr ? "abrSampler" : "brickDomainSampler";
    if (cfg.sampler == SamplerKind::Dense) {
        AMRVK_CHECK(volume.dense.has_value(), "internal: dense sampler without a dense grid");
        const accel::DenseGrid& d = *volume.dense;
        mDenseValues = gpu::makeBuffer<float>(ctx, d.values, "denseGrid");
        mParams.denseValues = mDenseValues.address();
        mParams.denseDims = glm::ivec4(d.dims, d.level);
        mParams.denseOrigin = v4(glm::dvec3(d.origin - volume.localOrigin), double(amr::cellWidth(d.level)));
    } else if (cfg.backend == Backend::Sw) {
        mSamplerNodes = gpu::makeBuffer<accel::BvhNode>(ctx, volume.samplerBvh.nodes, std::string(samplerStructure) + "Bvh");
        mSamplerPrims = gpu::makeBuffer<uint32_t>(ctx, volume.samplerBvh.primIds, std::string(samplerStructure) + "BvhPrims");
    } else {
        const auto& boxes = volume.samplerBoxes;
        mSamplerAabbs = gpu::Buffer(ctx, std::max<uint64_t>(16, boxes.size() * sizeof(shared::AabbGpu)),
                                    gpu::MemoryKind::Device, std::string(samplerStructure) + "Aabbs", kAsInput);
        if (!boxes.empty()) mSamplerAabbs.upload(boxes.data(), boxes.size() * sizeof(shared::AabbGpu));
        mSamplerAccel = gpu::AabbAccelerationStructure(ctx, uint32_t(boxes.size()), std::string(samplerStructure) + "Accel");
        ctx.submitAndWait([&](VkCommandBuffer cmd) { mSamplerAccel.build(cmd, mSamplerAabbs); });
        mParams.samplerAccel = mSamplerAccel.tlasAddress();
    }
    if (volume.abrs) {
        std::vector<shared::AbrGpu> abrs;
        abrs.reserve(volume.abrs->abrs.size());
        const glm::dvec3 o(volume.localOrigin);
        for (const accel::Abr& a : volume.abrs->abrs)
            abrs.push_back({glm::vec3(a.box.lower() - o), a.brickBegin, glm::vec3(a.box.upper() - o), a.brickCount});
        mAbrs = gpu::makeBuffer<shared::AbrGpu>(ctx, abrs, "abrs");
        mAbrBrickList = gpu::makeBuffer<uint32_t>(ctx, volume.abrs->brickList, "abrBrickLists");
    }
    if (volume.grid) {
        mGridRanges = gpu::makeBuffer<accel::ValueRange>(ctx, volume.grid->ranges, "macrocellRanges");
        mGridMajorants = gpu::Buffer(ctx, std::max<uint64_t>(16, volume.grid->ranges.size() * sizeof(float)),
                                     gpu::MemoryKind::Device, "macrocellMajorants");
        mParams.gridDims = glm::ivec4(volume.grid->dims, 0);
        mParams.gridOrigin = v4(volume.grid->origin - glm::dvec3(volume.localOrigin));
        mParams.gridCellSize = v4(volume.grid->cellSize);
        mParams.gridRanges = mGridRanges.address();
        mParams.gridMajorants = mGridMajorants.address();
    }
    mCounters = gpu::Buffer(ctx, shared::kCounterCount * sizeof(uint32_t), gpu::MemoryKind::HostRead, "counters");
    mParamsBuffer = gpu::Buffer(ctx, sizeof(shared::RenderParams), gpu::MemoryKind::Device, "renderParams");

    mParams.boundsLo = v4(glm::dvec3(0.0), 1.0 / double(amr::cellWidth(volume.minLevel)));
    mParams.boundsHi = v4(glm::dvec3(volume.bounds.upper - volume.bounds.lower), 1.0);
    mParams.bricks = mBricks.valid() ? mBricks.address() : 0;
    mParams.brickValues = mBrickValues.valid() ? mBrickValues.address() : 0;
    mParams.samplerNodes = mSamplerNodes.valid() ? mSamplerNodes.address() : 0;
    mParams.samplerPrims = mSamplerPrims.valid() ? mSamplerPrims.address() : 0;
    mParams.abrs = mAbrs.valid() ? mAbrs.address() : 0;
    mParams.abrBrickList = mAbrBrickList.valid() ? mAbrBrickList.address() : 0;
    mParams.counters = mCounters.address();
    if (cfg.traversal != TraversalKind::KdTree) uploadDomainBoxes();  // kdtree: per TF
}

uint32_t Renderer::domainCount() const {
    if (mScene.config.traversal == TraversalKind::GridBvh) return uint32_t(mScene.grid->ranges.size());
    return uint32_t(mScene.domains.boxes.size());
}

// Traversal boxes, their value ranges and majorants, and (rq) the BLAS input and structure.
void Renderer::uploadDomainBoxes() {
    const TraversalKind t = mScene.config.traversal;
    if (t == TraversalKind::GridDda) return;
    const uint32_t count = domainCount();
    if (t == TraversalKind::GridBvh) {
        mParams.domainRanges = mGridRanges.address();
        mParams.domainMajorants = mGridMajorants.address();
    } else {
        mDomainBoxes = gpu::makeBuffer<shared::AabbGpu>(mCtx, mScene.domains.boxes, traversalResource(t, "Boxes"));
        mDomainRanges = gpu::makeBuffer<accel::ValueRange>(mCtx, mScene.domains.ranges, traversalResource(t, "Ranges"));
        mDomainMajorants = gpu::Buffer(mCtx, std::max<uint64_t>(16, uint64_t(count) * sizeof(float)),
                                       gpu::MemoryKind::Device, traversalResource(t, "Majorants"));
        mParams.domainBoxes = mDomainBoxes.address();
        mParams.domainRanges = mDomainRanges.address();
        mParams.domainMajorants = mDomainMajorants.address();
    }
    if (mScene.config.backend == Backend::Rq) {
        mDomainAccel = {};
        mDomainAabbs = gpu::Buffer(mCtx, std::max<uint64_t>(24, uint64_t(count) * sizeof(shared::AabbGpu)),
                                   gpu::MemoryKind::Device, traversalResource(t, "Aabbs"), kAsInput);
        mDomainAccel = gpu::AabbAccelerationStructure(mCtx, count, traversalResource(t, "Accel"));
        mParams.domainAccel = mDomainAccel.tlasAddress();
    }
    mParams.domainInfo = glm::uvec4(count, 0, 0, 0);
    mActiveMask.clear();
}

// sw back-end: a BVH over the boxes with majorant > 0, rebuilt only when that set changes.
void Renderer::updateSwCulling(const std::vector<float>& majorants) {
    std::vector<uint8_t> mask(majorants.size());
    for (size_t i = 0; i < majorants.size(); ++i) mask[i] = majorants[i] > 0.0f;
    if (mask == mActiveMask && mDomainNodes.valid()) return;
    mActiveMask = std::move(mask);
    std::vector<accel::BoxD> boxes;
    std::vector<uint32_t> ids;
    const bool grid = mScene.config.traversal == TraversalKind::GridBvh;
    for (uint32_t i = 0; i < mActiveMask.size(); ++i) {
        if (!mActiveMask[i]) continue;
        ids.push_back(i);
        if (grid) {
            // The shader computes macrocell faces in float; pad the double box so nodes stay conservative.
            const accel::RangeGrid& g = *mScene.grid;
            const glm::ivec3 c(int(i % uint32_t(g.dims.x)), int((i / uint32_t(g.dims.x)) % uint32_t(g.dims.y)),
                               int(i / uint32_t(g.dims.x * g.dims.y)));
            const glm::dvec3 o = g.origin - glm::dvec3(mScene.localOrigin);
            const glm::dvec3 lo = o + glm::dvec3(c) * g.cellSize, hi = o + glm::dvec3(c + 1) * g.cellSize;
            const glm::dvec3 pad = 1e-5 * (glm::abs(lo) + glm::abs(hi) + 1.0);
            boxes.push_back({lo - pad, hi + pad});
        } else {
            const shared::AabbGpu& b = mScene.domains.boxes[i];
            boxes.push_back({glm::dvec3(b.lo), glm::dvec3(b.hi)});
        }
    }
    const TraversalKind t = mScene.config.traversal;
    mDomainNodes = gpu::Buffer();
    mDomainPrims = gpu::Buffer();
    accel::Bvh bvh = boxes.empty() ? accel::Bvh{} : accel::buildBvh(boxes);
    for (uint32_t& p : bvh.primIds) p = ids[p];
    mDomainNodes = gpu::makeBuffer<accel::BvhNode>(mCtx, bvh.nodes, traversalResource(t, "Bvh"));
    mDomainPrims = gpu::makeBuffer<uint32_t>(mCtx, bvh.primIds, traversalResource(t, "BvhPrims"));
    mParams.domainNodes = mDomainNodes.address();
    mParams.domainPrims = mDomainPrims.address();
}

void Renderer::setTransferFunction(const scene::TransferFunction& tf) {
    const auto& positions = tf.positions();
    std::vector<glm::vec4> colors = tf.colors();
    AMRVK_CHECK(!positions.empty() && positions.size() == colors.size(), "transfer function has no nodes");
    const StructureConfig& cfg = mScene.config;
    Timer hostTimer;
    if (cfg.traversal == TraversalKind::KdTree) {
        mScene.rebuildKdTree([&tf](float lo, float hi) { return tf.maxAlpha(lo, hi); });
        uploadDomainBoxes();
    }
    mTfPositions = gpu::makeBuffer<float>(mCtx, positions, "tfPositions");
    mTfColors = gpu::makeBuffer<glm::vec4>(mCtx, colors, "tfColors");
    mParams.tfInfo = glm::vec4(float(positions.size()), 0, 0, 0);
    mParams.tfPositions = mTfPositions.address();
    mParams.tfColors = mTfColors.address();
    mParamsBuffer.upload(&mParams, sizeof mParams);
    if (!mMajorantPipeline.valid())
        mMajorantPipeline = gpu::ComputePipeline(mCtx, gpu::loadShader("majorants"), "majorants",
                                                 sizeof(shared::StructurePush));
    const bool rq = cfg.backend == Backend::Rq && cfg.traversalUsesBoxes();
    if (rq && !mAabbPipeline.valid())
        mAabbPipeline = gpu::ComputePipeline(mCtx, gpu::loadShader("domain_aabbs"), "domain_aabbs",
                                             sizeof(shared::StructurePush));
    const uint32_t boxCount = cfg.traversalUsesBoxes() ? domainCount() : 0;
    const bool ownDomainMajorants = cfg.traversalUsesBoxes() && cfg.traversal != TraversalKind::GridBvh;
    gpu::GpuTimer timer(mCtx, 4);
    mCtx.submitAndWait([&](VkCommandBuffer cmd) {
        timer.reset(cmd);
        uint32_t scope = timer.begin(cmd, "majorants");
        if (mScene.grid) {
            const uint32_t n = uint32_t(mScene.grid->ranges.size());
            shared::StructurePush push{mParamsBuffer.address(), mGridRanges.address(), mGridMajorants.address(), n, 0};
            mMajorantPipeline.dispatch(cmd, &push, (n + 63) / 64);
        }
        if (ownDomainMajorants && boxCount > 0) {
            shared::StructurePush push{mParamsBuffer.address(), mDomainRanges.address(), mDomainMajorants.address(),
                                       boxCount, 0};
            mMajorantPipeline.dispatch(cmd, &push, (boxCount + 63) / 64);
        }
        gpu::computeBarrier(cmd);
        if (rq && boxCount > 0) {
            shared::StructurePush push{mParamsBuffer.address(), mParams.domainMajorants, mDomainAabbs.address(),
                                       boxCount, scene::shaderConstant(cfg.traversal)};
            mAabbPipeline.dispatch(cmd, &push, (boxCount + 63) / 64);
            gpu::computeBarrier(cmd);
            mDomainAccel.build(cmd, mDomainAabbs);
        }
        timer.end(cmd, scope);
        gpu::computeBarrier(cmd);
    });
    mMajorantSeconds = timer.total("majorants");
    if (cfg.traversalUsesBoxes()) {
        std::vector<float> majorants(boxCount);
        if (boxCount > 0) {
            const gpu::Buffer& src = cfg.traversal == TraversalKind::GridBvh ? mGridMajorants : mDomainMajorants;
            src.download(majorants.data(), majorants.size() * sizeof(float));
        }
        mActiveBoxes = uint64_t(std::count_if(majorants.begin(), majorants.end(), [](float m) { return m > 0.0f; }));
        if (cfg.backend == Backend::Sw) updateSwCulling(majorants);
        mParams.domainInfo.y = mActiveBoxes > 0 ? 1u : 0u;
        mParamsBuffer.upload(&mParams, sizeof mParams);
    }
    mStructureSeconds = hostTimer.seconds();
    mHasTf = true;
}

void Renderer::overrideMajorants(const std::vector<float>& majorants) {
    AMRVK_CHECK(mScene.grid && mScene.config.traversal == TraversalKind::GridDda,
                "overrideMajorants: grid-dda traversal only");
    AMRVK_CHECK(majorants.size() == mScene.grid->ranges.size(), "overrideMajorants: ", majorants.size(),
                " values for ", mScene.grid->ranges.size(), " macrocells");
    mGridMajorants.upload(majorants.data(), majorants.size() * sizeof(float));
}

std::vector<float> Renderer::downloadMajorants() const {
    AMRVK_CHECK(mScene.grid.has_value(), "downloadMajorants: no macrocell grid in this configuration");
    std::vector<float> out(mScene.grid->ranges.size());
    mGridMajorants.download(out.data(), out.size() * sizeof(float));
    return out;
}

std::vector<float> Renderer::downloadDomainMajorants() const {
    AMRVK_CHECK(mDomainMajorants.valid(), "downloadDomainMajorants: no traversal boxes in this configuration");
    std::vector<float> out(mScene.domains.boxes.size());
    if (!out.empty()) mDomainMajorants.download(out.data(), out.size() * sizeof(float));
    return out;
}

const gpu::ComputePipeline& Renderer::pathTracePipeline(Mode mode) {
    int key = int(mode);
    auto it = mPathTrace.find(key);
    if (it != mPathTrace.end()) return it->second;
    const StructureConfig& cfg = mScene.config;
    const uint32_t modeConst = mode == Mode::Ae    ? shared::kModeAe
                               : mode == Mode::Ss  ? shared::kModeSs
                               : mode == Mode::Dvr ? shared::kModeDvr
                                                   : shared::kModeMs;
    // The ray-query variant is compiled only for rq: its SPIR-V needs the rayQuery feature.
    const char* shader = cfg.backend == Backend::Rq ? "path_trace_rq" : "path_trace";
    auto [pos, ok] = mPathTrace.emplace(
        key, gpu::ComputePipeline(mCtx, gpu::loadShader(shader),
                                  std::string("path_trace.") + scene::modeName(mode) + "." + cfg.label(),
                                  sizeof(shared::PushConstants),
                                  {{0, modeConst}, {1, scene::shaderConstant(cfg.sampler)},
                                   {2, scene::shaderConstant(cfg.traversal)}, {3, scene::shaderConstant(cfg.backend)}}));
    return pos->second;
}

void Renderer::writeParams(const scene::RenderSettings& s) {
    AMRVK_CHECK(s.width > 0 && s.height > 0 && s.width <= 16384 && s.height <= 16384, "--size ", s.width, "x",
                s.height, " is outside 1..16384");
    AMRVK_CHECK(s.densityScale >= 0 && std::isfinite(s.densityScale), "--density-scale ", s.densityScale,
                " must be finite and >= 0");
    const amr::Transform& xf = mScene.model->voxelToWorld;
    const glm::dvec3 origin(mScene.localOrigin);
    scene::RayBasis rb = scene::makeRayBasis(s.camera, s.width, s.height, xf, origin);
    mParams.eye = v4(rb.eye);
    mParams.dir00 = v4(rb.dir00);
    mParams.du = v4(rb.du);
    mParams.dv = v4(rb.dv);
    mParams.image = glm::uvec4(uint32_t(s.width), uint32_t(s.height), s.seed, 0u);
    mParams.boundsHi.w = float(s.densityScale);
    mParams.ambient = v4(s.ambient);
    mParams.background = v4(s.background.value_or(s.ambient));
    mParams.shading = glm::vec4(float(std::clamp(s.g, -0.999, 0.999)), float(s.lights.size()), 0, 0);
    for (size_t i = 0; i < shared::kMaxLights; ++i) mParams.lights[i] = {};
    const auto lights = scene::lightsInVoxelSpace(s, xf);
    for (size_t i = 0; i < lights.size(); ++i) {
        const scene::VoxelLight& L = lights[i];
        mParams.lights[i] = L.point ? shared::LightGpu{v4(L.posOrDir - origin, shared::kLightPoint), v4(L.radiance)}
                                    : shared::LightGpu{v4(L.posOrDir, shared::kLightDirectional), v4(L.radiance)};
    }
    AMRVK_CHECK(s.dvrStep > 0 && std::isfinite(s.dvrStep), "--dt ", s.dvrStep, " must be finite and > 0");
    // dvr shading light: the first directional light, else a headlight along the view direction.
    glm::dvec3 shadeDir = -glm::dvec3(rb.dir00 + 0.5 * double(s.width) * rb.du + 0.5 * double(s.height) * rb.dv);
    for (const scene::VoxelLight& L : lights)
        if (!L.point) {
            shadeDir = L.posOrDir;
            break;
        }
    mParams.dvr = glm::vec4(float(s.dvrStep), s.dvrShading ? 1.0f : 0.0f, 0.99f, 0.3f);
    mParams.dvrLight = v4(glm::normalize(shadeDir));
    const uint64_t pixels = uint64_t(s.width) * uint64_t(s.height);
    if (!mAccum.valid() || s.width != mWidth || s.height != mHeight) {
        mAccum = gpu::Buffer();
        mAccum = gpu::Buffer(mCtx, pixels * 2 * sizeof(glm::vec4), gpu::MemoryKind::Device, "accumulation");
        mWidth = s.width;
        mHeight = s.height;
    }
    mParams.accum = mAccum.address();
    mParamsBuffer.upload(&mParams, sizeof mParams);
}

scene::RenderOutput Renderer::render(const scene::RenderSettings& settings, uint32_t spp,
                              const std::function<void(uint32_t, uint32_t)>& progress) {
    return render(settings, spp, progress, {}, {});
}

scene::RenderOutput Renderer::render(const scene::RenderSettings& settings, uint32_t spp,
                              const std::function<void(uint32_t, uint32_t)>& progress,
                              const std::vector<uint32_t>& snapshotSpp,
                              const std::function<void(const scene::RenderOutput&)>& snapshot) {
    AMRVK_CHECK(mHasTf, "internal: render() before setTransferFunction()");
    AMRVK_CHECK(spp >= 1, "--spp must be at least 1");
    writeParams(settings);
    const gpu::ComputePipeline& pipeline = pathTracePipeline(settings.mode);
    mAccum.fillZero();
    scene::RenderOutput out;
    out.spp = spp;
    const uint32_t gx = (uint32_t(settings.width) + 7) / 8, gy = (uint32_t(settings.height) + 7) / 8;
    gpu::GpuTimer timer(mCtx, 64);
    uint32_t done = 0, batch = 1;
    size_t nextSnapshot = 0;
    std::array<uint32_t, shared::kCounterCount> counters{};
    std::vector<glm::vec4> accum(size_t(settings.width) * size_t(settings.height) * 2);
    auto readBack = [&](scene::RenderOutput& o) {
        mAccum.download(accum.data(), accum.size() * sizeof(glm::vec4));
        o.mean = amrvk::Image(settings.width, settings.height);
        o.sumSq.resize(accum.size() / 2);
        for (size_t i = 0; i < o.mean.pixels.size(); ++i) {
            glm::vec4 sum = accum[2 * i];
            float count = sum.w > 0 ? sum.w : 1.0f;
            o.mean.pixels[i] = glm::vec4(glm::vec3(sum) / count, 1.0f);
            o.sumSq[i] = accum[2 * i + 1];
        }
    };
    while (done < spp) {
        while (nextSnapshot < snapshotSpp.size() && snapshotSpp[nextSnapshot] <= done) ++nextSnapshot;
        uint32_t n = std::min(batch, spp - done);
        if (nextSnapshot < snapshotSpp.size()) n = std::min(n, snapshotSpp[nextSnapshot] - done);
        mCtx.submitAndWait([&](VkCommandBuffer cmd) {
            timer.reset(cmd);
            vkCmdFillBuffer(cmd, mCounters.handle(), 0, VK_WHOLE_SIZE, 0);
            gpu::computeBarrier(cmd);
            for (uint32_t i = 0; i < n; ++i) {
                uint32_t scope = timer.begin(cmd, "path_trace");
                shared::PushConstants push{mParamsBuffer.address(), done + i, 0};
                pipeline.dispatch(cmd, &push, gx, gy);
                timer.end(cmd, scope);
                gpu::computeBarrier(cmd);
            }
        });
        mCounters.download(counters.data(), sizeof counters);
        uint32_t largest = 0;
        for (uint32_t k = 0; k < shared::kCounterCount; ++k) {
            out.stats.counters[k] += counters[k];
            largest = std::max(largest, counters[k]);
        }
        out.stats.gpuSeconds += timer.total("path_trace");
        done += n;
        // Grow batches while the 32-bit counters stay far from overflowing.
        if (largest < (1u << 28) && batch < 64) batch *= 2;
        else if (largest >= (1u << 30) && batch > 1) batch /= 2;
        out.stats.paths = uint64_t(done) * uint64_t(settings.width) * uint64_t(settings.height);
        if (snapshot && nextSnapshot < snapshotSpp.size() && snapshotSpp[nextSnapshot] == done) {
            scene::RenderOutput partial;
            partial.spp = done;
            partial.stats = out.stats;
            readBack(partial);
            snapshot(partial);
        }
        if (progress) progress(done, spp);
    }
    readBack(out);
    return out;
}

}  // namespace amrvk::render
