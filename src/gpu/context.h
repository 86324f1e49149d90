#pragma once
// The Vulkan instance and device amrvk computes on. Knows nothing about AMR.
//  - Device selection: --device INDEX|NAME, else the first discrete GPU, else integrated, else
//    any (lavapipe). Every device is reported with type, driver, memory, ray-query support and, if
//    unusable, why (listDevices()).
//  - Required: Vulkan 1.3 features bufferDeviceAddress, synchronization2, scalarBlockLayout,
//    shaderInt64, and the float control shaderRoundingModeRTEFloat32 (the path tracer declares
//    RoundingModeRTE for its double-float sums, lib/double_float.glsl). Optional: rayQuery +
//    accelerationStructure (hasRayQuery()).
//  - Host memory import: on a CPU device (lavapipe) with VK_EXT_external_memory_host, read-only
//    arrays are handed to the device where they lie instead of copied (hostImportAlignment(),
//    gpu::Buffer::importHost, gpu::shareOrCopyBuffer), since device memory is host memory there.
//  - Validation: the Khronos layer with a messenger that counts errors (tests fail on any).
#include <vulkan/vulkan.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <vector>

namespace amrvk::gpu {

struct ContextOptions {
    std::string device;       // "" = automatic; a decimal index or a case-insensitive name part
    bool validation = false;  // also on when AMRVK_VALIDATION=1
    // Automatic choice only: among the usable devices of the best type, take the (spread % count)-th
    // (an MPI rank passes its rank on the node: one GPU per rank where a node has several).
    uint32_t spread = 0;
    bool requireRayQuery = false;
    bool disableRayQuery = false;  // leave ray queries off even where supported (tests, comparisons)
    bool disableHostImport = false;  // copy arrays even on a CPU device that could share them (tests)
    // Samples per pixel one path-trace invocation takes in a whole-image dispatch; 0 = automatic
    // (8 on CPU devices, where it was measured to help; 1 on GPUs until measured there).
    uint32_t samplesPerInvocation = 0;
    // Path regeneration in the path tracer's whole-image dispatches (passes/path_trace.comp): a
    // workgroup's samples are a pool its invocations take from one at a time, so a lane whose path
    // ended takes the next instead of idling. The same image; off by default (on lavapipe it raised
    // the lanes' use but not the paths per second: docs/benchmarks.md section 27).
    bool pathRegeneration = false;
    // How long one submission may run (seconds) before amrvk ends the process with one line naming
    // the work: a runaway loop in a --shader-dir shader cannot be cancelled on the device, and
    // waiting on, or destroying, a device that still runs it would hang. 0 = adaptive: path tracing,
    // the staged data-parallel pass and the majorants are held to a limit that follows their
    // measured pace (core/gpu_deadline.h, gpu/paced_submit.h), other work to 600 s.
    double gpuTimeoutSeconds = 0;
    // Presentation (the viewer): instance extensions the window system needs, and a function that
    // creates the window's surface once the instance exists. The device picked must then present
    // to that surface from its queue and gets VK_KHR_swapchain; the Context destroys the surface.
    std::vector<std::string> instanceExtensions;
    std::function<VkSurfaceKHR(VkInstance)> createSurface;
};

// The adaptive --gpu-timeout of one submission (core/gpu_deadline.h); a fixed --gpu-timeout
// ignores it. The work is cut once it has run limitSeconds (0: Context::kUnmeasuredLimitSeconds)
// and, where it has a progress count (one that changes while the work is alive, e.g. paths
// finished, read from mapped memory while it runs), that count has not changed for quietSeconds.
struct AdaptiveWait {
    double limitSeconds = 0;
    double quietSeconds = 0;
    std::function<uint64_t()> progress;
    std::string stillText = "finishing no path";  // what the runaway line says of a count standing still
};

struct DeviceReport {
    uint32_t index = 0;
    std::string name, type, driver, apiVersion;
    uint64_t deviceLocalBytes = 0;
    bool rayQuery = false;
    bool roundingModeRTEFloat32 = false;  // VkPhysicalDeviceFloatControlsProperties
    bool usable = false;
    std::string rejectReason;  // empty when usable
};

// What device selection asks of a device: probed from Vulkan, or made up by a test.
struct DeviceCapabilities {
    uint32_t apiVersion = 0;  // VK_MAKE_API_VERSION
    bool bufferDeviceAddress = false, scalarBlockLayout = false, synchronization2 = false, shaderInt64 = false;
    // The double-float sums of the accumulation (lib/double_float.glsl) are error-free only where
    // float additions round to nearest; Vulkan's default is RTE or RTZ, implementation-defined, so
    // the path tracer declares RoundingModeRTE, which needs this.
    bool shaderRoundingModeRTEFloat32 = false;
    bool window = false;     // a window asked for: the device must present to it
    bool swapchain = false;  // VK_KHR_swapchain (only asked for with a window)
    bool computeQueue = false;  // a compute queue with timestamps (that presents, with a window)
};

// Why a device with these capabilities cannot be used, "" when it can (the first reason found).
std::string rejectReason(const DeviceCapabilities& c);

// Enumerates every physical device with the reason it cannot be used, if any.
std::vector<DeviceReport> listDevices();

// Device memory per named resource and in total: current and peak bytes.
class MemoryTracker {
public:
    struct Usage {
        uint64_t current = 0, peak = 0;
    };
    void add(const std::string& name, uint64_t bytes);
    void remove(const std::string& name, uint64_t bytes);
    uint64_t currentBytes() const;
    uint64_t peakBytes() const;
    // Starts a new peak measurement: every peak becomes the current usage.
    void resetPeak();
    // Every resource name seen so far (freed ones keep their peak with current 0).
    std::map<std::string, Usage> perResource() const;

private:
    mutable std::mutex mMutex;
    std::map<std::string, Usage> mUsage;
    uint64_t mCurrent = 0, mPeak = 0;
};

// Installs SIGSEGV/SIGBUS handlers that, while a submission waits, print one line naming the GPU
// work that crashed the process (then remove the temporaries and exit 1); other crashes keep their
// default action. main() calls it once.
void reportGpuCrashes();
// Text those lines (and the --gpu-timeout line) name the process by after "error: ", e.g. "rank 1
// of 3" in an MPI job; empty: none.
void setErrorPrefix(const std::string& who);
// While it lives, a crash of the process is reported as "the Vulkan driver crashed WHAT (out of
// memory?)": drivers that JIT-compile (lavapipe) crash instead of failing when memory runs out.
class DriverCrashScope {
public:
    explicit DriverCrashScope(const std::string& what);  // e.g. "creating device 'llvmpipe'"
    ~DriverCrashScope();
    DriverCrashScope(const DriverCrashScope&) = delete;
    DriverCrashScope& operator=(const DriverCrashScope&) = delete;
};

class Context {
public:
    explicit Context(const ContextOptions& options = {});
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkInstance instance() const { return mInstance; }
    VkPhysicalDevice physicalDevice() const { return mPhysical; }
    VkDevice device() const { return mDevice; }
    VkQueue queue() const { return mQueue; }
    VkSurfaceKHR surface() const { return mSurface; }  // VK_NULL_HANDLE without presentation
    uint32_t queueFamily() const { return mQueueFamily; }
    const DeviceReport& deviceReport() const { return mReport; }
    const VkPhysicalDeviceLimits& limits() const { return mLimits; }
    bool hasRayQuery() const { return mRayQuery; }
    // ContextOptions::samplesPerInvocation resolved for this device (>= 1).
    uint32_t samplesPerInvocation() const { return mSamplesPerInvocation; }
    bool pathRegeneration() const { return mPathRegeneration; }
    uint64_t validationErrors() const { return mValidationErrors; }
    const std::string& lastValidationMessage() const { return mLastValidationMessage; }
    MemoryTracker& memory() { return mMemory; }

