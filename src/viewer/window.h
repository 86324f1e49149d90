#pragma once
// A GLFW window for a Vulkan swapchain (no OpenGL context). The only place GLFW is used besides
// the ImGui back-end. Without a display it fails with one line that suggests --headless.
#include <vulkan/vulkan.h>

#include <string>
#include <vector>

struct GLFWwindow;

namespace amrvk::viewer {

// One input event, in the order GLFW delivered it: a key or button pressed and released between two
// frames still arrives as two events (polling the state would miss it). Codes and actions are
// GLFW's.
struct InputEvent {
    enum class Kind { Key, Button, Cursor, Scroll };
    Kind kind = Kind::Key;
    int code = 0;         // key or mouse button
    int action = 0;       // GLFW_PRESS, GLFW_RELEASE or GLFW_REPEAT
    int mods = 0;         // GLFW_MOD_* at the time
    double x = 0, y = 0;  // cursor position (window coordinates; buttons too) or scroll offsets
};

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
    void hide() const;  // the window disappears at once (closing while a long build finishes)
    void pollEvents() const;
    void waitEvents(double seconds) const;  // sleeps until an event or the timeout (minimised window)
    // Framebuffer size in pixels; (0, 0) while minimised.
    void framebufferSize(int& width, int& height) const;
    void setClipboard(const std::string& text) const;
    // The events since the last call, oldest first. Installed before ImGui's back-end, which chains
    // to these callbacks, so both see every event.
    std::vector<InputEvent> takeEvents();

private:
    void push(const InputEvent& e) { mEvents.push_back(e); }
    GLFWwindow* mWindow = nullptr;
    std::vector<InputEvent> mEvents;
};

}  // namespace amrvk::viewer
