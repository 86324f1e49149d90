#include "viewer/swapchain.h"

#include <algorithm>

#include "core/error.h"
#include "gpu/vk_check.h"

namespace amrvk::viewer {

Swapchain::Swapchain(gpu::Context& ctx, int width, int height) : mCtx(ctx) {
    AMRVK_CHECK(ctx.surface(), "internal: a swapchain needs a context with a window surface");
    VkDevice dev = ctx.device();
    VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    AMRVK_VK_CHECK(vkCreateSemaphore(dev, &sci, nullptr, &mAcquired));
    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    fci.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    AMRVK_VK_CHECK(vkCreateFence(dev, &fci, nullptr, &mInFlight));
    VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pci.queueFamilyIndex = ctx.queueFamily();
    AMRVK_VK_CHECK(vkCreateCommandPool(dev, &pci, nullptr, &mPool));
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = mPool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    AMRVK_VK_CHECK(vkAllocateCommandBuffers(dev, &ai, &mCmd));

    // Render pass: the UI drawn over the image the display pass filled (load, keep).
    VkAttachmentDescription color{};
    color.format = mFormat;
    color.samples = VK_SAMPLE_COUNT_1_BIT;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    color.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.colorAttachmentCount = 1;
    sub.pColorAttachments = &ref;
    VkSubpassDependency dep{};
    dep.srcSubpass = VK_SUBPASS_EXTERNAL;
    dep.dstSubpass = 0;
    dep.srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dep.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dep.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    dep.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    VkRenderPassCreateInfo rci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    rci.attachmentCount = 1;
    rci.pAttachments = &color;
    rci.subpassCount = 1;
    rci.pSubpasses = &sub;
    rci.dependencyCount = 1;
    rci.pDependencies = &dep;
    AMRVK_VK_CHECK(vkCreateRenderPass(dev, &rci, nullptr, &mRenderPass));
    create(width, height);
}

Swapchain::~Swapchain() {
    VkDevice dev = mCtx.device();
    vkDeviceWaitIdle(dev);
    destroy();
    if (mSwapchain) vkDestroySwapchainKHR(dev, mSwapchain, nullptr);
    vkDestroyRenderPass(dev, mRenderPass, nullptr);
    vkDestroyCommandPool(dev, mPool, nullptr);
    vkDestroyFence(dev, mInFlight, nullptr);
    vkDestroySemaphore(dev, mAcquired, nullptr);
}

void Swapchain::destroy() {
    VkDevice dev = mCtx.device();
    for (VkFramebuffer f : mFramebuffers) vkDestroyFramebuffer(dev, f, nullptr);
    for (VkImageView v : mViews) vkDestroyImageView(dev, v, nullptr);
    for (VkSemaphore s : mRenderDone) vkDestroySemaphore(dev, s, nullptr);
    mFramebuffers.clear();
    mViews.clear();
    mRenderDone.clear();
    mImages.clear();
}

void Swapchain::create(int width, int height) {
    VkPhysicalDevice pd = mCtx.physicalDevice();
    VkSurfaceKHR surface = mCtx.surface();
    VkDevice dev = mCtx.device();
    VkSurfaceCapabilitiesKHR caps{};
    AMRVK_VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(pd, surface, &caps));
    const auto formats = gpu::vkList<VkSurfaceFormatKHR>(vkGetPhysicalDeviceSurfaceFormatsKHR, pd, surface);
    const bool unorm = std::any_of(formats.begin(), formats.end(), [](const VkSurfaceFormatKHR& f) {
        return f.format == VK_FORMAT_B8G8R8A8_UNORM && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
    });
    AMRVK_CHECK(unorm, "the window surface offers no B8G8R8A8_UNORM format");
    const VkImageUsageFlags usage =
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    AMRVK_CHECK((caps.supportedUsageFlags & usage) == usage, "the window surface cannot be a transfer target");
    mExtent = caps.currentExtent.width != UINT32_MAX
                  ? caps.currentExtent
                  : VkExtent2D{std::clamp(uint32_t(width), caps.minImageExtent.width, caps.maxImageExtent.width),
                               std::clamp(uint32_t(height), caps.minImageExtent.height, caps.maxImageExtent.height)};
    mMinImageCount = std::max(caps.minImageCount, 2u);
    if (caps.maxImageCount > 0) mMinImageCount = std::min(mMinImageCount, caps.maxImageCount);

    VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    ci.surface = surface;
    ci.minImageCount = mMinImageCount;
    ci.imageFormat = mFormat;
    ci.imageColorSpace = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
    ci.imageExtent = mExtent;
    ci.imageArrayLayers = 1;
    ci.imageUsage = usage;
    ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    ci.preTransform = caps.currentTransform;
    ci.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    ci.presentMode = VK_PRESENT_MODE_FIFO_KHR;  // always available; the frame budget sets the pace
    ci.clipped = VK_TRUE;
    ci.oldSwapchain = mSwapchain;
    VkSwapchainKHR next = VK_NULL_HANDLE;
    AMRVK_VK_CHECK(vkCreateSwapchainKHR(dev, &ci, nullptr, &next));
    if (mSwapchain) vkDestroySwapchainKHR(dev, mSwapchain, nullptr);
    mSwapchain = next;

    mImages = gpu::vkList<VkImage>(vkGetSwapchainImagesKHR, dev, mSwapchain);
    for (VkImage image : mImages) {
        VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        vci.image = image;
        vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
        vci.format = mFormat;
        vci.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkImageView view = VK_NULL_HANDLE;
        AMRVK_VK_CHECK(vkCreateImageView(dev, &vci, nullptr, &view));
        mViews.push_back(view);
        VkFramebufferCreateInfo fci{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
        fci.renderPass = mRenderPass;
        fci.attachmentCount = 1;
        fci.pAttachments = &view;
        fci.width = mExtent.width;
        fci.height = mExtent.height;
        fci.layers = 1;
        VkFramebuffer fb = VK_NULL_HANDLE;
        AMRVK_VK_CHECK(vkCreateFramebuffer(dev, &fci, nullptr, &fb));
        mFramebuffers.push_back(fb);
        VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        VkSemaphore s = VK_NULL_HANDLE;
        AMRVK_VK_CHECK(vkCreateSemaphore(dev, &sci, nullptr, &s));
        mRenderDone.push_back(s);
    }
}

void Swapchain::recreate(int width, int height) {
    vkDeviceWaitIdle(mCtx.device());
    destroy();
    create(width, height);
}

bool Swapchain::frame(const std::function<void(VkCommandBuffer, VkImage, VkFramebuffer)>& record) {
    VkDevice dev = mCtx.device();
    AMRVK_VK_CHECK(vkWaitForFences(dev, 1, &mInFlight, VK_TRUE, UINT64_MAX));
    uint32_t index = 0;
    const VkResult acquired = vkAcquireNextImageKHR(dev, mSwapchain, UINT64_MAX, mAcquired, VK_NULL_HANDLE, &index);
    if (acquired == VK_ERROR_OUT_OF_DATE_KHR) return false;
    if (acquired != VK_SUBOPTIMAL_KHR) AMRVK_VK_CHECK(acquired);
    AMRVK_VK_CHECK(vkResetFences(dev, 1, &mInFlight));
    AMRVK_VK_CHECK(vkResetCommandBuffer(mCmd, 0));
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    AMRVK_VK_CHECK(vkBeginCommandBuffer(mCmd, &bi));
    record(mCmd, mImages[index], mFramebuffers[index]);
    AMRVK_VK_CHECK(vkEndCommandBuffer(mCmd));

    VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    wait.semaphore = mAcquired;
    wait.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    signal.semaphore = mRenderDone[index];
    signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    VkCommandBufferSubmitInfo cbi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cbi.commandBuffer = mCmd;
    VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    si.waitSemaphoreInfoCount = 1;
    si.pWaitSemaphoreInfos = &wait;
    si.commandBufferInfoCount = 1;
    si.pCommandBufferInfos = &cbi;
    si.signalSemaphoreInfoCount = 1;
    si.pSignalSemaphoreInfos = &signal;
    AMRVK_VK_CHECK(vkQueueSubmit2(mCtx.queue(), 1, &si, mInFlight));

    VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    pi.waitSemaphoreCount = 1;
    pi.pWaitSemaphores = &mRenderDone[index];
    pi.swapchainCount = 1;
    pi.pSwapchains = &mSwapchain;
    pi.pImageIndices = &index;
    const VkResult presented = vkQueuePresentKHR(mCtx.queue(), &pi);
    if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR || acquired == VK_SUBOPTIMAL_KHR)
        return false;
    AMRVK_VK_CHECK(presented);
    return true;
}

}  // namespace amrvk::viewer
