#include "gpu/compute_pipeline.h"

#include <utility>

#include "gpu/vk_check.h"

namespace amrvk::gpu {

ComputePipeline::ComputePipeline(Context& ctx, const std::vector<uint32_t>& spirv, std::string name,
                                 uint32_t pushConstantBytes, const std::vector<SpecConstant>& specialization)
    : mCtx(&ctx), mPushBytes(pushConstantBytes), mName(std::move(name)) {
    AMRVK_CHECK(!spirv.empty(), "shader '", mName, "' is empty");
    AMRVK_CHECK(pushConstantBytes <= ctx.limits().maxPushConstantsSize, "shader '", mName, "' pushes ",
                pushConstantBytes, " bytes; the device allows ", ctx.limits().maxPushConstantsSize);
    try {
        VkShaderModuleCreateInfo mci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
        mci.codeSize = spirv.size() * sizeof(uint32_t);
        mci.pCode = spirv.data();
        AMRVK_VK_CHECK(vkCreateShaderModule(ctx.device(), &mci, nullptr, &mModule));
        VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushConstantBytes};
        VkPipelineLayoutCreateInfo lci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        lci.pushConstantRangeCount = pushConstantBytes ? 1 : 0;
        lci.pPushConstantRanges = &range;
        AMRVK_VK_CHECK(vkCreatePipelineLayout(ctx.device(), &lci, nullptr, &mLayout));
        std::vector<VkSpecializationMapEntry> entries;
        std::vector<uint32_t> data;
        for (const auto& s : specialization) {
            entries.push_back({s.id, uint32_t(data.size() * sizeof(uint32_t)), sizeof(uint32_t)});
            data.push_back(s.value);
        }
        VkSpecializationInfo si{uint32_t(entries.size()), entries.data(), data.size() * sizeof(uint32_t),
                                data.data()};
        VkComputePipelineCreateInfo pci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
        pci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        pci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
        pci.stage.module = mModule;
        pci.stage.pName = "main";
        pci.stage.pSpecializationInfo = entries.empty() ? nullptr : &si;
        pci.layout = mLayout;
        pci.flags = VK_PIPELINE_CREATE_DISPATCH_BASE_BIT;  // dispatchPart
        {
            const DriverCrashScope scope("compiling pipeline '" + mName + "'");
            AMRVK_VK_CHECK(vkCreateComputePipelines(ctx.device(), VK_NULL_HANDLE, 1, &pci, nullptr, &mPipeline));
        }
        ctx.setDebugName(VK_OBJECT_TYPE_PIPELINE, uint64_t(mPipeline), mName);
        // JIT drivers (lavapipe) compile a pipeline at its first dispatch, for seconds on a loaded
        // machine; an empty dispatch, which runs no shader code, compiles it here, so that no
        // submission's time (the adaptive --gpu-timeout's probe, the GPU timers) includes it.
        const std::vector<uint8_t> zeros(mPushBytes);
        ctx.submitAndWait([&](VkCommandBuffer cmd) { dispatch(cmd, zeros.data(), 0, 0, 0); },
                          "an empty dispatch compiling '" + mName + "'");
    } catch (...) {
        release();
        throw;
    }
}

ComputePipeline::~ComputePipeline() { release(); }

void ComputePipeline::release() {
    if (!mCtx) return;
    if (mPipeline) vkDestroyPipeline(mCtx->device(), mPipeline, nullptr);
    if (mLayout) vkDestroyPipelineLayout(mCtx->device(), mLayout, nullptr);
    if (mModule) vkDestroyShaderModule(mCtx->device(), mModule, nullptr);
    mPipeline = VK_NULL_HANDLE;
    mLayout = VK_NULL_HANDLE;
    mModule = VK_NULL_HANDLE;
    mCtx = nullptr;
}

ComputePipeline::ComputePipeline(ComputePipeline&& o) noexcept { *this = std::move(o); }

