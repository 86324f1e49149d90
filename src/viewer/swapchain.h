#pragma once
// The window's swapchain: B8G8R8A8_UNORM images usable as transfer destination (the display pass's
// pixels are copied in, already sRGB encoded) and source (window captures), a render pass that
// draws the UI over them, and one frame in flight. Out-of-date or suboptimal images (a resize)
// are reported so the caller recreates it; a minimised window (size 0) is never recreated.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <vector>

#include "gpu/context.h"

namespace amrvk::viewer {

class Swapchain {
public:
    Swapchain(gpu::Context& ctx, int width, int height);
    ~Swapchain();
    Swapchain(const Swapchain&) = delete;
    Swapchain& operator=(const Swapchain&) = delete;

    // For a new framebuffer size (waits for the device first).
    void recreate(int width, int height);
    VkExtent2D extent() const { return mExtent; }
    VkRenderPass renderPass() const { return mRenderPass; }
    uint32_t imageCount() const { return uint32_t(mImages.size()); }
    uint32_t minImageCount() const { return mMinImageCount; }

    // One frame: acquires an image, records `record(cmd, image, framebuffer)` (the image is in
    // UNDEFINED layout at the start; the render pass leaves it ready to present), submits and
    // presents. False when the swapchain is out of date: recreate it and draw again.
    bool frame(const std::function<void(VkCommandBuffer, VkImage, VkFramebuffer)>& record);

private:
    void create(int width, int height);
    void destroy();

    gpu::Context& mCtx;
    VkSwapchainKHR mSwapchain = VK_NULL_HANDLE;
    VkFormat mFormat = VK_FORMAT_B8G8R8A8_UNORM;
    VkExtent2D mExtent{};
    uint32_t mMinImageCount = 2;
    VkRenderPass mRenderPass = VK_NULL_HANDLE;
    std::vector<VkImage> mImages;
    std::vector<VkImageView> mViews;
    std::vector<VkFramebuffer> mFramebuffers;
    std::vector<VkSemaphore> mRenderDone;  // per image: submit -> present
    VkSemaphore mAcquired = VK_NULL_HANDLE;
    VkFence mInFlight = VK_NULL_HANDLE;
    VkCommandPool mPool = VK_NULL_HANDLE;
    VkCommandBuffer mCmd = VK_NULL_HANDLE;
};

}  // namespace amrvk::viewer
