#include "viewer/window.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <cstdlib>
#include <utility>

#include "core/error.h"
#include "gpu/vk_check.h"

namespace amrvk::viewer {

namespace {

Window& owner(GLFWwindow* w) { return *static_cast<Window*>(glfwGetWindowUserPointer(w)); }

std::string lastGlfwError() {
    const char* text = nullptr;
    glfwGetError(&text);
    return text ? text : "unknown GLFW error";
}

}  // namespace

Window::Window(int width, int height, const std::string& title) {
    if (!glfwInit()) {
        const std::string why = lastGlfwError();
        const char* display = std::getenv("DISPLAY");
        AMRVK_CHECK(false, "cannot open a window (", why, display && *display ? "" : "; DISPLAY is not set",
                    "): run with --headless, or under xvfb-run");
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
    mWindow = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!mWindow) {
        const std::string why = lastGlfwError();
        glfwTerminate();
        AMRVK_CHECK(false, "cannot open a window (", why, "): run with --headless, or under xvfb-run");
    }
    glfwSetWindowUserPointer(mWindow, this);
    glfwSetKeyCallback(mWindow, [](GLFWwindow* w, int key, int, int action, int mods) {
        owner(w).push({InputEvent::Kind::Key, key, action, mods});
    });
    glfwSetMouseButtonCallback(mWindow, [](GLFWwindow* w, int button, int action, int mods) {
        double x = 0, y = 0;
        glfwGetCursorPos(w, &x, &y);  // where the press happened (decides picture or panel)
        owner(w).push({InputEvent::Kind::Button, button, action, mods, x, y});
    });
    glfwSetCursorPosCallback(mWindow, [](GLFWwindow* w, double x, double y) {
        owner(w).push({InputEvent::Kind::Cursor, 0, 0, 0, x, y});
    });
    glfwSetScrollCallback(mWindow, [](GLFWwindow* w, double x, double y) {
        owner(w).push({InputEvent::Kind::Scroll, 0, 0, 0, x, y});
    });
}

Window::~Window() {
    if (mWindow) glfwDestroyWindow(mWindow);
    glfwTerminate();
}

std::vector<std::string> Window::requiredInstanceExtensions() {
    uint32_t n = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&n);
    AMRVK_CHECK(names, "GLFW found no Vulkan support for windows (", lastGlfwError(), ")");
    return std::vector<std::string>(names, names + n);
}

VkSurfaceKHR Window::createSurface(VkInstance instance) const {
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    AMRVK_VK_CHECK(glfwCreateWindowSurface(instance, mWindow, nullptr, &surface));
    return surface;
}

bool Window::shouldClose() const { return glfwWindowShouldClose(mWindow); }
void Window::requestClose() const { glfwSetWindowShouldClose(mWindow, GLFW_TRUE); }
void Window::hide() const { glfwHideWindow(mWindow); }
void Window::pollEvents() const { glfwPollEvents(); }
void Window::waitEvents(double seconds) const { glfwWaitEventsTimeout(seconds); }
void Window::framebufferSize(int& width, int& height) const { glfwGetFramebufferSize(mWindow, &width, &height); }
void Window::setClipboard(const std::string& text) const { glfwSetClipboardString(mWindow, text.c_str()); }
std::vector<InputEvent> Window::takeEvents() { return std::exchange(mEvents, {}); }

}  // namespace amrvk::viewer
