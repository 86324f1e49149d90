#include "render/device_scene.h"

#include "accel/dda.h"
#include "core/error.h"
#include "core/progress.h"

namespace amrvk::render {

using scene::Backend;
using scene::SamplerKind;
using scene::TraversalKind;

std::string traversalResourceName(TraversalKind traversal, const char* what) {
    return std::string(scene::traversalName(traversal)) + "Traversal" + what;
}

DeviceScene::DeviceScene(gpu::Context& ctx, const scene::VolumeScene& scene) : mVolume(scene.sharedVolume()) {
    const scene::StructurePlan& plan = scene.plan();
    const scene::Volume& v = scene.volume();
    AMRVK_CHECK(plan.backend == Backend::Sw || ctx.hasRayQuery(), "--backend rq: device '", ctx.deviceReport().name,
                "' has no VK_KHR_ray_query");
    // At 10^8 cells the copies take seconds: a stage line, ending with the device memory taken.
    const uint64_t deviceBytesBefore = ctx.memory().currentBytes();
    ProgressStage stage("uploading the structures to the device");
    mParams.boundsHi = glm::vec3(v.toLocal(glm::dvec3(v.bounds().upper)));
    mParams.invFinestCellWidth = float(1.0 / double(amr::cellWidth(v.minLevel())));
    if (plan.bricksOnDevice) {
        std::vector<shared::BrickGpu> bricks;
        bricks.reserve(v.bricks.bricks.size());
        for (const accel::Brick& b : v.bricks.bricks)
            bricks.push_back({v.toLocal(glm::i64vec3(b.lower)), b.level, b.size, uint32_t(b.begin)});
        mBricks = gpu::makeBuffer<shared::BrickGpu>(ctx, bricks, "bricks");
        mBrickValues = gpu::shareOrCopyBuffer<float>(ctx, v.brickValues(), "brickValues");  // 4 B a cell
        mParams.bricks = mBricks.address();
        mParams.brickValues = mBrickValues.address();
    }
    const std::string sampler = plan.lookup == scene::Lookup::AbrBvh ? "abrSampler" : "brickDomainSampler";
    if (plan.denseGrid) {
        AMRVK_CHECK(scene.dense.has_value(), "internal: dense sampler without a dense grid");
        const accel::DenseGrid& d = *scene.dense;
        mDenseValues = gpu::makeBuffer<float>(ctx, d.values, "denseGrid");
        mParams.denseValues = mDenseValues.address();
        mParams.denseDims = d.dims;
        mParams.denseLevel = d.level;
        mParams.denseOrigin = glm::vec3(v.toLocal(glm::dvec3(d.origin)));
        mParams.denseSpacing = float(amr::cellWidth(d.level));
    }
    if (plan.lookup == scene::Lookup::BrickGrid) {
        AMRVK_CHECK(scene.brickGrid.has_value(), "internal: grid sampler without a brick grid");
        const accel::BrickGrid& g = *scene.brickGrid;
        mGridBrickLists = gpu::makeBuffer<uint32_t>(ctx, g.lists, "gridSamplerBrickLists");
        mParams.gridBrickLists = mGridBrickLists.address();
        mParams.gridDims = g.dims;  // the layout of the range grid too, when there is one
        mParams.gridOrigin = glm::vec3(v.toLocal(g.origin));
        mParams.gridCellSize = glm::vec3(g.cellSize);
    }
    if (plan.samplerBvh) {
        mSamplerNodes = gpu::makeBuffer<shared::BvhNodeGpu>(ctx, scene.samplerBvh.nodes, sampler + "Bvh");
        mSamplerPrims = gpu::makeBuffer<uint32_t>(ctx, scene.samplerBvh.primIds, sampler + "BvhPrims");
        mParams.samplerNodes = mSamplerNodes.address();
        mParams.samplerPrims = mSamplerPrims.address();
    }
    if (plan.samplerBoxes) {
        const auto& boxes = scene.samplerBoxes;
        mSamplerAabbs = gpu::makeBuffer<shared::AabbGpu>(ctx, boxes, sampler + "Aabbs", kAsInput);
        mSamplerAccel = gpu::AabbAccelerationStructure(ctx, uint32_t(boxes.size()), sampler + "Accel");
        ctx.submitAndWait([&](VkCommandBuffer cmd) { mSamplerAccel.build(cmd, mSamplerAabbs); });
        mParams.samplerAccel = mSamplerAccel.tlasAddress();
    }
    if (plan.abrs) {
        std::vector<shared::AbrGpu> abrs;
        abrs.reserve(scene.abrs->abrs.size());
        for (const accel::Abr& a : scene.abrs->abrs) {
            const shared::AabbGpu box = v.toLocal({a.box.lower(), a.box.upper()});
            abrs.push_back({box.lo, a.brickBegin, box.hi, a.brickCount});
        }
        mAbrs = gpu::makeBuffer<shared::AbrGpu>(ctx, abrs, "abrs");
        mAbrBrickList = gpu::makeBuffer<uint32_t>(ctx, scene.abrs->brickList, "abrBrickLists");
        mParams.abrs = mAbrs.address();
        mParams.abrBrickList = mAbrBrickList.address();
    }
    if (plan.macrocellRanges) {
        mGridRanges = gpu::makeBuffer<accel::ValueRange>(ctx, scene.grid->ranges, "macrocellRanges");
        mParams.gridDims = scene.grid->dims;
        mParams.gridOrigin = glm::vec3(v.toLocal(scene.grid->origin));
        mParams.gridCellSize = glm::vec3(scene.grid->cellSize);
        mParams.gridRanges = mGridRanges.address();
        if (plan.traversal == TraversalKind::GridDda) mParams.gridBlockShift = uint32_t(accel::ddaBlockShift(scene.grid->dims));
        if (plan.traversal == TraversalKind::GridBvh) mParams.gridBvhQueryAfter = accel::kGridBvhQueryAfter;
    }
    if (plan.staticBoxes) {
        const TraversalKind t = plan.traversal;
        mDomainBoxes = gpu::makeBuffer<shared::AabbGpu>(ctx, scene.domains.boxes, traversalResourceName(t, "Boxes"));
        mDomainRanges = gpu::makeBuffer<accel::ValueRange>(ctx, scene.domains.ranges, traversalResourceName(t, "Ranges"));
    }
    stage.setResult(formatBytes(ctx.memory().currentBytes() - deviceBytesBefore) + " of device memory");
}

}  // namespace amrvk::render
