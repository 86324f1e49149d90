#include "gpu/context.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cctype>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "core/file_io.h"
#include "core/strings.h"
#include "gpu/vk_check.h"

namespace amrvk::gpu {

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

// Device types in order of preference: the rank is the index; any other type ranks last as "other".
constexpr std::pair<VkPhysicalDeviceType, const char*> kDeviceTypes[] = {
    {VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, "discrete GPU"},
    {VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU, "integrated GPU"},
    {VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU, "virtual GPU"},
    {VK_PHYSICAL_DEVICE_TYPE_CPU, "CPU"}};

int typeRank(VkPhysicalDeviceType t) {
    int rank = 0;
    while (rank < 4 && kDeviceTypes[rank].first != t) ++rank;
    return rank;
}

const char* typeName(VkPhysicalDeviceType t) { return typeRank(t) < 4 ? kDeviceTypes[typeRank(t)].second : "other"; }

bool hasExtension(const std::vector<VkExtensionProperties>& exts, const char* name) {
    return std::any_of(exts.begin(), exts.end(),
                       [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

bool validationAvailable() {
    const auto layers = vkList<VkLayerProperties>(vkEnumerateInstanceLayerProperties);
    return std::any_of(layers.begin(), layers.end(),
                       [](const VkLayerProperties& l) { return std::strcmp(l.layerName, kValidationLayer) == 0; });
}

bool instanceExtensionAvailable(const char* name) {
    return hasExtension(vkList<VkExtensionProperties>(vkEnumerateInstanceExtensionProperties, (const char*)nullptr),
                        name);
}

VkInstance createInstance(bool validation, bool debugUtils, const std::vector<std::string>& extra = {}) {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "amrvk";
    app.pEngineName = "amrvk";
    app.apiVersion = VK_API_VERSION_1_3;
    std::vector<const char*> layers, exts;
    if (validation) layers.push_back(kValidationLayer);
    if (debugUtils) exts.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    for (const std::string& e : extra) exts.push_back(e.c_str());
    VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ci.pApplicationInfo = &app;
    ci.enabledLayerCount = uint32_t(layers.size());
    ci.ppEnabledLayerNames = layers.data();
    ci.enabledExtensionCount = uint32_t(exts.size());
    ci.ppEnabledExtensionNames = exts.data();
    VkInstance instance = VK_NULL_HANDLE;
    const VkResult vkCreateInstanceResult = vkCreateInstance(&ci, nullptr, &instance);
    AMRVK_CHECK(vkCreateInstanceResult != VK_ERROR_INCOMPATIBLE_DRIVER,
                "no Vulkan 1.3 driver found (install mesa-vulkan-drivers for lavapipe, or a GPU driver)");
    AMRVK_VK_CHECK(vkCreateInstanceResult);
    return instance;
}

struct Probe {
    DeviceReport report;
    uint32_t queueFamily = 0;
    VkPhysicalDeviceType type{};
    bool hostMemoryImport = false;  // VK_EXT_external_memory_host
};

Probe probeDevice(VkPhysicalDevice pd, uint32_t index, VkSurfaceKHR surface = VK_NULL_HANDLE) {
    Probe p;
    VkPhysicalDeviceFloatControlsProperties floats{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FLOAT_CONTROLS_PROPERTIES};
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES, &floats};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &driver};
    vkGetPhysicalDeviceProperties2(pd, &props);
    VkPhysicalDeviceMemoryProperties mem{};
    vkGetPhysicalDeviceMemoryProperties(pd, &mem);
    DeviceReport& r = p.report;
    r.index = index;
    r.name = props.properties.deviceName;
    r.type = typeName(props.properties.deviceType);
    p.type = props.properties.deviceType;
    r.driver = std::string(driver.driverName) + " " + driver.driverInfo;
    r.roundingModeRTEFloat32 = floats.shaderRoundingModeRTEFloat32;
    uint32_t v = props.properties.apiVersion;
    r.apiVersion = std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) +
                   "." + std::to_string(VK_API_VERSION_PATCH(v));
    for (uint32_t i = 0; i < mem.memoryHeapCount; ++i)
        if (mem.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) r.deviceLocalBytes += mem.memoryHeaps[i].size;

    const auto exts = vkList<VkExtensionProperties>(vkEnumerateDeviceExtensionProperties, pd, (const char*)nullptr);
    VkPhysicalDeviceRayQueryFeaturesKHR rq{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
    VkPhysicalDeviceAccelerationStructureFeaturesKHR as{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
    bool rqExts = hasExtension(exts, VK_KHR_RAY_QUERY_EXTENSION_NAME) &&
                  hasExtension(exts, VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME) &&
                  hasExtension(exts, VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME);
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13};
    if (rqExts) {
        f13.pNext = &rq;
        rq.pNext = &as;
    }
    VkPhysicalDeviceFeatures2 f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f12};
    if (v >= VK_API_VERSION_1_3) vkGetPhysicalDeviceFeatures2(pd, &f);
    r.rayQuery = rqExts && rq.rayQuery && as.accelerationStructure;

    const auto qs = vkList<VkQueueFamilyProperties>(vkGetPhysicalDeviceQueueFamilyProperties, pd);
    const uint32_t qn = uint32_t(qs.size());
    bool compute = false;
    for (uint32_t i = 0; i < qn && !compute; ++i) {
        VkBool32 present = VK_TRUE;
        if (surface) vkGetPhysicalDeviceSurfaceSupportKHR(pd, i, surface, &present);
        if ((qs[i].queueFlags & VK_QUEUE_COMPUTE_BIT) && qs[i].timestampValidBits > 0 && present) {
            p.queueFamily = i;
            compute = true;
        }
    }
    const bool swapchain = hasExtension(exts, VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    p.hostMemoryImport = hasExtension(exts, VK_EXT_EXTERNAL_MEMORY_HOST_EXTENSION_NAME);

    DeviceCapabilities c;
    c.apiVersion = v;
    c.bufferDeviceAddress = f12.bufferDeviceAddress;
    c.scalarBlockLayout = f12.scalarBlockLayout;
    c.synchronization2 = f13.synchronization2;
    c.shaderInt64 = f.features.shaderInt64;
    c.shaderRoundingModeRTEFloat32 = r.roundingModeRTEFloat32;
    c.window = surface != VK_NULL_HANDLE;
    c.swapchain = swapchain;
    c.computeQueue = compute;
    r.rejectReason = rejectReason(c);
    r.usable = r.rejectReason.empty();
    return p;
}

std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance) {
    uint32_t n = 0;
    AMRVK_VK_CHECK(vkEnumeratePhysicalDevices(instance, &n, nullptr));
    std::vector<VkPhysicalDevice> pds(n);
    AMRVK_VK_CHECK(vkEnumeratePhysicalDevices(instance, &n, pds.data()));
    return pds;
}

// The device a run uses: --device (an index or part of a name; refused with the reason when it
// cannot serve), else the usable devices of the best type, the spread-th of them. Throws one line
// with every device's reason when none is usable.
int chooseDevice(const std::vector<Probe>& probes, const ContextOptions& options) {
    int chosen = -1;
    // Why a device cannot serve this run: its own reason, or the ray queries --backend rq asked for.
    auto describe = [&](const Probe& p) {
        const std::string why = !p.report.usable ? p.report.rejectReason
                                : options.requireRayQuery && !p.report.rayQuery ? "no VK_KHR_ray_query (--backend rq)"
                                                                                : "usable";
        return p.report.name + ": " + why;
    };
    if (!options.device.empty()) {
        bool numeric = std::all_of(options.device.begin(), options.device.end(), ::isdigit);
        for (size_t i = 0; i < probes.size() && chosen < 0; ++i) {
            bool match = numeric ? std::to_string(i) == options.device
                                 : toLower(probes[i].report.name).find(toLower(options.device)) != std::string::npos;
            if (!match) continue;
            AMRVK_CHECK(probes[i].report.usable, "--device ", options.device, ": ", describe(probes[i]));
            AMRVK_CHECK(!options.requireRayQuery || probes[i].report.rayQuery, "--device ", options.device,
                        ": ", probes[i].report.name, " has no VK_KHR_ray_query");
            chosen = int(i);
        }
        AMRVK_CHECK(chosen >= 0, "--device ", options.device, ": no such device (see amrvk devices)");
    } else {
        // The usable devices of the best type; the spread-th of them (0: the first).
        std::vector<int> best;
        for (size_t i = 0; i < probes.size(); ++i) {
            const Probe& p = probes[i];
            if (!p.report.usable || (options.requireRayQuery && !p.report.rayQuery)) continue;
            if (!best.empty() && typeRank(p.type) > typeRank(probes[size_t(best[0])].type)) continue;
            if (!best.empty() && typeRank(p.type) < typeRank(probes[size_t(best[0])].type)) best.clear();
            best.push_back(int(i));
        }
        if (best.empty()) {
            std::string reasons;
            for (const auto& p : probes) reasons += (reasons.empty() ? "" : "; ") + describe(p);
            AMRVK_CHECK(false, "no usable Vulkan device (", reasons, ")");
        }
        chosen = best[options.spread % best.size()];
    }
    return chosen;
}

}  // namespace

