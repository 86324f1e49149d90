#pragma once
// The device copy of one VolumeScene configuration, and only of what it uses: bricks and values
// (AMR samplers), the sampler's hierarchy (sw: BVH nodes and primitive ids; rq: AABBs and a
// BLAS/TLAS), ABRs, macrocell value ranges (grid traversals), the dense samples (dense sampler),
// and the TF-independent traversal boxes with their value ranges (abr, brick, ext-brick; the
// kdtree's boxes depend on the TF and belong to the MajorantPass). Built once per structure
// combination; a TF edit never touches it. Fills shared::SceneGpu. Local voxel space throughout
// (every coordinate goes through VolumeScene::toLocal).
#include <cstdint>
#include <memory>

#include "gpu/acceleration_structure.h"
#include "gpu/buffer.h"
#include "gpu/context.h"
#include "scene/volume_scene.h"
#include "shared/render_params.h"

namespace amrvk::render {

class DeviceScene {
public:
    DeviceScene(gpu::Context& ctx, const scene::VolumeScene& scene);

    const shared::SceneGpu& params() const { return mParams; }
    // Macrocell value ranges (grid traversals), else invalid.
    const gpu::Buffer& gridRanges() const { return mGridRanges; }
    // Traversal boxes and their ranges of abr | brick | ext-brick, else invalid.
    const gpu::Buffer& domainBoxes() const { return mDomainBoxes; }
    const gpu::Buffer& domainRanges() const { return mDomainRanges; }

private:
    // The volume whose values a CPU device reads where they lie (gpu::shareOrCopyBuffer): declared
    // before the buffers, so that it outlives them.
    std::shared_ptr<const scene::Volume> mVolume;
    shared::SceneGpu mParams{};
    gpu::Buffer mBricks, mBrickValues, mSamplerNodes, mSamplerPrims, mSamplerAabbs, mAbrs, mAbrBrickList;
    gpu::Buffer mGridRanges, mDenseValues, mGridBrickLists, mDomainBoxes, mDomainRanges;
    gpu::AabbAccelerationStructure mSamplerAccel;
};

// "<traversal>Traversal<what>": the name of a traversal buffer in the device-memory report.
std::string traversalResourceName(scene::TraversalKind traversal, const char* what);

// Usage of buffers that feed an acceleration-structure build (AABBs).
inline constexpr VkBufferUsageFlags kAsInput = VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR;

}  // namespace amrvk::render
