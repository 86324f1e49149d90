#pragma once
// Vulkan failures become gpu::VulkanError naming the call and the VkResult.
#include <vulkan/vulkan.h>

#include "core/error.h"

namespace amrvk::gpu {

const char* resultName(VkResult result);

class VulkanError : public Error {
public:
    VulkanError(VkResult result, const char* call)
        : Error(strCat("Vulkan call ", call, " failed with ", resultName(result))), mResult(result) {}
    VkResult result() const { return mResult; }

private:
    VkResult mResult;
};

#define AMRVK_VK_CHECK(expr)                                                         \
    do {                                                                             \
        VkResult amrvkVkResult_ = (expr);                                            \
        if (amrvkVkResult_ != VK_SUCCESS) throw ::amrvk::gpu::VulkanError(amrvkVkResult_, #expr); \
    } while (0)

}  // namespace amrvk::gpu