std::string rejectReason(const DeviceCapabilities& c) {
    const uint32_t v = c.apiVersion;
    if (v < VK_API_VERSION_1_3)
        return "Vulkan " + std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
               std::to_string(VK_API_VERSION_PATCH(v)) + " < 1.3";
    if (!c.bufferDeviceAddress) return "no bufferDeviceAddress";
    if (!c.scalarBlockLayout) return "no scalarBlockLayout";
    if (!c.synchronization2) return "no synchronization2";
    if (!c.shaderInt64) return "no shaderInt64";
    if (!c.shaderRoundingModeRTEFloat32)
        return "no shaderRoundingModeRTEFloat32 (the double-float accumulation needs float sums rounded to nearest)";
    if (c.window && !c.swapchain) return "no VK_KHR_swapchain (cannot show a window)";
    if (!c.computeQueue)
        return c.window ? "no compute queue with timestamps that presents to the window" : "no compute queue with timestamps";
    return "";
}

std::vector<DeviceReport> listDevices() {
    VkInstance instance = createInstance(false, false);
    std::vector<DeviceReport> out;
    auto pds = physicalDevices(instance);
    for (uint32_t i = 0; i < pds.size(); ++i) out.push_back(probeDevice(pds[i], i).report);
    vkDestroyInstance(instance, nullptr);
    return out;
}

