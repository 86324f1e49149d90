#pragma once
// Vulkan failures become gpu::VulkanError naming the call and the VkResult.
#include <vulkan/vulkan.h>

#include <vector>

#include "core/error.h"

namespace amrvk::gpu {

const char* resultName(VkResult result);

class VulkanError : public Error {
public:
    VulkanError(VkResult result, const char* call)
        : Error(strCat("Vulkan call ", call, " failed with ", resultName(result),
                       result == VK_ERROR_OUT_OF_HOST_MEMORY || result == VK_ERROR_OUT_OF_DEVICE_MEMORY
                           ? " (out of memory)"
                           : "")),
          mResult(result) {}
    VkResult result() const { return mResult; }

private:
    VkResult mResult;
};

#define AMRVK_VK_CHECK(expr)                                                         \
    do {                                                                             \
        VkResult amrvkVkResult_ = (expr);                                            \
        if (amrvkVkResult_ != VK_SUCCESS) throw ::amrvk::gpu::VulkanError(amrvkVkResult_, #expr); \
    } while (0)

// Vulkan's two-call enumeration: fn(args..., &count, nullptr), then fn(args..., &count, items).
template <typename T, typename F, typename... Args>
std::vector<T> vkList(F fn, Args... args) {
    uint32_t n = 0;
    fn(args..., &n, nullptr);
    std::vector<T> items(n);
    fn(args..., &n, items.data());
    items.resize(n);
    return items;
}

}  // namespace amrvk::gpu
