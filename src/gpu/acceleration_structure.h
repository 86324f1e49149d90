#pragma once
// Hardware acceleration structures over axis-aligned boxes for VK_KHR_ray_query, reached from
// compute shaders by device address (accelerationStructureEXT(uint64_t) in GLSL, no descriptor).
//  - One bottom-level structure over `count` AABBs (one geometry, primitive index = AABB index)
//    and one top-level structure with a single identity instance (mask 0xFF, custom index 0).
//  - The geometry is not opaque: every AABB the traversal does not cull is returned to the shader
//    as a gl_RayQueryCandidateIntersectionAABBEXT candidate; the shader decides (generate or skip).
//    Vulkan allows an implementation to report the same AABB more than once per query.
//  - An AABB whose minX is NaN is inactive (Vulkan rule) and is never reported: callers cull boxes
//    by rewriting their data and calling build() again, without renumbering. Driver bug: lavapipe
//    of Mesa 25.0.7 then loses active boxes too (NaN leaks into BVH node bounds); there, cull with
//    a zero-width box (minX == maxX) and skip boxes with !(minX < maxX) in the shader instead.
//  - Point queries: origin p, any direction, tMin 0, tMax > 0 (e.g. 1e-30) yields every box whose
//    closed bounds contain p; with tMax == 0 lavapipe misses many boxes that p lies on the face of.
//  - Memory (device bytes) is counted in ctx.memory() as name + ".blas", ".tlas", ".scratch",
//    ".instances".
#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>

#include "gpu/buffer.h"
#include "gpu/context.h"

namespace amrvk::gpu {

// The most boxes one AABB acceleration structure may hold on ctx's device (its
// maxPrimitiveCount); 0 without ray queries. Checked before anything is built for --backend rq.
uint64_t maxAccelerationPrimitives(const Context& ctx);

class AabbAccelerationStructure {
public:
    AabbAccelerationStructure() = default;
    // Sizes everything for `count` AABBs; nothing is built yet. Requires ctx.hasRayQuery().
    // count == 0 gives a valid empty structure: a top-level structure with no instance, which
    // shaders may trace (no candidate is ever reported).
    AabbAccelerationStructure(Context& ctx, uint32_t count, std::string name);
    ~AabbAccelerationStructure();
    AabbAccelerationStructure(AabbAccelerationStructure&& other) noexcept;
    AabbAccelerationStructure& operator=(AabbAccelerationStructure&& other) noexcept;
    AabbAccelerationStructure(const AabbAccelerationStructure&) = delete;
    AabbAccelerationStructure& operator=(const AabbAccelerationStructure&) = delete;

    // Records a full build of the bottom- then the top-level structure into `cmd`, with barriers:
    // prior transfer/compute writes (the AABBs) and prior ray queries -> build; bottom -> top;
    // top -> later compute-shader ray queries. May be recorded again after the AABBs change.
    // aabbBuffer: count VkAabbPositionsKHR (6 floats, 24 bytes each) from offset 0, created with
    // VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR; unused when count == 0.
    void build(VkCommandBuffer cmd, const Buffer& aabbBuffer);

    // Device address of the top-level structure (0 when !valid()).
    uint64_t tlasAddress() const { return mTlasAddress; }
    // Device bytes of BLAS + TLAS + scratch + instance buffers, as counted in ctx.memory().
    uint64_t memoryBytes() const;
    uint32_t count() const { return mCount; }
    bool valid() const { return mTlas != VK_NULL_HANDLE; }

private:
    struct Functions {
        PFN_vkCreateAccelerationStructureKHR create = nullptr;
        PFN_vkDestroyAccelerationStructureKHR destroy = nullptr;
        PFN_vkGetAccelerationStructureBuildSizesKHR buildSizes = nullptr;
        PFN_vkGetAccelerationStructureDeviceAddressKHR address = nullptr;
        PFN_vkCmdBuildAccelerationStructuresKHR cmdBuild = nullptr;
    };
    void release();

    Context* mCtx = nullptr;
    Functions mFn;
    uint32_t mCount = 0;
    std::string mName;
    VkAccelerationStructureKHR mBlas = VK_NULL_HANDLE;  // none when mCount == 0
    VkAccelerationStructureKHR mTlas = VK_NULL_HANDLE;
    Buffer mBlasBuffer, mTlasBuffer, mScratch, mInstances;
    VkDeviceAddress mScratchAddress = 0;  // mScratch's address rounded up to the scratch alignment
    VkDeviceAddress mTlasAddress = 0;
};

}  // namespace amrvk::gpu