    // Records, submits and waits; returns the wall seconds from submit to the fence. `what` names
    // the work in the one-line error when it runs past the limit or crashes the process (e.g.
    // "path_trace.ms.grid-dda/grid/sw from --shader-dir DIR"): a dispatch that reads or writes
    // outside its buffers can crash a CPU device (lavapipe), where buffer device addresses have no
    // robust access. The limit is --gpu-timeout where given, else `adaptive` (AdaptiveWait).
    // Thread-safe: submissions from several threads (a pipeline compiled on another thread while
    // structures upload, render::warmPathTracer) take turns on the one queue and command pool.
    double submitAndWait(const std::function<void(VkCommandBuffer)>& record, const std::string& what = "GPU work",
                         const AdaptiveWait& adaptive = {});
    // No --gpu-timeout was given: callers that measure their pace pass adaptive limits.
    bool adaptiveTimeout() const { return mFixedTimeoutSeconds == 0; }
    static constexpr double kUnmeasuredLimitSeconds = 600;  // work without a measured pace
    uint32_t findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required,
                            VkMemoryPropertyFlags preferred = 0) const;
    // The alignment host memory imported into this device must have (minImportedHostPointerAlignment),
    // or 0 where it imports none: not a CPU device, no VK_EXT_external_memory_host, or disabled.
    uint64_t hostImportAlignment() const { return mHostImportAlignment; }
    // The memory types host memory at p (aligned to hostImportAlignment()) can be imported as; 0 if none.
    uint32_t hostPointerMemoryTypes(const void* p) const;
    void setDebugName(VkObjectType type, uint64_t handle, const std::string& name) const;

private:
    void release();
    void createMessenger();  // the validation messages' callback (onValidationMessage)
    void queryHostImport();  // vkGetMemoryHostPointerPropertiesEXT and the import alignment
    VkResult waitAdaptive(const AdaptiveWait& wait, const std::string& what);
    static VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(
        VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
        const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);

    VkInstance mInstance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT mMessenger = VK_NULL_HANDLE;
    VkSurfaceKHR mSurface = VK_NULL_HANDLE;
    VkPhysicalDevice mPhysical = VK_NULL_HANDLE;
    VkDevice mDevice = VK_NULL_HANDLE;
    VkQueue mQueue = VK_NULL_HANDLE;
    uint32_t mQueueFamily = 0;
    VkCommandPool mCommandPool = VK_NULL_HANDLE;
    VkFence mFence = VK_NULL_HANDLE;
    VkPhysicalDeviceLimits mLimits{};
    VkPhysicalDeviceMemoryProperties mMemoryProperties{};
    DeviceReport mReport;
    bool mRayQuery = false;
    uint32_t mSamplesPerInvocation = 1;
    bool mPathRegeneration = false;
    uint64_t mHostImportAlignment = 0;
    PFN_vkGetMemoryHostPointerPropertiesEXT mHostPointerProperties = nullptr;
    double mFixedTimeoutSeconds = 0;  // --gpu-timeout; 0 = adaptive
    bool mDebugUtils = false;
    std::recursive_mutex mSubmitMutex;  // the queue, command pool and fence of submitAndWait
    std::mutex mValidationMutex;        // the two fields below, written by the validation callback
    std::atomic<uint64_t> mValidationErrors{0};
    std::string mLastValidationMessage;
    MemoryTracker mMemory;
};

}  // namespace amrvk::gpu
