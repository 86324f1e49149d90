#pragma once
// A GLFW window for a Vulkan swapchain (no OpenGL context). The only place GLFW is used besides
// the ImGui back-end. Without a display it fails with one line that suggests --headless.
#include <vulkan/vulkan.h>

#include <string>
#include <vector>

struct GLFWwindow;

namespace amrvk::viewer {

class Window {
public:
    Window(int width, int height, const std::string& title);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    GLFWwindow* handle() const { return mWindow; }
    // Instance extensions the surface needs, and the surface itself (the gpu::Context owns it).
    static std::vector<std::string> requiredInstanceExtensions();
    VkSurfaceKHR createSurface(VkInstance instance) const;

    bool shouldClose() const;
    void requestClose() const;
    void pollEvents() const;
    void waitEvents(double seconds) const;  // sleeps until an event or the timeout (minimised window)
    // Framebuffer size in pixels; (0, 0) while minimised.
    void framebufferSize(int& width, int& height) const;
    void setTitle(const std::string& title) const;
    void setClipboard(const std::string& text) const;

private:
    GLFWwindow* mWindow = nullptr;
};

}  // namespace amrvk::viewer
