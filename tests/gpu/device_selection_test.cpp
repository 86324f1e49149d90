// Device selection asks for round-to-nearest float sums (issue 32, point 6): the double-float
// accumulation (shaders/lib/double_float.glsl) is error-free only where float additions round to
// nearest, Vulkan's default is RTE or RTZ (implementation-defined), so the path tracers declare
// RoundingModeRTE and a device without shaderRoundingModeRTEFloat32 is refused with its reason.
// The decision is checked on made-up capabilities; the property on the devices of this machine.
#include <gtest/gtest.h>

#include <filesystem>

#include "gpu/context.h"
#include "gpu/shader_compiler.h"
#include "gpu/shader_library.h"
#include "gpu_fixture.h"

using namespace amrvk;

namespace {

gpu::DeviceCapabilities everything() {
    gpu::DeviceCapabilities c;
    c.apiVersion = VK_API_VERSION_1_3;
    c.bufferDeviceAddress = c.scalarBlockLayout = c.synchronization2 = c.shaderInt64 = true;
    c.shaderRoundingModeRTEFloat32 = true;
    c.swapchain = c.computeQueue = true;
    return c;
}

// Whether a SPIR-V module declares OpCapability RoundingModeRTE and OpExecutionMode RoundingModeRTE 32.
bool declaresRte(const std::vector<uint32_t>& spirv) {
    constexpr uint32_t kOpCapability = 17, kOpExecutionMode = 16, kRoundingModeRTE = 4462, kCapabilityRTE = 4467;
    bool capability = false, mode = false;
    for (size_t i = 5; i < spirv.size();) {
        const uint32_t words = spirv[i] >> 16, op = spirv[i] & 0xffff;
        if (words == 0) break;
        if (op == kOpCapability && words >= 2 && spirv[i + 1] == kCapabilityRTE) capability = true;
        if (op == kOpExecutionMode && words >= 4 && spirv[i + 2] == kRoundingModeRTE && spirv[i + 3] == 32) mode = true;
        i += words;
    }
    return capability && mode;
}

}  // namespace

TEST(DeviceSelection, RefusesADeviceThatCannotRoundFloatSumsToNearest) {
    EXPECT_EQ(gpu::rejectReason(everything()), "");
    gpu::DeviceCapabilities c = everything();
    c.shaderRoundingModeRTEFloat32 = false;
    EXPECT_NE(gpu::rejectReason(c).find("no shaderRoundingModeRTEFloat32"), std::string::npos) << gpu::rejectReason(c);
}

TEST(DeviceSelection, NamesEachMissingRequirement) {
    const std::pair<bool gpu::DeviceCapabilities::*, const char*> required[] = {
        {&gpu::DeviceCapabilities::bufferDeviceAddress, "no bufferDeviceAddress"},
        {&gpu::DeviceCapabilities::scalarBlockLayout, "no scalarBlockLayout"},
        {&gpu::DeviceCapabilities::synchronization2, "no synchronization2"},
        {&gpu::DeviceCapabilities::shaderInt64, "no shaderInt64"},
        {&gpu::DeviceCapabilities::computeQueue, "no compute queue with timestamps"}};
    for (const auto& [field, reason] : required) {
        gpu::DeviceCapabilities c = everything();
        c.*field = false;
        EXPECT_EQ(gpu::rejectReason(c), reason);
    }
    gpu::DeviceCapabilities old = everything();
    old.apiVersion = VK_API_VERSION_1_2;
    EXPECT_EQ(gpu::rejectReason(old), "Vulkan 1.2.0 < 1.3");
    // The swapchain only matters with a window.
    gpu::DeviceCapabilities headless = everything();
    headless.swapchain = false;
    EXPECT_EQ(gpu::rejectReason(headless), "");
    headless.window = true;
    EXPECT_EQ(gpu::rejectReason(headless), "no VK_KHR_swapchain (cannot show a window)");
}

TEST(DeviceSelection, ReportsTheRoundingModeOfEveryDevice) {
    // Read from Vulkan (a report left false would refuse every device): a usable device rounds to
    // nearest, and the tests always have one.
    const std::vector<gpu::DeviceReport> devices = gpu::listDevices();
    bool usable = false;
    for (const gpu::DeviceReport& d : devices) {
        EXPECT_TRUE(!d.usable || d.roundingModeRTEFloat32) << d.name;
        usable = usable || d.usable;
    }
    EXPECT_TRUE(usable);
}

TEST(DeviceSelection, ThePathTracersDeclareRoundingModeRte) {
    gpu::registerShaders(shaders::passShaders());
    for (const char* name : {"path_trace", "path_trace_rq", "path_trace_dp", "path_trace_dp_rq", "path_trace_ubrm",
                             "path_trace_rq_ubrm", "path_trace_dp_ubrm", "path_trace_dp_rq_ubrm"})
        EXPECT_TRUE(declaresRte(gpu::loadShader(name))) << name << " (embedded)";
    // The same from source, as a --shader-dir compiles it at run time (shaderc).
    const std::filesystem::path shaders = std::filesystem::path(AMRVK_SOURCE_DIR) / "shaders";
    for (const char* name : {"path_trace", "path_trace_dp"})
        EXPECT_TRUE(declaresRte(gpu::compileComputeShader(shaders / "passes" / (std::string(name) + ".comp"), {}, {shaders})))
            << name << " (shaderc)";
    // Power: a shader without double_float.glsl declares nothing.
    EXPECT_FALSE(declaresRte(gpu::loadShader("majorants")));
}
