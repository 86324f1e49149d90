#pragma once
// Everything that depends on the transfer function (barney's computeMajorants(tf) over ranges
// built once): the TF nodes on the GPU; the majorant of every macrocell and traversal box
// (majorants.comp: exact TF alpha maximum over the value range); the culled traversal hierarchy
// over the boxes whose majorant can be > 0 (sw: a BVH built on the host from the value ranges it
// already holds; rq: domain_aabbs.comp collapses culled boxes, then a BLAS rebuild); and, for the
// kdtree traversal, the TF-specific kd-tree itself; for grid traversals with sub-majorants, the
// sub-boxes of the loose macrocells (scene/sub_majorants.h). Fills shared::MajorantsGpu. Never touches the
// TF-independent structures (VolumeScene, DeviceScene), which it only reads.
#include <atomic>
#include <cstdint>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "accel/kdtree.h"
#include "core/gpu_deadline.h"
#include "gpu/acceleration_structure.h"
#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu/context.h"
#include "gpu/shader_library.h"
#include "render/device_scene.h"
#include "scene/sub_majorants.h"
#include "scene/transfer_function.h"
#include "scene/volume_scene.h"

namespace amrvk::render {

class MajorantPass {
public:
    // All three must outlive the pass and stay as they are (a structure change makes a new pass);
    // the pass's pipelines come from `shaders`.
    MajorantPass(gpu::Context& ctx, const scene::VolumeScene& scene, const DeviceScene& device,
                 const gpu::ShaderLibrary& shaders);
    ~MajorantPass();  // stops a sub-majorant build in the background (cancelSubMajorants)
    MajorantPass(const MajorantPass&) = delete;
    MajorantPass& operator=(const MajorantPass&) = delete;

    // Host part of a TF change: TF nodes, the kd-tree and its boxes (kdtree traversal), and the set
    // of traversal boxes whose value range can reach alpha > 0 (TransferFunction::maxAlpha, the
    // CPU twin of the shader's tfMaxAlpha) with, for sw, the BVH over them (rebuilt only when that
    // set changed). Fills params(); dispatch() must follow once they are on the GPU.
    void prepare(const scene::TransferFunction& tf);
    // GPU part: majorants of every structure, and for rq the AABBs and BLAS of the culled boxes.
    // paramsAddress: a RenderParams buffer holding params() and the scene's SceneGpu. Under the
    // adaptive --gpu-timeout the two shaders are held to their measured pace (gpu/paced_submit.h).
    void dispatch(uint64_t paramsAddress);

    const shared::MajorantsGpu& params() const { return mParams; }
    double gpuSeconds() const { return mGpuSeconds; }    // last dispatch: majorant passes (+ AABBs, BLAS)
    double hostSeconds() const { return mHostSeconds; }  // last prepare: kd-tree and sw culling BVH
    double kdTreeSeconds() const { return mKdTree ? mKdTree->buildSeconds : 0.0; }
    // Traversal boxes (macrocells for grid-bvh) whose range can reach alpha > 0 under the last TF.
    uint64_t activeBoxes() const { return mActiveBoxes; }
    // Per traversal box: 1 when its range can reach alpha > 0 under the last TF (the culling set).
    const std::vector<uint8_t>& activeMask() const { return mActive; }
    // The traversal boxes (local voxel space) of abr | brick | ext-brick | kdtree; empty otherwise.
    const std::vector<shared::AabbGpu>& traversalBoxes() const;
    // Host bytes of the TF-dependent structures (the kd-tree).
    std::vector<std::pair<std::string, uint64_t>> hostBytes() const;

    // Majorant per macrocell / traversal box as computed on the GPU (tests and statistics).
    std::vector<float> downloadGridMajorants() const;
    std::vector<float> downloadDomainMajorants() const;
    // grid-dda's block majorants (empty without blocks): the max over each block's macrocells.
    std::vector<float> downloadBlockMajorants() const;
    uint32_t blockCount() const { return mBlockCount; }
    uint32_t emptyBlocks() const { return mEmptyBlocks; }  // of majorant 0 under the last TF
    // Whether grid-dda crosses empty blocks in one step: Auto where at least
    // accel::kMinEmptyBlockFraction of them are empty under the TF (params().gridBlocks).
    enum class GridBlockUse { Auto, Always, Never };
    void setGridBlockUse(GridBlockUse use);
    bool gridBlocksUsed() const { return mParams.gridBlocks != 0; }
    // Overwrites the macrocell majorants, then the blocks' (grid-dda only; after a dispatch;
    // tests: deliberate overestimates).
    void overrideGridMajorants(const std::vector<float>& majorants);
    // The sub-majorants of the last TF (empty without them: plan().subMajorants off, or still
    // building in the background).
    const scene::SubMajorantGrid& subMajorants() const { return mSub; }
    // Where set, prepare() builds the sub-majorants on another thread and the pass renders with the
    // macrocell majorants alone until adoptSubMajorants() takes them: a TF edit in the viewer does
    // not wait for them. They change no expectation (delta tracking decides as without them), so
    // the accumulation goes on across the adoption. Off: prepare() builds them at once.
    void setSubMajorantsInBackground(bool on) { mSubInBackground = on; }
    // A finished background build: its buffers uploaded and params() pointing at them; true when
    // params() changed. waitForSubMajorants() waits for it first.
    bool adoptSubMajorants();
    bool waitForSubMajorants();
    // Stops a background build and waits for it (before the scene's structures change).
    void cancelSubMajorants();
    // Tests: look up every collision a sub-majorant decides too and count it as a violation where
    // the extinction exceeds the sub-majorant (MajorantsGpu::subMajorantCheck).
    void setSubMajorantCheck(bool on) { mParams.subMajorantCheck = on ? 1u : 0u; }
    // Overwrites every sub-box's q (0..255) of the last TF (tests: deliberate underestimates).
    void overrideSubMajorants(uint32_t q);

