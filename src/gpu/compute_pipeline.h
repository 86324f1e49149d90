#pragma once
// A compute pipeline whose only interface is a push-constant block (buffers are reached by
// device address) plus specialization constants chosen at creation time.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

#include "gpu/context.h"

namespace amrvk::gpu {

struct SpecConstant {
    uint32_t id;
    uint32_t value;  // bit pattern: uint, int or float
};

class ComputePipeline {
public:
    ComputePipeline() = default;
    ComputePipeline(Context& ctx, const std::vector<uint32_t>& spirv, std::string name,
                    uint32_t pushConstantBytes, const std::vector<SpecConstant>& specialization = {});
    ~ComputePipeline();
    ComputePipeline(ComputePipeline&& o) noexcept;
    ComputePipeline& operator=(ComputePipeline&& o) noexcept;
    ComputePipeline(const ComputePipeline&) = delete;
    ComputePipeline& operator=(const ComputePipeline&) = delete;

    const std::string& name() const { return mName; }
    bool valid() const { return mPipeline != VK_NULL_HANDLE; }
    // Binds, pushes `push` (exactly pushConstantBytes) and dispatches the given workgroups.
    void dispatch(VkCommandBuffer cmd, const void* push, uint32_t groupsX, uint32_t groupsY = 1,
                  uint32_t groupsZ = 1) const;
    // The same for workgroups [firstX, firstX + groupsX) of a 1-D dispatch: gl_WorkGroupID and
    // gl_GlobalInvocationID count from firstX, so parts of one dispatch run as it would (every
    // pipeline is created with VK_PIPELINE_CREATE_DISPATCH_BASE_BIT; gpu/paced_submit.h).
    void dispatchPart(VkCommandBuffer cmd, const void* push, uint32_t firstX, uint32_t groupsX) const;

private:
    void release();
    Context* mCtx = nullptr;
    VkShaderModule mModule = VK_NULL_HANDLE;
    VkPipelineLayout mLayout = VK_NULL_HANDLE;
    VkPipeline mPipeline = VK_NULL_HANDLE;
    uint32_t mPushBytes = 0;
    std::string mName;
};

// A memory barrier on the whole device memory from (srcStage, srcAccess) to (dstStage, dstAccess).
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);
// A compute-to-compute (and compute-to-transfer) memory barrier on the whole device memory.
void computeBarrier(VkCommandBuffer cmd);

// One side of an image barrier: the stages and accesses before or after it, and the layout.
struct ImageUse {
    VkPipelineStageFlags2 stage;
    VkAccessFlags2 access;
    VkImageLayout layout;
};
// A layout transition of a single-level colour image (e.g. a swapchain image) from one use to the next.
void imageBarrier(VkCommandBuffer cmd, VkImage image, const ImageUse& from, const ImageUse& to);
// The copy region of a whole single-level colour image, tightly packed rows.
VkBufferImageCopy wholeImageCopy(VkExtent2D extent);

// GPU timestamps around scopes: begin(cmd) ... end(cmd, scope); seconds() after the submit.
class GpuTimer {
public:
    GpuTimer(Context& ctx, uint32_t maxScopes = 256);
    ~GpuTimer();
    GpuTimer(const GpuTimer&) = delete;
    GpuTimer& operator=(const GpuTimer&) = delete;
    void reset(VkCommandBuffer cmd);
    uint32_t begin(VkCommandBuffer cmd);
    void end(VkCommandBuffer cmd, uint32_t scope);
    // Sum of the seconds of every scope since the last reset; call after the submit completed.
    double seconds() const;

private:
    Context& mCtx;
    VkQueryPool mPool = VK_NULL_HANDLE;
    uint32_t mMax;
    uint32_t mScopes = 0;  // begun since the last reset
};

}  // namespace amrvk::gpu