ComputePipeline& ComputePipeline::operator=(ComputePipeline&& o) noexcept {
    if (this != &o) {
        release();
        mCtx = std::exchange(o.mCtx, nullptr);
        mModule = std::exchange(o.mModule, VK_NULL_HANDLE);
        mLayout = std::exchange(o.mLayout, VK_NULL_HANDLE);
        mPipeline = std::exchange(o.mPipeline, VK_NULL_HANDLE);
        mPushBytes = o.mPushBytes;
        mName = std::move(o.mName);
    }
    return *this;
}

void ComputePipeline::dispatch(VkCommandBuffer cmd, const void* push, uint32_t gx, uint32_t gy,
                               uint32_t gz) const {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, mPipeline);
    if (mPushBytes) vkCmdPushConstants(cmd, mLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, mPushBytes, push);
    vkCmdDispatch(cmd, gx, gy, gz);
}

void ComputePipeline::dispatchPart(VkCommandBuffer cmd, const void* push, uint32_t firstX, uint32_t groupsX) const {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, mPipeline);
    if (mPushBytes) vkCmdPushConstants(cmd, mLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, mPushBytes, push);
    vkCmdDispatchBase(cmd, firstX, 0, 0, groupsX, 1, 1);
}

void imageBarrier(VkCommandBuffer cmd, VkImage image, const ImageUse& from, const ImageUse& to) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask = from.stage;
    b.srcAccessMask = from.access;
    b.dstStageMask = to.stage;
    b.dstAccessMask = to.access;
    b.oldLayout = from.layout;
    b.newLayout = to.layout;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkDependencyInfo di{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    di.imageMemoryBarrierCount = 1;
    di.pImageMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &di);
}

VkBufferImageCopy wholeImageCopy(VkExtent2D extent) {
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {extent.width, extent.height, 1};
    return region;
}

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
    const VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2, nullptr, srcStage, srcAccess, dstStage, dstAccess};
    VkDependencyInfo di{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    di.memoryBarrierCount = 1;
    di.pMemoryBarriers = &mb;
    vkCmdPipelineBarrier2(cmd, &di);
}

void computeBarrier(VkCommandBuffer cmd) {
    constexpr VkPipelineStageFlags2 kStages = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT;
    memoryBarrier(cmd, kStages, VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT, kStages,
                  VK_ACCESS_2_SHADER_READ_BIT | VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_TRANSFER_READ_BIT |
                      VK_ACCESS_2_TRANSFER_WRITE_BIT);
}

GpuTimer::GpuTimer(Context& ctx, uint32_t maxScopes) : mCtx(ctx), mMax(maxScopes) {
    VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    qci.queryType = VK_QUERY_TYPE_TIMESTAMP;
    qci.queryCount = 2 * maxScopes;
    AMRVK_VK_CHECK(vkCreateQueryPool(ctx.device(), &qci, nullptr, &mPool));
}

GpuTimer::~GpuTimer() {
    if (mPool) vkDestroyQueryPool(mCtx.device(), mPool, nullptr);
}

void GpuTimer::reset(VkCommandBuffer cmd) {
    vkCmdResetQueryPool(cmd, mPool, 0, 2 * mMax);
    mScopes = 0;
}

uint32_t GpuTimer::begin(VkCommandBuffer cmd) {
    AMRVK_CHECK(mScopes < mMax, "too many timed GPU scopes (", mMax, ")");
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, mPool, 2 * mScopes);
    return mScopes++;
}

void GpuTimer::end(VkCommandBuffer cmd, uint32_t scope) {
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, mPool, 2 * scope + 1);
}

double GpuTimer::seconds() const {
    if (mScopes == 0) return 0;
    std::vector<uint64_t> ticks(2 * mScopes);
    AMRVK_VK_CHECK(vkGetQueryPoolResults(mCtx.device(), mPool, 0, uint32_t(ticks.size()),
                                         ticks.size() * sizeof(uint64_t), ticks.data(), sizeof(uint64_t),
                                         VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    double s = 0;
    for (uint32_t i = 0; i < mScopes; ++i) s += double(ticks[2 * i + 1] - ticks[2 * i]);
    return s * double(mCtx.limits().timestampPeriod) * 1e-9;
}

}  // namespace amrvk::gpu