void MemoryTracker::add(const std::string& name, uint64_t bytes) {
    std::lock_guard lock(mMutex);
    Usage& u = mUsage[name];
    u.current += bytes;
    u.peak = std::max(u.peak, u.current);
    mCurrent += bytes;
    mPeak = std::max(mPeak, mCurrent);
}

void MemoryTracker::remove(const std::string& name, uint64_t bytes) {
    std::lock_guard lock(mMutex);
    Usage& u = mUsage[name];
    u.current -= std::min(u.current, bytes);
    mCurrent -= std::min(mCurrent, bytes);
}

uint64_t MemoryTracker::currentBytes() const {
    std::lock_guard lock(mMutex);
    return mCurrent;
}

uint64_t MemoryTracker::peakBytes() const {
    std::lock_guard lock(mMutex);
    return mPeak;
}

void MemoryTracker::resetPeak() {
    std::lock_guard lock(mMutex);
    mPeak = mCurrent;
    for (auto& [name, usage] : mUsage) usage.peak = usage.current;
}

std::map<std::string, MemoryTracker::Usage> MemoryTracker::perResource() const {
    std::lock_guard lock(mMutex);
    return mUsage;
}

VKAPI_ATTR VkBool32 VKAPI_CALL Context::onValidationMessage(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* self = static_cast<Context*>(user);
    const std::lock_guard lock(self->mValidationMutex);  // messages may come from two threads
    if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
        ++self->mValidationErrors;
        self->mLastValidationMessage = data->pMessage ? data->pMessage : "";
        std::fprintf(stderr, "amrvk: Vulkan validation error: %s\n", self->mLastValidationMessage.c_str());
    } else if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
        std::fprintf(stderr, "amrvk: Vulkan validation warning: %s\n", data->pMessage ? data->pMessage : "");
    }
    return VK_FALSE;
}

