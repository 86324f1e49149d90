#pragma once
// A named, move-only Vulkan buffer with its own memory, addressed by buffer device address
// (shaders reach it through a 64-bit pointer, so no descriptor and no 128 MiB binding limit).
// Device memory is counted per name in the context's MemoryTracker.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "gpu/context.h"

namespace amrvk::gpu {

enum class MemoryKind {
    Device,    // device-local; filled by upload()
    HostRead,  // host-visible, cached where possible; for readback
};

// Device-local buffers are filled and read back through a staging buffer of at most this size.
inline constexpr uint64_t kStagingBytes = uint64_t{64} << 20;

class Buffer {
public:
    Buffer() = default;
    Buffer(Context& ctx, uint64_t bytes, MemoryKind kind, std::string name,
           VkBufferUsageFlags extraUsage = 0);
    ~Buffer();
    Buffer(Buffer&& other) noexcept;
    Buffer& operator=(Buffer&& other) noexcept;
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;

    // A buffer over host memory that the device reads where it lies (Context::hostImportAlignment()
    // > 0: a CPU device): [data, data + bytes) stays the caller's, alive and unchanged while the
    // buffer lives. The whole pages around it are imported; address() is data's. Read-only: upload
    // and fillZero refuse it. An invalid Buffer where the device cannot import that memory.
    static Buffer importHost(Context& ctx, const void* data, uint64_t bytes, std::string name);
    bool imported() const { return mImported; }

    VkBuffer handle() const { return mBuffer; }
    VkDeviceAddress address() const { return mAddress; }
    uint64_t size() const { return mSize; }
    // Device bytes allocated for it (>= size()), as counted in ctx.memory().
    uint64_t allocatedBytes() const { return mAllocated; }
    const std::string& name() const { return mName; }
    bool valid() const { return mBuffer != VK_NULL_HANDLE; }
    // Host-mapped: download() reads it without a submission (so also while work runs).
    bool mapped() const { return mMapped != nullptr; }

    // Copies bytes into the buffer (directly if mapped, else through a staging buffer).
    void upload(const void* data, uint64_t bytes, uint64_t offset = 0);
    template <typename T>
    void upload(std::span<const T> values) {
        upload(values.data(), values.size_bytes());
    }
    // Copies `bytes` of the buffer from `offset` on to host memory.
    void download(void* data, uint64_t bytes, uint64_t offset = 0) const;
    // The copies unmapped (device-local) buffers take: through a staging buffer of chunkBytes,
    // one chunk at a time (kStagingBytes by default). Public so tests exercise them on devices
    // whose memory is all mapped (lavapipe).
    void uploadStaged(const void* data, uint64_t bytes, uint64_t offset, uint64_t chunkBytes);
    void downloadStaged(void* data, uint64_t bytes, uint64_t chunkBytes, uint64_t offset = 0) const;
    template <typename T>
    std::vector<T> download() const {
        std::vector<T> out(mSize / sizeof(T));
        download(out.data(), out.size() * sizeof(T));
        return out;
    }
    void fillZero();

private:
    void release();
    Context* mCtx = nullptr;
    VkBuffer mBuffer = VK_NULL_HANDLE;
    VkDeviceMemory mMemory = VK_NULL_HANDLE;
    VkDeviceAddress mAddress = 0;
    uint64_t mSize = 0;
    uint64_t mAllocated = 0;  // bytes counted in the MemoryTracker
    uint64_t mOffset = 0;     // bytes from the VkBuffer's start to the data (imported: to the caller's)
    bool mImported = false;
    void* mMapped = nullptr;
    bool mCoherent = true;
    std::string mName;
};

// A device buffer holding `values` (at least 16 bytes so empty arrays still have an address).
template <typename T>
Buffer makeBuffer(Context& ctx, std::span<const T> values, const std::string& name,
                  VkBufferUsageFlags extraUsage = 0) {
    Buffer b(ctx, std::max<uint64_t>(values.size_bytes(), 16), MemoryKind::Device, name, extraUsage);
    if (!values.empty()) b.upload(values);
    return b;
}

// A device buffer holding `values`: the values themselves where the device imports host memory
// (the caller keeps them alive and unchanged while the buffer lives; no copy, no second array),
// else a copy (makeBuffer).
template <typename T>
Buffer shareOrCopyBuffer(Context& ctx, std::span<const T> values, const std::string& name) {
    if (!values.empty())
        if (Buffer b = Buffer::importHost(ctx, values.data(), values.size_bytes(), name); b.valid()) return b;
    return makeBuffer<T>(ctx, values, name);
}

}  // namespace amrvk::gpu
