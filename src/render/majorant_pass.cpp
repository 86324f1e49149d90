#include "render/majorant_pass.h"

#include <algorithm>

#include "accel/dda.h"
#include "core/error.h"
#include "core/stats.h"
#include "gpu/paced_submit.h"
#include "gpu/shader_library.h"

namespace amrvk::render {

using scene::Backend;
using scene::TraversalKind;

namespace {
gpu::Buffer floatBuffer(gpu::Context& ctx, uint64_t count, const std::string& name) {
    return gpu::Buffer(ctx, std::max<uint64_t>(16, count * sizeof(float)), gpu::MemoryKind::Device, name);
}
}  // namespace

MajorantPass::MajorantPass(gpu::Context& ctx, const scene::VolumeScene& scene, const DeviceScene& device,
                           const gpu::ShaderLibrary& shaders)
    : mCtx(ctx), mScene(scene), mDevice(device), mShaders(shaders) {
    const scene::StructurePlan& plan = scene.plan();
    const TraversalKind t = plan.traversal;
    if (plan.macrocellRanges) {
        const shared::SceneGpu& sp = device.params();
        const glm::ivec3 blocks = accel::ddaBlockDims({.dims = sp.gridDims}, int(sp.gridBlockShift));
        mBlockCount = sp.gridBlockShift > 0 ? uint32_t(blocks.x * blocks.y * blocks.z) : 0;
        // grid-dda's block majorants follow the macrocells' in the same buffer.
        mGridMajorants = floatBuffer(ctx, scene.grid->ranges.size() + mBlockCount, "macrocellMajorants");
        mParams.gridMajorants = mGridMajorants.address();
    }
    if (plan.traversalBoxes == scene::BoxSet::Macrocells) {  // the macrocells' own majorants
        mParams.domainCount = uint32_t(scene.grid->ranges.size());
        mParams.domainRanges = device.gridRanges().address();
        mParams.domainMajorants = mGridMajorants.address();
    } else if (plan.staticBoxes) {
        mParams.domainCount = uint32_t(scene.domains.boxes.size());
        mParams.domainBoxes = device.domainBoxes().address();
        mParams.domainRanges = device.domainRanges().address();
        mDomainMajorants = floatBuffer(ctx, mParams.domainCount, traversalResourceName(t, "Majorants"));
        mParams.domainMajorants = mDomainMajorants.address();
    }
    if (plan.subMajorants) {
        AMRVK_CHECK(scene.brickGrid.has_value(), "internal: sub-majorants without the brick grid");
        mSubRanges.emplace(*scene.brickGrid, scene.volume().bricks, scene.volume().brickValues());
    }
    if (plan.rayQueryCulling && !plan.boxesPerTf) {  // kdtree: made with its boxes, per TF
        mDomainAabbs = gpu::Buffer(ctx, std::max<uint64_t>(24, uint64_t(mParams.domainCount) * sizeof(shared::AabbGpu)),
                                   gpu::MemoryKind::Device, traversalResourceName(t, "Aabbs"), kAsInput);
        mDomainAccel = gpu::AabbAccelerationStructure(ctx, mParams.domainCount, traversalResourceName(t, "Accel"));
        mParams.domainAccel = mDomainAccel.tlasAddress();
    }
}

const std::vector<accel::ValueRange>& MajorantPass::domainRanges() const {
    switch (mScene.plan().traversalBoxes) {
        case scene::BoxSet::Macrocells: return mScene.grid->ranges;
        case scene::BoxSet::KdLeaves: return mKdTree->leafRanges;
        default: return mScene.domains.ranges;
    }
}

void MajorantPass::buildKdTree(const scene::TransferFunction& tf) {
    mKdTree = mScene.kdTreeFor(tf);
    mKdBoxesHost.clear();
    mKdBoxesHost.reserve(mKdTree->leaves.size());
    for (const accel::BoxD& b : mKdTree->leaves) mKdBoxesHost.push_back(mScene.volume().toLocal(b));
    const TraversalKind t = TraversalKind::KdTree;
    const uint32_t count = uint32_t(mKdBoxesHost.size());
    mKdBoxes = gpu::Buffer();
    mKdRanges = gpu::Buffer();
    mDomainMajorants = gpu::Buffer();
    mKdBoxes = gpu::makeBuffer<shared::AabbGpu>(mCtx, mKdBoxesHost, traversalResourceName(t, "Boxes"));
    mKdRanges = gpu::makeBuffer<accel::ValueRange>(mCtx, mKdTree->leafRanges, traversalResourceName(t, "Ranges"));
    mDomainMajorants = floatBuffer(mCtx, count, traversalResourceName(t, "Majorants"));
    mParams.domainCount = count;
    mParams.domainBoxes = mKdBoxes.address();
    mParams.domainRanges = mKdRanges.address();
    mParams.domainMajorants = mDomainMajorants.address();
    if (mScene.plan().rayQueryCulling) {
        mDomainAccel = {};
        mDomainAabbs = gpu::Buffer();
        mDomainAabbs = gpu::Buffer(mCtx, std::max<uint64_t>(24, uint64_t(count) * sizeof(shared::AabbGpu)),
                                   gpu::MemoryKind::Device, traversalResourceName(t, "Aabbs"), kAsInput);
        mDomainAccel = gpu::AabbAccelerationStructure(mCtx, count, traversalResourceName(t, "Accel"));
        mParams.domainAccel = mDomainAccel.tlasAddress();
    }
    mBvhMask.clear();  // new boxes: the culling BVH must be rebuilt
}

MajorantPass::~MajorantPass() { cancelSubMajorants(); }

scene::SubMajorantOptions MajorantPass::subMajorantOptions() const {
    const accel::RangeGrid& grid = *mScene.grid;
    return {.maxDivision = int(mScene.config().subMajorants),
            .cancel = mSubCancel.get(),
            .budgetBytes = scene::kDefaultSubMajorantBudget,
            .chordInFinestCells = scene::chordOf(grid, double(amr::cellWidth(mScene.volume().minLevel())))};
}

// The loose macrocells' sub-boxes under `tf` (scene/sub_majorants.h): at once, or on another
// thread (setSubMajorantsInBackground) with the macrocell majorants alone until adopted.
void MajorantPass::buildSubMajorants(const scene::TransferFunction& tf) {
    cancelSubMajorants();
    uploadSubMajorants({});
    if (!mSubInBackground) {
        uploadSubMajorants(scene::buildSubMajorants(*mScene.grid, *mSubRanges, tf, subMajorantOptions()));
        return;
    }
    // The build reads the scene's grid and brick lists, which stay until the scene is configured
    // again: Renderer::setStructure cancels it first.
    mSubPending = std::async(std::launch::async, [this, tf, options = subMajorantOptions()] {
        return scene::buildSubMajorants(*mScene.grid, *mSubRanges, tf, options);
    });
}

void MajorantPass::uploadSubMajorants(scene::SubMajorantGrid grid) {
    mSub = std::move(grid);
    mSubWords = gpu::Buffer();
    mSubBytes = gpu::Buffer();
    mParams.subMajorantsOn = mSub.refined > 0 ? 1u : 0u;
    mParams.subRefinement = mParams.subMajorants = 0;
    if (mSub.refined == 0) return;
    mSubWords = gpu::makeBuffer<uint32_t>(mCtx, mSub.words, "subMajorantWords");
    mSubBytes = gpu::makeBuffer<uint32_t>(mCtx, mSub.bytes, "subMajorants");
    mParams.subRefinement = mSubWords.address();
    mParams.subMajorants = mSubBytes.address();
}

bool MajorantPass::adoptSubMajorants() {
    if (!mSubPending.valid() || mSubPending.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return false;
    scene::SubMajorantGrid grid = mSubPending.get();
    if (grid.cancelled) return false;
    uploadSubMajorants(std::move(grid));
    return mSub.refined > 0;
}

bool MajorantPass::waitForSubMajorants() {
    if (mSubPending.valid()) mSubPending.wait();
    return adoptSubMajorants();
}

void MajorantPass::cancelSubMajorants() {
    if (!mSubPending.valid()) return;
    mSubCancel->store(true);
    mSubPending.wait();
    mSubPending = {};
    mSubCancel->store(false);
}

void MajorantPass::overrideSubMajorants(uint32_t q) {
    AMRVK_CHECK(mSub.refined > 0, "overrideSubMajorants: no sub-majorants under the last TF");
    const uint32_t b = std::min(q, 255u);
    std::vector<uint32_t> bytes(mSub.bytes.size(), b | b << 8 | b << 16 | b << 24);
    mSubBytes.upload(bytes.data(), bytes.size() * sizeof(uint32_t));
}

const std::vector<shared::AabbGpu>& MajorantPass::traversalBoxes() const {
    return mScene.plan().boxesPerTf ? mKdBoxesHost : mScene.domains.boxes;
}

// sw back-end: a BVH over the active boxes, rebuilt only when that set changes.
void MajorantPass::updateSwCulling() {
    if (mActive == mBvhMask && mDomainNodes.valid()) return;
    mBvhMask = mActive;
    std::vector<accel::BoxD> boxes;
    std::vector<uint32_t> ids;
    const TraversalKind t = mScene.plan().traversal;
    const std::vector<shared::AabbGpu>& domainBoxes = traversalBoxes();
    for (uint32_t i = 0; i < mActive.size(); ++i) {
        if (!mActive[i]) continue;
        ids.push_back(i);
        if (mScene.plan().traversalBoxes == scene::BoxSet::Macrocells) {
            // The shader computes macrocell faces in float; pad the double box so nodes stay conservative.
            const accel::RangeGrid& g = *mScene.grid;
            const glm::ivec3 c(int(i % uint32_t(g.dims.x)), int((i / uint32_t(g.dims.x)) % uint32_t(g.dims.y)),
                               int(i / uint32_t(g.dims.x * g.dims.y)));
            const glm::dvec3 o = mScene.volume().toLocal(g.origin);
            const glm::dvec3 lo = o + glm::dvec3(c) * g.cellSize, hi = o + glm::dvec3(c + 1) * g.cellSize;
            const glm::dvec3 pad = 1e-5 * (glm::abs(lo) + glm::abs(hi) + 1.0);
            boxes.push_back({lo - pad, hi + pad});
        } else {
            const shared::AabbGpu& b = domainBoxes[i];
            boxes.push_back({glm::dvec3(b.lo), glm::dvec3(b.hi)});
        }
    }
    mDomainNodes = gpu::Buffer();
    mDomainPrims = gpu::Buffer();
    accel::Bvh bvh = boxes.empty() ? accel::Bvh{} : accel::buildBvh(boxes);
    for (uint32_t& p : bvh.primIds) p = ids[p];
    mDomainNodes = gpu::makeBuffer<shared::BvhNodeGpu>(mCtx, bvh.nodes, traversalResourceName(t, "Bvh"));
    mDomainPrims = gpu::makeBuffer<uint32_t>(mCtx, bvh.primIds, traversalResourceName(t, "BvhPrims"));
    mParams.domainNodes = mDomainNodes.address();
    mParams.domainPrims = mDomainPrims.address();
}

void MajorantPass::prepare(const scene::TransferFunction& tf) {
    const auto& positions = tf.positions();
    const auto& colors = tf.colors();
    AMRVK_CHECK(!positions.empty() && positions.size() == colors.size(), "transfer function has no nodes");
    Timer host;
    const scene::StructurePlan& plan = mScene.plan();
    // The majorants' work per box grows with the TF's nodes (tfMaxAlpha walks its alpha tree).
    if (positions.size() != mTfNodesMeasured) mMajorantDeadline.reset();
    mTfNodesMeasured = positions.size();
    mTfPositions = gpu::makeBuffer<float>(mCtx, positions, "tfPositions");
    mTfColors = gpu::makeBuffer<glm::vec4>(mCtx, colors, "tfColors");
    mTfAlphaTree = gpu::makeBuffer<float>(mCtx, tf.alphaTree(), "tfAlphaTree");
    if (mMinorantsOn) {
        mTfAlphaMinTree = gpu::makeBuffer<float>(mCtx, tf.alphaMinTree(), "tfAlphaMinTree");
        mParams.tfAlphaMinTree = mTfAlphaMinTree.address();
    }
    mParams.tfPositions = mTfPositions.address();
    mParams.tfColors = mTfColors.address();
    mParams.tfAlphaTree = mTfAlphaTree.address();
    mParams.tfNodeCount = uint32_t(positions.size());
    if (plan.boxesPerTf) buildKdTree(tf);
    if (plan.subMajorants) buildSubMajorants(tf);
    if (plan.boxMajorants) {
        // The host holds every value range: the boxes that can have a majorant > 0 are known
        // without reading the GPU's majorants back.
        const std::vector<accel::ValueRange>& ranges = domainRanges();
        mActive.assign(ranges.size(), 0);
        for (size_t i = 0; i < ranges.size(); ++i) mActive[i] = tf.maxAlpha(ranges[i].lo, ranges[i].hi) > 0.0f;
        mActiveBoxes = uint64_t(std::count(mActive.begin(), mActive.end(), uint8_t(1)));
        mParams.domainAnyActive = mActiveBoxes > 0 ? 1u : 0u;
        if (!plan.rayQueryCulling) updateSwCulling();
    }
    mHostSeconds = host.seconds();
}

// One of the pass's shaders (push constants: shared::StructurePush), named with where it came from.
gpu::ComputePipeline MajorantPass::structurePipeline(const std::string& name) const {
    return gpu::ComputePipeline(mCtx, mShaders.load(name), name + mShaders.origin(), sizeof(shared::StructurePush));
}

void MajorantPass::dispatch(uint64_t paramsAddress) {
    const scene::StructurePlan& plan = mScene.plan();
    if (!mMajorantPipeline.valid()) {
        mMajorantPipeline = structurePipeline("majorants");
        mMajorantDeadline.reset();
    }
    const bool rq = plan.rayQueryCulling;
    if (rq && !mAabbPipeline.valid()) {
        mAabbPipeline = structurePipeline("domain_aabbs");
        mAabbDeadline.reset();
    }
    const uint32_t boxCount = plan.boxMajorants ? mParams.domainCount : 0;
    gpu::GpuTimer timer(mCtx, 4);
    mGpuSeconds = 0;
    // One dispatch space of workgroups: the macrocells' majorants, then the traversal boxes' own.
    const uint32_t gridCount = mScene.grid ? uint32_t(mScene.grid->ranges.size()) : 0;
    const uint32_t boxesOwn = mDomainMajorants.valid() ? boxCount : 0;
    const uint32_t gridGroups = (gridCount + 63) / 64, boxGroups = (boxesOwn + 63) / 64;
    const shared::StructurePush gridPush{paramsAddress, mDevice.gridRanges().address(), mGridMajorants.address(),
                                         gridCount, 0, mMinorantsOn ? mGridMinorants.address() : 0};
    const shared::StructurePush boxPush{paramsAddress, mParams.domainRanges, mDomainMajorants.address(), boxesOwn, 0, 0};
    if (gridGroups + boxGroups > 0)
        mGpuSeconds += gpu::submitPaced(mCtx, mMajorantDeadline,
                                        {.groups = uint64_t(gridGroups) + boxGroups,
                                         .record = [&](VkCommandBuffer cmd, uint32_t first, uint32_t count, bool) {
                                             const uint32_t end = first + count;
                                             if (first < gridGroups)
                                                 mMajorantPipeline.dispatchPart(cmd, &gridPush, first,
                                                                                std::min(end, gridGroups) - first);
                                             if (end > gridGroups) {
                                                 const uint32_t lo = std::max(first, gridGroups) - gridGroups;
                                                 mMajorantPipeline.dispatchPart(cmd, &boxPush, lo, end - gridGroups - lo);
                                             }
                                             gpu::computeBarrier(cmd);
                                         },
                                         .what = mMajorantPipeline.name(),
                                         .timer = &timer})
                           .gpuSeconds;
    mParamsAddress = paramsAddress;
    if (mBlockCount > 0) {
        mGpuSeconds += dispatchBlockMajorants(&timer);
        countEmptyBlocks();
    }
    if (!rq || boxCount == 0) return;
    // Ray-query culling: the BLAS input (a shader, paced like the majorants), then the BLAS build
    // (the driver's work, no --shader-dir code: the default limit).
    const shared::StructurePush aabbPush{paramsAddress, mParams.domainMajorants, mDomainAabbs.address(), boxCount,
                                         uint32_t(plan.traversal), 0};
    mGpuSeconds += gpu::submitPaced(mCtx, mAabbDeadline,
                                    {.groups = (uint64_t(boxCount) + 63) / 64,
                                     .record = [&](VkCommandBuffer cmd, uint32_t first, uint32_t count, bool) {
                                         mAabbPipeline.dispatchPart(cmd, &aabbPush, first, count);
                                         gpu::computeBarrier(cmd);
                                     },
                                     .what = mAabbPipeline.name(),
                                     .timer = &timer})
                       .gpuSeconds;
    mCtx.submitAndWait(
        [&](VkCommandBuffer cmd) {
            timer.reset(cmd);
            const uint32_t scope = timer.begin(cmd);
            mDomainAccel.build(cmd, mDomainAabbs);
            timer.end(cmd, scope);
            gpu::computeBarrier(cmd);
        },
        "the culling BLAS build of " + std::to_string(boxCount) + " boxes");
    mGpuSeconds += timer.seconds();
}

// grid-dda's blocks: the max of each block's macrocell majorants, after the majorants themselves.
double MajorantPass::dispatchBlockMajorants(gpu::GpuTimer* timer) {
    if (!mBlockPipeline.valid()) {
        mBlockPipeline = structurePipeline("block_majorants");
        mBlockDeadline.reset();
    }
    const uint64_t cells = mScene.grid->ranges.size();
    const shared::StructurePush push{mParamsAddress, mGridMajorants.address(),
                                     mGridMajorants.address() + cells * sizeof(float), mBlockCount, 0, 0};
    return gpu::submitPaced(mCtx, mBlockDeadline,
                            {.groups = (uint64_t(mBlockCount) + 63) / 64,
                             .record = [&](VkCommandBuffer cmd, uint32_t first, uint32_t count, bool) {
                                 mBlockPipeline.dispatchPart(cmd, &push, first, count);
                                 gpu::computeBarrier(cmd);
                             },
                             .what = mBlockPipeline.name(),
                             .timer = timer})
        .gpuSeconds;
}

// Whether grid-dda crosses empty blocks under this TF (MajorantsGpu::gridBlocks): from the
// blocks' majorants, read back (one float a block: 16 KiB for a grid of 128^3).
void MajorantPass::countEmptyBlocks() {
    const std::vector<float> blocks = downloadBlockMajorants();
    mEmptyBlocks = uint32_t(std::count(blocks.begin(), blocks.end(), 0.0f));
    decideGridBlocks();
}

void MajorantPass::decideGridBlocks() {
    const bool pays = double(mEmptyBlocks) >= accel::kMinEmptyBlockFraction * double(mBlockCount);
    mParams.gridBlocks = mBlockCount > 0 && (mBlockUse == GridBlockUse::Always || (mBlockUse == GridBlockUse::Auto && pays))
                             ? 1u
                             : 0u;
}

void MajorantPass::setGridBlockUse(GridBlockUse use) {
    mBlockUse = use;
    decideGridBlocks();
}

std::vector<std::pair<std::string, uint64_t>> MajorantPass::hostBytes() const {
    std::vector<std::pair<std::string, uint64_t>> out;
    if (mKdTree) out.emplace_back("kdTree", mKdTree->memoryBytes());
    if (mSub.refined > 0) out.emplace_back("subMajorants", mSub.memoryBytes());
    return out;
}

std::vector<float> MajorantPass::downloadGridMajorants() const {
    AMRVK_CHECK(mGridMajorants.valid(), "downloadGridMajorants: no macrocell grid in this configuration");
    std::vector<float> out(mScene.grid->ranges.size());
    mGridMajorants.download(out.data(), out.size() * sizeof(float));
    return out;
}

std::string MajorantPass::setMinorants(bool on) {
    mMinorantsOn = false;
    mGridMinorants = gpu::Buffer();
    mTfAlphaMinTree = gpu::Buffer();
    mParams.gridMinorants = mParams.tfAlphaMinTree = 0;
    if (!on) return "";
    const TraversalKind t = mScene.plan().traversal;
    if (!mScene.grid || (t != TraversalKind::GridDda && t != TraversalKind::GridBvh))
        return std::string("the traversal is ") + scene::traversalName(t) + " (minorants need grid-dda or grid-bvh)";
    // A point with no cell has no extinction: a minorant > 0 would be wrong there. Leaf cells do not
    // overlap (amr::validateCells), so they fill their bounds exactly when their volumes add up to it.
    const amr::ModelSummary& m = mScene.volume().summary;
    if (m.leafVolume != m.bounds.volume())
        return "the leaf cells do not fill their bounds (a minorant needs a value everywhere)";
    mGridMinorants = floatBuffer(mCtx, mScene.grid->ranges.size(), "macrocellMinorants");
    mParams.gridMinorants = mGridMinorants.address();
    mMinorantsOn = true;
    return "";
}

std::vector<float> MajorantPass::downloadGridMinorants() const {
    AMRVK_CHECK(minorantsOn(), "downloadGridMinorants: minorants are off");
    std::vector<float> out(mScene.grid->ranges.size());
    mGridMinorants.download(out.data(), out.size() * sizeof(float));
    return out;
}

std::vector<float> MajorantPass::downloadBlockMajorants() const {
    std::vector<float> out(mBlockCount);
    if (mBlockCount > 0)
        mGridMajorants.download(out.data(), out.size() * sizeof(float), mScene.grid->ranges.size() * sizeof(float));
    return out;
}

std::vector<float> MajorantPass::downloadDomainMajorants() const {
    AMRVK_CHECK(mDomainMajorants.valid(), "downloadDomainMajorants: no traversal boxes in this configuration");
    std::vector<float> out(mParams.domainCount);
    if (!out.empty()) mDomainMajorants.download(out.data(), out.size() * sizeof(float));
    return out;
}

void MajorantPass::overrideGridMajorants(const std::vector<float>& majorants) {
    AMRVK_CHECK(mScene.grid && mScene.plan().traversal == TraversalKind::GridDda,
                "overrideMajorants: grid-dda traversal only");
    AMRVK_CHECK(majorants.size() == mScene.grid->ranges.size(), "overrideMajorants: ", majorants.size(),
                " values for ", mScene.grid->ranges.size(), " macrocells");
    mGridMajorants.upload(majorants.data(), majorants.size() * sizeof(float));
    if (mBlockCount > 0) {
        AMRVK_CHECK(mParamsAddress != 0, "overrideMajorants: dispatch() must run first");
        gpu::GpuTimer timer(mCtx, 2);
        dispatchBlockMajorants(&timer);
        countEmptyBlocks();
    }
}

}  // namespace amrvk::render