namespace {

// What the device is running now, as the message to print if the process crashes meanwhile:
// written before a wait, read by the SIGSEGV/SIGBUS handler (no allocation there).
constexpr size_t kCrashMessageBytes = 1024;
char gCrashMessage[kCrashMessageBytes];
std::string gWho;  // "rank R of N: " in an MPI job (setErrorPrefix)
std::atomic<int> gGpuWorkRunning{0};  // scopes open now, on any thread (a pipeline warms on another)

extern "C" void reportGpuCrash(int sig) {
    if (gGpuWorkRunning.load() > 0) {
        const ssize_t n = ::write(2, gCrashMessage, ::strnlen(gCrashMessage, kCrashMessageBytes));
        (void)n;
        removeTemporariesNow();
        ::_exit(1);
    }
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

void setCrashMessage(const std::string& what) {
    std::snprintf(gCrashMessage, kCrashMessageBytes,
                  "amrvk: error: %sGPU work '%s' crashed the process: it read or wrote outside its buffers "
                  "(a --shader-dir shader?)\n",
                  gWho.c_str(), what.c_str());
}

}  // namespace

DriverCrashScope::DriverCrashScope(const std::string& what) {
    std::snprintf(gCrashMessage, kCrashMessageBytes, "amrvk: error: %sthe Vulkan driver crashed %s (out of memory?)\n",
                  gWho.c_str(), what.c_str());
    gGpuWorkRunning.fetch_add(1);
}

DriverCrashScope::~DriverCrashScope() { gGpuWorkRunning.fetch_sub(1); }

Context::Context(const ContextOptions& options) {
    if (options.gpuTimeoutSeconds > 0) mFixedTimeoutSeconds = options.gpuTimeoutSeconds;
    bool validation = options.validation;
    if (const char* env = std::getenv("AMRVK_VALIDATION"); env && std::strcmp(env, "1") == 0) validation = true;
    if (validation)
        AMRVK_CHECK(validationAvailable(), "Vulkan validation requested but ", kValidationLayer,
                    " is not installed (apt-get install vulkan-validationlayers)");
    mDebugUtils = instanceExtensionAvailable(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    mInstance = createInstance(validation, mDebugUtils, options.instanceExtensions);
    try {
        if (validation && mDebugUtils) createMessenger();

        if (options.createSurface) {
            mSurface = options.createSurface(mInstance);
            AMRVK_CHECK(mSurface, "could not create a Vulkan surface for the window");
        }
        auto pds = physicalDevices(mInstance);
        AMRVK_CHECK(!pds.empty(), "no Vulkan device found (install mesa-vulkan-drivers for lavapipe)");
        std::vector<Probe> probes;
        for (uint32_t i = 0; i < pds.size(); ++i) probes.push_back(probeDevice(pds[i], i, mSurface));
        const int chosen = chooseDevice(probes, options);
        const Probe& pick = probes[size_t(chosen)];
        mPhysical = pds[size_t(chosen)];
        mReport = pick.report;
        mSamplesPerInvocation = options.samplesPerInvocation > 0 ? options.samplesPerInvocation
                                : pick.type == VK_PHYSICAL_DEVICE_TYPE_CPU ? 8u
                                                                           : 1u;
        mPathRegeneration = options.pathRegeneration;
        mQueueFamily = pick.queueFamily;
        mRayQuery = pick.report.rayQuery && !options.disableRayQuery;
        VkPhysicalDeviceProperties props{};
        vkGetPhysicalDeviceProperties(mPhysical, &props);
        mLimits = props.limits;
        vkGetPhysicalDeviceMemoryProperties(mPhysical, &mMemoryProperties);

        float priority = 1.0f;
        VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        qci.queueFamilyIndex = mQueueFamily;
        qci.queueCount = 1;
        qci.pQueuePriorities = &priority;
        VkPhysicalDeviceRayQueryFeaturesKHR rq{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
        VkPhysicalDeviceAccelerationStructureFeaturesKHR as{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
        VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
        VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13};
        VkPhysicalDeviceFeatures2 f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f12};
        f.features.shaderInt64 = VK_TRUE;
        f12.bufferDeviceAddress = VK_TRUE;
        f12.scalarBlockLayout = VK_TRUE;
        f13.synchronization2 = VK_TRUE;
        std::vector<const char*> exts;
        if (mRayQuery) {
            f13.pNext = &rq;
            rq.pNext = &as;
            rq.rayQuery = VK_TRUE;
            as.accelerationStructure = VK_TRUE;
            exts = {VK_KHR_RAY_QUERY_EXTENSION_NAME, VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME,
                    VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME};
        }
        if (mSurface) exts.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
        // On a CPU device, device memory is host memory: arrays are shared, not copied, where the
        // driver can import them (lavapipe can). On a GPU an import would leave them across the bus.
        const bool hostImport = pick.type == VK_PHYSICAL_DEVICE_TYPE_CPU && pick.hostMemoryImport && !options.disableHostImport;
        if (hostImport) exts.push_back(VK_EXT_EXTERNAL_MEMORY_HOST_EXTENSION_NAME);
        VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &f};
        dci.queueCreateInfoCount = 1;
        dci.pQueueCreateInfos = &qci;
        dci.enabledExtensionCount = uint32_t(exts.size());
        dci.ppEnabledExtensionNames = exts.data();
        {
            const DriverCrashScope scope("creating device '" + mReport.name + "'");
            AMRVK_VK_CHECK(vkCreateDevice(mPhysical, &dci, nullptr, &mDevice));
        }
        vkGetDeviceQueue(mDevice, mQueueFamily, 0, &mQueue);
        if (hostImport) queryHostImport();

        VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT | VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
        pci.queueFamilyIndex = mQueueFamily;
        AMRVK_VK_CHECK(vkCreateCommandPool(mDevice, &pci, nullptr, &mCommandPool));
        VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        AMRVK_VK_CHECK(vkCreateFence(mDevice, &fci, nullptr, &mFence));
    } catch (...) {
        release();
        throw;
    }
}

void Context::createMessenger() {
    VkDebugUtilsMessengerCreateInfoEXT mci{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    mci.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT;
    mci.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                      VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    mci.pfnUserCallback = &Context::onValidationMessage;
    mci.pUserData = this;
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(mInstance, "vkCreateDebugUtilsMessengerEXT"));
    AMRVK_CHECK(create, "vkCreateDebugUtilsMessengerEXT is not available");
    AMRVK_VK_CHECK(create(mInstance, &mci, nullptr, &mMessenger));
}

void Context::queryHostImport() {
    VkPhysicalDeviceExternalMemoryHostPropertiesEXT hp{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_MEMORY_HOST_PROPERTIES_EXT};
    VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &hp};
    vkGetPhysicalDeviceProperties2(mPhysical, &p2);
    mHostPointerProperties = reinterpret_cast<PFN_vkGetMemoryHostPointerPropertiesEXT>(
        vkGetDeviceProcAddr(mDevice, "vkGetMemoryHostPointerPropertiesEXT"));
    if (mHostPointerProperties && hp.minImportedHostPointerAlignment > 0)
        mHostImportAlignment = hp.minImportedHostPointerAlignment;
}

