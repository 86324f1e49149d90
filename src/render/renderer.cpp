#include "render/renderer.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <span>

#include "core/error.h"
#include "gpu/shader_library.h"

namespace amrvk::shaders {
std::span<const gpu::EmbeddedShader> passShaders();
}

namespace amrvk::render {

namespace {

}  // namespace

Renderer::Renderer(gpu::Context& ctx, std::shared_ptr<const scene::Volume> volume, const scene::StructureConfig& config,
                   gpu::ShaderLibrary shaders)
    : mCtx(ctx), mShaders(std::move(shaders)), mScene(std::move(volume), config), mPathTrace(ctx) {
    gpu::registerShaders(shaders::passShaders());
    mParamsBuffer = gpu::Buffer(ctx, sizeof(shared::RenderParams), gpu::MemoryKind::Device, "renderParams");
    mParams.counters = mPathTrace.countersAddress();
    mParams.pathStats = mPathTrace.pathStatsAddress();
    writeShading(mSettings);  // defaults (density scale 1, tracking cap) for kernels run before setSettings
    buildDeviceScene();
}

void Renderer::buildDeviceScene() {
    mMajorants.reset();  // refers to the device scene: goes first
    mDevice.reset();
    mDevice = std::make_unique<DeviceScene>(mCtx, mScene);
    mMajorants = std::make_unique<MajorantPass>(mCtx, mScene, *mDevice, mShaders);
    mMajorants->setGridBlockUse(mGridBlockUse);
    mMajorants->setSubMajorantCheck(mSubMajorantCheck);
    mMajorants->setSubMajorantsInBackground(mSubInBackground);
    mMinorantsOff = mMajorants->setMinorants(mMinorantsWanted);
    ++mCounts.deviceScenes;
    mParams.scene = mDevice->params();
    if (mGridBvhQueryAfter > 0 && mParams.scene.gridBvhQueryAfter > 0)  // grid-bvh, K set by a test
        mParams.scene.gridBvhQueryAfter = mGridBvhQueryAfter;
    takeMajorantParams();
}

void Renderer::takeMajorantParams() {
    mParams.majorants = mMajorants->params();
    mParamsDirty = true;
}

void Renderer::redo(const scene::Invalidation& inv, const scene::RenderSettings* s) {
    if (inv.viewParams) {
        writeView(*s);
        ++mCounts.viewWrites;
    }
    if (inv.shadingParams) {
        writeShading(*s);
        ++mCounts.shadingWrites;
    }
    if (inv.viewParams || inv.shadingParams) mParamsDirty = true;
    if (inv.accumulationBuffer && mPathTrace.resize(s->width, s->height)) {
        ++mCounts.accumulationBuffers;
        mParamsDirty = true;  // its address is in RenderParams
    }
    if (inv.deviceScene) buildDeviceScene();
    if (inv.pipelines) {
        mPathTrace.dropPipelines();
        ++mCounts.pipelineDrops;
    }
    if (inv.minorants) {
        mMinorantsWanted = s->controlExtinction == scene::ControlExtinction::Minorant;
        mMinorantsOff = mMajorants->setMinorants(mMinorantsWanted);
        takeMajorantParams();
    }
    // Majorants, culling and the kd-tree go together (invalidatedBy sets all three); they need a TF.
    // The minorants are made by the same pass.
    if ((inv.majorants || inv.culling || inv.kdTree) && mTf) {
        mMajorants->prepare(*mTf);
        takeMajorantParams();
        uploadParams();
        mMajorants->dispatch(mParamsBuffer.address());
        takeMajorantParams();  // grid-dda's block decision comes from the GPU's majorants
        ++mCounts.majorantDispatches;
    }
    if (inv.accumulation) {
        mPathTrace.reset();
        ++mCounts.accumulationResets;
    }
}

void Renderer::uploadParams() {
    if (!mParamsDirty) return;
    mParams.accum = mPathTrace.accumAddress();
    mParamsBuffer.upload(&mParams, sizeof mParams);
    mParamsDirty = false;
}

uint64_t Renderer::paramsAddress() {
    uploadParams();
    return mParamsBuffer.address();
}

void Renderer::commit(const Edit& e) {
    if (e.tf)
        AMRVK_CHECK(!e.tf->positions().empty() && e.tf->positions().size() == e.tf->colors().size(),
                    "transfer function has no nodes");
    scene::ChangeSet changes;
    if (e.settings) {
        changes = mHasSettings
                      ? scene::settingsChanges(mSettings, *e.settings)
                      : scene::ChangeSet(scene::Change::Camera) | scene::Change::ImageSize | scene::Change::Lighting;
        if (!mHasSettings && e.settings->controlExtinction != scene::ControlExtinction::None)
            changes |= scene::Change::Control;
        if (!changes.empty()) scene::validateSettings(*e.settings);
    }
    if (e.tf) changes |= scene::Change::TransferFunction;
    const bool newStructure = e.structure && !(*e.structure == mScene.config() && mBroken.empty());
    if (changes.empty() && !newStructure) return;
    if (newStructure) {
        configure(*e.structure);
        changes |= scene::Change::Structure;
    }
    const shared::RenderParams saved = mParams;  // an invalid camera or light changes nothing
    const UpdateCounts counts = mCounts;
    const std::optional<scene::TransferFunction> tf = mTf;
    if (e.tf) mTf = *e.tf;
    try {
        redo(scene::invalidatedBy(changes), e.settings ? &*e.settings : &mSettings);
    } catch (...) {
        if (!newStructure) {  // a new structure's device copy is made: it stays, with the old TF's majorants to come
            mParams = saved;
            mCounts = counts;
            mTf = tf;
        }
        throw;
    }
    if (e.settings) {
        mSettings = *e.settings;
        mHasSettings = true;
    }
}

void Renderer::configure(const scene::StructureConfig& config) {
    const scene::StructureConfig previous = mScene.config();
    mMajorants->cancelSubMajorants();  // a background build reads the structures configure frees
    try {
        mScene.configure(config);
    } catch (...) {
        // The host structures of `previous` may be freed already: build them again, so the device
        // copy (untouched so far) and the majorant pass keep matching the scene.
        try {
            mScene.configure(previous);
        } catch (const std::exception& e) {
            mBroken = e.what();
        }
        throw;
    }
    mBroken.clear();
}

void Renderer::setStructure(const scene::StructureConfig& config) { commit({.structure = config}); }

void Renderer::setTransferFunction(const scene::TransferFunction& tf) { commit({.tf = tf}); }

void Renderer::writeView(const scene::RenderSettings& s) {
    const scene::RayBasis rb = scene::makeRayBasis(s.camera, s.width, s.height, mScene.volume().model.voxelToWorld);
    mParams.view.eye = glm::vec3(mScene.volume().toLocal(rb.eye));
    mParams.view.dir00 = glm::vec3(rb.dir00);
    mParams.view.du = glm::vec3(rb.du);
    mParams.view.dv = glm::vec3(rb.dv);
    mParams.view.width = uint32_t(s.width);
    mParams.view.height = uint32_t(s.height);
    mParams.view.seed = s.seed;
}

void Renderer::writeShading(const scene::RenderSettings& s) {
    shared::ShadingGpu& sh = mParams.shading;
    sh = {};
    sh.ambient = glm::vec3(s.ambient);
    sh.background = glm::vec3(s.background.value_or(s.ambient));
    sh.g = float(std::clamp(s.g, -0.999, 0.999));
    sh.densityScale = float(s.densityScale);
    sh.maxTrackingSteps = s.maxTrackingSteps;
    const auto lights = scene::lightsInVoxelSpace(s, mScene.volume().model.voxelToWorld);
    sh.lightCount = uint32_t(lights.size());
    for (size_t i = 0; i < lights.size(); ++i) {
        const scene::VoxelLight& L = lights[i];
        sh.lights[i].type = uint32_t(L.point ? shared::LightType::Point : shared::LightType::Directional);
        sh.lights[i].posOrDir = glm::vec3(L.point ? mScene.volume().toLocal(L.posOrDir) : L.posOrDir);
        sh.lights[i].radiance = glm::vec3(L.radiance);
    }
    // dvr shading light: the first directional light, else a headlight along the view direction.
    const scene::RayBasis rb = scene::makeRayBasis(s.camera, s.width, s.height, mScene.volume().model.voxelToWorld);
    glm::dvec3 shadeDir = -(rb.dir00 + 0.5 * double(s.width) * rb.du + 0.5 * double(s.height) * rb.dv);
    for (const scene::VoxelLight& L : lights)
        if (!L.point) {
            shadeDir = L.posOrDir;
            break;
        }
    sh.dvrStep = float(s.dvrStep);
    sh.dvrShading = s.dvrShading ? 1u : 0u;
    sh.dvrOpacityStop = 0.99f;
    sh.dvrAmbient = 0.3f;
    sh.dvrLightDir = glm::vec3(glm::normalize(shadeDir));
    // The cut-away is part of the medium; its block is rewritten with the shading block.
    mParams.cut = scene::cutAwayGpu(s.cut, mScene.volume().model.voxelToWorld, -mScene.volume().toLocal(glm::dvec3(0.0)));
}

void Renderer::setSettings(const scene::RenderSettings& s) { commit({.settings = s}); }

void Renderer::setCamera(const scene::Camera& camera) {
    scene::RenderSettings s = mSettings;
    s.camera = camera;
    setSettings(s);
}

std::future<gpu::ComputePipeline> warmPathTracer(gpu::Context& ctx, TracerVariant variant,
                                                 const scene::StructureConfig& config,
                                                 const gpu::ShaderLibrary& shaders) {
    gpu::registerShaders(shaders::passShaders());  // here, before the other thread looks them up
    return std::async(std::launch::async, [&ctx, variant, config, shaders] {
        // At the lowest priority: it takes a core when one idles (the serial stretches of the
        // build), and runs alone once the renderer waits for it.
        setpriority(PRIO_PROCESS, pid_t(syscall(SYS_gettid)), 19);
        return compilePathTracer(ctx, "path_trace", sizeof(shared::PushConstants), variant, config, shaders);
    });
}

void Renderer::adoptPathTracer(TracerVariant variant, std::future<gpu::ComputePipeline>& warm) {
    if (!warm.valid()) return;
    gpu::ComputePipeline compiled;
    try {
        compiled = warm.get();
    } catch (...) {  // compiled again at the first accumulate, which reports the error
        return;
    }
    mPathTrace.adopt(variant, mScene.config(), std::move(compiled));
}

void Renderer::setShaders(gpu::ShaderLibrary shaders) {
    // Compile first (throws before anything is replaced), then drop the rest and reset.
    if (mHasSettings) mPathTrace.recompile(TracerVariant::of(mSettings), mScene.config(), shaders);
    mShaders = std::move(shaders);
    const scene::Invalidation inv = scene::invalidatedBy(scene::Change::Shaders);
    if (mHasSettings) {
        ++mCounts.pipelineDrops;  // recompile() replaced every pipeline
        redo({.accumulation = inv.accumulation});
    } else {
        redo(inv);
    }
}

void Renderer::resetAccumulation() { redo({.accumulation = true}); }

void Renderer::setFirstSample(uint32_t first) {
    resetAccumulation();
    mPathTrace.setFirstSample(first);
}

void Renderer::requireRenderable() const {
    AMRVK_CHECK(mBroken.empty(), "no structures to render with (the last structure change failed: ", mBroken, ")");
    AMRVK_CHECK(mTf.has_value(), "internal: accumulate() before setTransferFunction()");
    AMRVK_CHECK(mHasSettings, "internal: accumulate() before setSettings()");
}

const gpu::ComputePipeline& Renderer::currentPipeline() {
    requireRenderable();
    const gpu::ComputePipeline& pipeline = mPathTrace.pipeline(TracerVariant::of(mSettings), mScene.config(), mShaders);
    uploadParams();
    return pipeline;
}

void Renderer::adoptSubMajorants() {
    if (mMajorants->adoptSubMajorants()) takeMajorantParams();
}

bool Renderer::waitForSubMajorants() {
    const bool came = mMajorants->waitForSubMajorants();
    if (came) takeMajorantParams();
    return came;
}

void Renderer::setSubMajorantsInBackground(bool on) {
    mSubInBackground = on;
    mMajorants->setSubMajorantsInBackground(on);
}

double Renderer::accumulateRows(uint32_t rows) {
    adoptSubMajorants();
    const gpu::ComputePipeline& pipeline = currentPipeline();
    return mPathTrace.rows(pipeline, mParamsBuffer.address(), rows);
}

void Renderer::accumulate(uint32_t spp, const std::function<void(uint32_t, uint32_t)>& progress, uint32_t maxBatch) {
    adoptSubMajorants();
    const gpu::ComputePipeline& pipeline = currentPipeline();
    const uint32_t start = mPathTrace.spp();
    mPathTrace.accumulate(pipeline, mParamsBuffer.address(), spp, [&](uint32_t total) {
        if (progress) progress(total - start, spp);
    }, maxBatch);
}

StagedReport Renderer::accumulateStaged(const StagedRender& staged, uint32_t spp,
                                        const std::function<void(uint32_t, uint32_t)>& progress) {
    requireRenderable();
    waitForSubMajorants();  // every rank renders with the same structures
    AMRVK_CHECK(mSettings.mode != scene::Mode::Dvr, "staged rendering: mode dvr is not supported (use ae, ss or ms)");
    AMRVK_CHECK(mPathTrace.rowsDone() == 0, "internal: a staged render while a sample is half traced");
    uploadParams();
    StagedPass pass(mCtx,
                    compilePathTracer(mCtx, "path_trace_dp", sizeof(shared::DataParallelPush),
                                      TracerVariant::of(mSettings), mScene.config(), mShaders),
                    uint32_t(mSettings.width) * uint32_t(mSettings.height));
    StagedReport report =
        pass.run(mParamsBuffer.address(), mPathTrace.firstSample() + mPathTrace.spp(), spp, staged, progress);
    mPathTrace.addSamples(spp, report.stats);
    return report;
}

scene::RenderOutput Renderer::render(const scene::RenderSettings& settings, uint32_t spp,
                                     const std::function<void(uint32_t, uint32_t)>& progress,
                                     const std::vector<uint32_t>& snapshotSpp,
                                     const std::function<void(const scene::RenderOutput&)>& snapshot) {
    AMRVK_CHECK(spp >= 1, "--spp must be at least 1");
    waitForSubMajorants();  // one image from scratch: the same structures for every sample
    setSettings(settings);
    if (accumulatedSpp() > 0) resetAccumulation();
    auto onBatch = [&](uint32_t, uint32_t) {
        if (progress) progress(accumulatedSpp(), spp);
    };
    for (uint32_t next : snapshotSpp) {
        if (next <= accumulatedSpp() || next >= spp) continue;
        accumulate(next - accumulatedSpp(), onBatch);
        if (snapshot) snapshot(output());
    }
    accumulate(spp - accumulatedSpp(), onBatch);
    scene::RenderOutput out = output();
    if (snapshot && std::find(snapshotSpp.begin(), snapshotSpp.end(), spp) != snapshotSpp.end()) snapshot(out);
    return out;
}

void Renderer::overrideMajorants(const std::vector<float>& majorants) {
    mMajorants->overrideGridMajorants(majorants);
    takeMajorantParams();
    resetAccumulation();
}

void Renderer::setSubMajorantCheck(bool on) {
    mSubMajorantCheck = on;
    mMajorants->setSubMajorantCheck(on);
    takeMajorantParams();
}

void Renderer::overrideSubMajorants(uint32_t q) {
    mMajorants->overrideSubMajorants(q);
    resetAccumulation();
}

void Renderer::setGridBvhQueryAfter(uint32_t culledSteps) {
    AMRVK_CHECK(culledSteps >= 1, "grid-bvh: culled macrocells stepped before a box query must be >= 1, not 0");
    mGridBvhQueryAfter = culledSteps;
    if (mParams.scene.gridBvhQueryAfter > 0) {  // grid-bvh
        mParams.scene.gridBvhQueryAfter = culledSteps;
        mParamsDirty = true;
    }
}

void Renderer::setGridBlockUse(MajorantPass::GridBlockUse use) {
    mGridBlockUse = use;
    mMajorants->setGridBlockUse(use);
    takeMajorantParams();
}

}  // namespace amrvk::render
