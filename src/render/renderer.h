#pragma once
// The GPU renderer: uploads the structures of one scene::VolumeScene configuration (and only those),
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
#include "scene/render_output.h"
#include "scene/render_settings.h"
#include "scene/transfer_function.h"
#include "scene/volume_scene.h"
#include "shared/render_params.h"

namespace amrvk::render {

class Renderer {
public:
    // The scene must stay alive and configured as it is (kdtree: setTransferFunction rebuilds it).
    Renderer(gpu::Context& ctx, scene::VolumeScene& volume);

    // Uploads the TF, recomputes every majorant on the GPU and updates the culled traversal
    // structure (and, for kdtree, rebuilds the tree for this TF).
    void setTransferFunction(const scene::TransferFunction& tf);
    // Accumulates `spp` samples per pixel from scratch. `progress(done, total)` after each batch.
    scene::RenderOutput render(const scene::RenderSettings& settings, uint32_t spp,
                        const std::function<void(uint32_t, uint32_t)>& progress = {});
    // The same, also handing out the image after each sample count in `snapshotSpp` (ascending):
    // `snapshot(out)` sees the mean so far, out.spp samples and the GPU seconds spent so far
    // (downloads are not timed).
    scene::RenderOutput render(const scene::RenderSettings& settings, uint32_t spp,
                        const std::function<void(uint32_t, uint32_t)>& progress,
                        const std::vector<uint32_t>& snapshotSpp,
                        const std::function<void(const scene::RenderOutput&)>& snapshot);
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
    const scene::StructureConfig& config() const { return mScene.config; }
    // Device address of the RenderParams buffer (valid after setTransferFunction), for test kernels.
    uint64_t paramsAddress() const { return mParamsBuffer.address(); }
    // Overwrites the macrocell majorants (grid-dda only; tests: deliberate overestimates).
    void overrideMajorants(const std::vector<float>& majorants);
    gpu::Context& context() { return mCtx; }

private:
    void writeParams(const scene::RenderSettings& settings);
    const gpu::ComputePipeline& pathTracePipeline(scene::Mode mode);
    void uploadDomainBoxes();
    void updateSwCulling(const std::vector<float>& majorants);
    uint32_t domainCount() const;

    gpu::Context& mCtx;
    scene::VolumeScene& mScene;
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