Context::~Context() { release(); }

void Context::release() {
    if (mDevice) {
        vkDeviceWaitIdle(mDevice);
        if (mFence) vkDestroyFence(mDevice, mFence, nullptr);
        if (mCommandPool) vkDestroyCommandPool(mDevice, mCommandPool, nullptr);
        vkDestroyDevice(mDevice, nullptr);
        mDevice = VK_NULL_HANDLE;
    }
    if (mSurface) {
        vkDestroySurfaceKHR(mInstance, mSurface, nullptr);
        mSurface = VK_NULL_HANDLE;
    }
    if (mMessenger) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(mInstance, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(mInstance, mMessenger, nullptr);
        mMessenger = VK_NULL_HANDLE;
    }
    if (mInstance) {
        vkDestroyInstance(mInstance, nullptr);
        mInstance = VK_NULL_HANDLE;
    }
}


void setErrorPrefix(const std::string& who) { gWho = who.empty() ? "" : who + ": "; }

void reportGpuCrashes() {
    for (int sig : {SIGSEGV, SIGBUS}) std::signal(sig, reportGpuCrash);
}

namespace {

// The device cannot cancel a dispatch, and waiting for it or destroying the device hangs: one
// line, the temporaries removed, and the process ends here.
[[noreturn]] void endRunaway(const std::string& what, const std::string& why) {
    std::fprintf(stderr, "amrvk: error: %sGPU work '%s' ran longer than %s: a runaway loop? ending\n", gWho.c_str(),
                 what.c_str(), why.c_str());
    std::fflush(stderr);
    removeTemporariesNow();
    ::_exit(1);
}

std::string seconds(double s) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g s", s);
    return buf;
}

}  // namespace

