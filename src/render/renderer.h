#pragma once
// The GPU renderer: uploads the structures of one VolumeScene configuration (and only those),
// keeps majorants and culled traversal hierarchies in step with the transfer function
// (majorants.comp; sw: BVH over the boxes with majorant > 0 rebuilt on the host when that set
// changes; rq: domain_aabbs.comp + BLAS rebuild; kdtree: the tree itself is rebuilt per TF), and
// accumulates path-traced samples (path_trace.comp or path_trace_rq), 1 spp per dispatch.
// A new configuration needs a new Renderer; destroying the old one frees its device memory.
#include <array>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "gpu/acceleration_structure.h"
#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu/context.h"
#include "render/camera.h"
#include "render/image_io.h"
#include "render/transfer_function.h"
#include "render/volume_scene.h"
#include "shared/render_params.h"

namespace amrvk::render {

// ae | ss | ms: unbiased path tracing. dvr: the ray-marching baseline (biased by its step).
enum class Mode { Ae, Ss, Ms, Dvr };
Mode parseMode(const std::string& name);
const char* modeName(Mode mode);

struct Light {
    bool point = false;
    glm::dvec3 posOrDir{0.0, 0.0, 1.0};  // world position, or world direction towards the light
    glm::dvec3 radiance{1.0};            // radiance (directional) or intensity (point, 1/d^2 in world units)
};

// A light in voxel space: point position or unit direction towards the light; radiance
// (directional) or intensity scaled so that 1/d^2 with d in voxel units equals the world falloff.
struct VoxelLight {
    bool point = false;
    glm::dvec3 posOrDir{0.0};
    glm::dvec3 radiance{0.0};
};

struct RenderSettings;
std::vector<VoxelLight> lightsInVoxelSpace(const RenderSettings& settings, const amr::Transform& voxelToWorld);

struct RenderSettings {
    Mode mode = Mode::Ms;
    int width = 256, height = 256;
    uint32_t seed = 1;
    Camera camera;
    double densityScale = 1.0;
    double g = 0.0;                      // Henyey-Greenstein asymmetry, clamped to [-0.999, 0.999]
    glm::dvec3 ambient{1.0};             // environment radiance seen by escaping rays
    std::optional<glm::dvec3> background;  // seen by escaping primary rays; default = ambient
    std::vector<Light> lights;           // at most shared::kMaxLights
    double dvrStep = 0.5;                // dvr: step / finest cell width at the sample (ExaBrick's dt)
    bool dvrShading = false;             // dvr: gradient shading by the first directional light (else a headlight)
};

struct RenderStats {
    uint64_t paths = 0;
    double gpuSeconds = 0;  // GPU time of the path-trace dispatches
    std::array<uint64_t, shared::kCounterCount> counters{};
    uint64_t counter(uint32_t k) const { return counters[k]; }
};

struct RenderOutput {
    Image mean;                      // linear radiance per pixel (rgb), a = 1
    std::vector<glm::vec4> sumSq;    // per-pixel sum of squared samples (rgb)
    uint32_t spp = 0;
    RenderStats stats;
};

class Renderer {
public:
    // The scene must stay alive and configured as it is (kdtree: setTransferFunction rebuilds it).
    Renderer(gpu::Context& ctx, VolumeScene& scene);

    // Uploads the TF, recomputes every majorant on the GPU and updates the culled traversal
    // structure (and, for kdtree, rebuilds the tree for this TF).
    void setTransferFunction(const TransferFunction& tf);
    // Accumulates `spp` samples per pixel from scratch. `progress(done, total)` after each batch.
    RenderOutput render(const RenderSettings& settings, uint32_t spp,
                        const std::function<void(uint32_t, uint32_t)>& progress = {});
    // The same, also handing out the image after each sample count in `snapshotSpp` (ascending):
    // `snapshot(out)` sees the mean so far, out.spp samples and the GPU seconds spent so far
    // (downloads are not timed).
    RenderOutput render(const RenderSettings& settings, uint32_t spp,
                        const std::function<void(uint32_t, uint32_t)>& progress,
                        const std::vector<uint32_t>& snapshotSpp,
                        const std::function<void(const RenderOutput&)>& snapshot);
    // Majorant per macrocell as computed on the GPU (grid traversals; for tests and statistics).
    std::vector<float> downloadMajorants() const;
    // Majorant per traversal box (abr | brick | ext-brick | kdtree), as computed on the GPU.
    std::vector<float> downloadDomainMajorants() const;
    // GPU seconds of the last TF update: majorant passes (+ AABB pass and BLAS build for rq).
    double majorantSeconds() const { return mMajorantSeconds; }
    // Host seconds of the last TF update spent on TF-dependent structures (kd-tree, sw culling BVH).
    double structureUpdateSeconds() const { return mStructureSeconds; }
    // Traversal boxes (or macrocells for grid-bvh) with majorant > 0 after the last TF update.
    uint64_t activeTraversalBoxes() const { return mActiveBoxes; }
    const StructureConfig& config() const { return mScene.config; }
    // Device address of the RenderParams buffer (valid after setTransferFunction), for test kernels.
    uint64_t paramsAddress() const { return mParamsBuffer.address(); }
    // Overwrites the macrocell majorants (grid-dda only; tests: deliberate overestimates).
    void overrideMajorants(const std::vector<float>& majorants);
    gpu::Context& context() { return mCtx; }

private:
    void writeParams(const RenderSettings& settings);
    const gpu::ComputePipeline& pathTracePipeline(Mode mode);
    void uploadDomainBoxes();
    void updateSwCulling(const std::vector<float>& majorants);
    uint32_t domainCount() const;

    gpu::Context& mCtx;
    VolumeScene& mScene;
    shared::RenderParams mParams{};
    gpu::Buffer mBricks, mBrickValues, mSamplerNodes, mSamplerPrims, mSamplerAabbs, mAbrs, mAbrBrickList;
    gpu::Buffer mGridRanges, mGridMajorants, mTfPositions, mTfColors, mAccum, mCounters, mParamsBuffer;
    gpu::Buffer mDenseValues;
    gpu::Buffer mDomainBoxes, mDomainRanges, mDomainMajorants, mDomainNodes, mDomainPrims, mDomainAabbs;
    gpu::AabbAccelerationStructure mSamplerAccel, mDomainAccel;
    gpu::ComputePipeline mMajorantPipeline, mAabbPipeline;
    std::map<int, gpu::ComputePipeline> mPathTrace;  // created on first use per mode
    std::vector<uint8_t> mActiveMask;                // sw culling: boxes in the current domain BVH
    int mWidth = 0, mHeight = 0;
    double mMajorantSeconds = 0, mStructureSeconds = 0;
    uint64_t mActiveBoxes = 0;
    bool mHasTf = false;
};

}  // namespace amrvk::render