    // --control-extinction minorant: per macrocell the least TF alpha over its value range (less
    // kMinorantMargin of the greatest), made by every prepare() and dispatch() from now on, which the trackers take
    // as their control extinction (MajorantsGpu::gridMinorants). A minorant holds only where every
    // point of a macrocell has a value: on grid traversals (segments are macrocells) over data whose
    // leaf cells fill their bounds. Returns "" when they are made, else why not (one phrase); off
    // frees them.
    std::string setMinorants(bool on);
    bool minorantsOn() const { return mGridMinorants.valid() && mMinorantsOn; }
    std::vector<float> downloadGridMinorants() const;  // after a dispatch with minorants on

private:
    void buildKdTree(const scene::TransferFunction& tf);
    void buildSubMajorants(const scene::TransferFunction& tf);
    scene::SubMajorantOptions subMajorantOptions() const;
    void uploadSubMajorants(scene::SubMajorantGrid grid);
    void updateSwCulling();
    gpu::ComputePipeline structurePipeline(const std::string& name) const;
    double dispatchBlockMajorants(gpu::GpuTimer* timer);
    void countEmptyBlocks();
    void decideGridBlocks();
    const std::vector<accel::ValueRange>& domainRanges() const;

    gpu::Context& mCtx;
    const scene::VolumeScene& mScene;
    const DeviceScene& mDevice;
    const gpu::ShaderLibrary& mShaders;
    shared::MajorantsGpu mParams{};
    gpu::Buffer mTfPositions, mTfColors, mTfAlphaTree, mGridMajorants, mDomainMajorants;
    gpu::Buffer mKdBoxes, mKdRanges;               // kdtree traversal: the leaves of the TF's tree
    gpu::Buffer mDomainNodes, mDomainPrims;        // sw culling: BVH over the active boxes
    gpu::Buffer mDomainAabbs;                      // rq culling: BLAS input
    gpu::AabbAccelerationStructure mDomainAccel;
    gpu::ComputePipeline mMajorantPipeline, mAabbPipeline, mBlockPipeline;
    uint32_t mBlockCount = 0;      // grid-dda's blocks (majorants after the macrocells')
    uint32_t mEmptyBlocks = 0;     // of them, with majorant 0 under the last TF
    GridBlockUse mBlockUse = GridBlockUse::Auto;
    uint64_t mParamsAddress = 0;   // the RenderParams of the last dispatch
    // The adaptive --gpu-timeout of each shader (units: workgroups); the majorants' forgotten when
    // the TF's node count changes.
    GpuDeadline mMajorantDeadline, mAabbDeadline, mBlockDeadline;
    size_t mTfNodesMeasured = 0;
    std::optional<accel::KdTree> mKdTree;
    std::optional<accel::SubRangeMaker> mSubRanges;  // sub-majorants: the sub-boxes' ranges, from the brick grid
    scene::SubMajorantGrid mSub;
    gpu::Buffer mSubWords, mSubBytes;
    bool mMinorantsOn = false;
    gpu::Buffer mGridMinorants, mTfAlphaMinTree;  // --control-extinction minorant
    bool mSubInBackground = false;
    std::future<scene::SubMajorantGrid> mSubPending;  // a background build
    std::unique_ptr<std::atomic<bool>> mSubCancel = std::make_unique<std::atomic<bool>>(false);
    std::vector<shared::AabbGpu> mKdBoxesHost;     // local voxel space
    std::vector<uint8_t> mActive;                  // boxes whose range can reach alpha > 0
    std::vector<uint8_t> mBvhMask;                 // the boxes in the current sw BVH
    uint64_t mActiveBoxes = 0;
    double mGpuSeconds = 0, mHostSeconds = 0;
};

}  // namespace amrvk::render