// Polls every 0.1 s: past the limit, the work is cut once its progress count has stood still for
// quietSeconds (at once where there is no count).
VkResult Context::waitAdaptive(const AdaptiveWait& wait, const std::string& what) {
    using Clock = std::chrono::steady_clock;
    const Clock::time_point start = Clock::now();
    const double limit = wait.limitSeconds > 0 ? wait.limitSeconds : kUnmeasuredLimitSeconds;
    uint64_t last = wait.progress ? wait.progress() : 0;
    Clock::time_point lastChange = start;
    for (;;) {
        const VkResult r = vkWaitForFences(mDevice, 1, &mFence, VK_TRUE, 100'000'000);
        if (r != VK_TIMEOUT) return r;
        const Clock::time_point now = Clock::now();
        if (wait.progress) {
            const uint64_t v = wait.progress();
            if (v != last) lastChange = now;
            last = v;
        }
        const double elapsed = std::chrono::duration<double>(now - start).count();
        const double quiet = std::chrono::duration<double>(now - lastChange).count();
        if (elapsed < limit || (wait.progress && quiet < wait.quietSeconds)) continue;
        if (wait.limitSeconds <= 0)
            endRunaway(what, seconds(limit) + " (the --gpu-timeout default for work of no measured pace)");
        endRunaway(what, seconds(limit) + (wait.progress ? ", the last " + std::to_string(int(quiet)) + " s " + wait.stillText : "") +
                             " (the adaptive --gpu-timeout, from the measured pace and a floor; --gpu-timeout S "
                             "waits S s)");
    }
}

double Context::submitAndWait(const std::function<void(VkCommandBuffer)>& record, const std::string& what,
                              const AdaptiveWait& adaptive) {
    const std::lock_guard lock(mSubmitMutex);
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = mCommandPool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    AMRVK_VK_CHECK(vkAllocateCommandBuffers(mDevice, &ai, &cmd));
    struct Free {
        VkDevice d;
        VkCommandPool p;
        VkCommandBuffer c;
        ~Free() { vkFreeCommandBuffers(d, p, 1, &c); }
    } guard{mDevice, mCommandPool, cmd};
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    AMRVK_VK_CHECK(vkBeginCommandBuffer(cmd, &bi));
    record(cmd);
    AMRVK_VK_CHECK(vkEndCommandBuffer(cmd));
    VkCommandBufferSubmitInfo cbi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cbi.commandBuffer = cmd;
    VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    si.commandBufferInfoCount = 1;
    si.pCommandBufferInfos = &cbi;
    AMRVK_VK_CHECK(vkResetFences(mDevice, 1, &mFence));
    setCrashMessage(what);
    gGpuWorkRunning.fetch_add(1);
    const auto start = std::chrono::steady_clock::now();
    AMRVK_VK_CHECK(vkQueueSubmit2(mQueue, 1, &si, mFence));
    VkResult waited;
    if (adaptiveTimeout()) {
        waited = waitAdaptive(adaptive, what);
    } else {
        waited = vkWaitForFences(mDevice, 1, &mFence, VK_TRUE, uint64_t(mFixedTimeoutSeconds * 1e9));
        if (waited == VK_TIMEOUT) endRunaway(what, seconds(mFixedTimeoutSeconds) + " (--gpu-timeout)");
    }
    gGpuWorkRunning.fetch_sub(1);
    AMRVK_VK_CHECK(waited);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

uint32_t Context::hostPointerMemoryTypes(const void* p) const {
    if (mHostImportAlignment == 0 || reinterpret_cast<uintptr_t>(p) % mHostImportAlignment != 0) return 0;
    VkMemoryHostPointerPropertiesEXT props{VK_STRUCTURE_TYPE_MEMORY_HOST_POINTER_PROPERTIES_EXT};
    if (mHostPointerProperties(mDevice, VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_ALLOCATION_BIT_EXT, p, &props) != VK_SUCCESS)
        return 0;
    return props.memoryTypeBits;
}

uint32_t Context::findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required,
                                 VkMemoryPropertyFlags preferred) const {
    for (int pass = 0; pass < 2; ++pass) {
        VkMemoryPropertyFlags want = pass == 0 ? (required | preferred) : required;
        for (uint32_t i = 0; i < mMemoryProperties.memoryTypeCount; ++i)
            if ((typeBits & (1u << i)) && (mMemoryProperties.memoryTypes[i].propertyFlags & want) == want)
                return i;
    }
    AMRVK_CHECK(false, "no Vulkan memory type with the required properties");
    return 0;
}

void Context::setDebugName(VkObjectType type, uint64_t handle, const std::string& name) const {
    if (!mDebugUtils || !mMessenger) return;
    static PFN_vkSetDebugUtilsObjectNameEXT setName = nullptr;
    if (!setName)
        setName = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
            vkGetInstanceProcAddr(mInstance, "vkSetDebugUtilsObjectNameEXT"));
    if (!setName) return;
    VkDebugUtilsObjectNameInfoEXT ni{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
    ni.objectType = type;
    ni.objectHandle = handle;
    ni.pObjectName = name.c_str();
    setName(mDevice, &ni);
}

}  // namespace amrvk::gpu
