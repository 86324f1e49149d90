#pragma once
// Dear ImGui 1.86 on the window (GLFW back-end) and the swapchain's render pass (Vulkan back-end):
// the only place besides viewer/panels.cpp that calls ImGui. Debian's libimgui-dev has both
// back-ends compiled in.
#include <vulkan/vulkan.h>

#include "gpu/context.h"

struct GLFWwindow;

namespace amrvk::viewer {

class ImGuiLayer {
public:
    ImGuiLayer(gpu::Context& ctx, GLFWwindow* window, VkRenderPass renderPass, uint32_t minImageCount,
               uint32_t imageCount);
    ~ImGuiLayer();
    ImGuiLayer(const ImGuiLayer&) = delete;
    ImGuiLayer& operator=(const ImGuiLayer&) = delete;

    void beginFrame();
    // Records the UI draw calls (inside the render pass).
    void render(VkCommandBuffer cmd);
    void setMinImageCount(uint32_t count);
    // Whether the UI wants the mouse / keyboard this frame (then the camera does not get them).
    bool wantsMouse() const;
    bool wantsKeyboard() const;

private:
    gpu::Context& mCtx;
    VkDescriptorPool mPool = VK_NULL_HANDLE;
};

}  // namespace amrvk::viewer
