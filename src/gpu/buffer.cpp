#include "gpu/buffer.h"

#include <algorithm>
#include <utility>

#include "core/parallel.h"
#include "gpu/vk_check.h"

namespace amrvk::gpu {

Buffer::Buffer(Context& ctx, uint64_t bytes, MemoryKind kind, std::string name,
               VkBufferUsageFlags extraUsage)
    : mCtx(&ctx), mSize(bytes), mName(std::move(name)) {
    AMRVK_CHECK(bytes > 0, "buffer '", mName, "' has size 0");
    VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bci.size = bytes;
    bci.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT | extraUsage;
    bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    const VkResult created = vkCreateBuffer(ctx.device(), &bci, nullptr, &mBuffer);
    AMRVK_CHECK(created != VK_ERROR_OUT_OF_DEVICE_MEMORY && created != VK_ERROR_OUT_OF_HOST_MEMORY,
                "out of GPU memory creating '", mName, "' (", bytes, " bytes; ", ctx.memory().currentBytes(),
                " bytes already in use)");
    AMRVK_VK_CHECK(created);
    try {
        VkMemoryRequirements req{};
        vkGetBufferMemoryRequirements(ctx.device(), mBuffer, &req);
        uint32_t type = kind == MemoryKind::Device
                            ? ctx.findMemoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT)
                            : ctx.findMemoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT,
                                                 VK_MEMORY_PROPERTY_HOST_CACHED_BIT |
                                                     VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
        VkPhysicalDeviceMemoryProperties mp{};
        vkGetPhysicalDeviceMemoryProperties(ctx.physicalDevice(), &mp);
        VkMemoryPropertyFlags flags = mp.memoryTypes[type].propertyFlags;
        VkMemoryAllocateFlagsInfo flagsInfo{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
        flagsInfo.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
        VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, &flagsInfo};
        mai.allocationSize = req.size;
        mai.memoryTypeIndex = type;
        VkResult r = vkAllocateMemory(ctx.device(), &mai, nullptr, &mMemory);
        AMRVK_CHECK(r != VK_ERROR_OUT_OF_DEVICE_MEMORY && r != VK_ERROR_OUT_OF_HOST_MEMORY,
                    "out of GPU memory allocating '", mName, "' (", bytes, " bytes; ",
                    ctx.memory().currentBytes(), " bytes already in use)");
        AMRVK_VK_CHECK(r);
        AMRVK_VK_CHECK(vkBindBufferMemory(ctx.device(), mBuffer, mMemory, 0));
        if (flags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
            AMRVK_VK_CHECK(vkMapMemory(ctx.device(), mMemory, 0, VK_WHOLE_SIZE, 0, &mMapped));
            // lavapipe reports success with mmap's failure value when host memory runs out.
            AMRVK_CHECK(mMapped && mMapped != reinterpret_cast<void*>(intptr_t(-1)), "out of memory mapping buffer '",
                        mName, "' (", bytes, " bytes)");
            mCoherent = (flags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT) != 0;
        }
        VkBufferDeviceAddressInfo ai{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
        ai.buffer = mBuffer;
        mAddress = vkGetBufferDeviceAddress(ctx.device(), &ai);
        ctx.setDebugName(VK_OBJECT_TYPE_BUFFER, uint64_t(mBuffer), mName);
        ctx.memory().add(mName, req.size);
        mAllocated = req.size;
    } catch (...) {
        release();
        throw;
    }
}

Buffer Buffer::importHost(Context& ctx, const void* data, uint64_t bytes, std::string name) {
    Buffer b;
    const uint64_t align = ctx.hostImportAlignment();
    if (align == 0 || bytes == 0) return b;
    const uintptr_t at = reinterpret_cast<uintptr_t>(data), base = at / align * align;
    const uint64_t size = (at + bytes - base + align - 1) / align * align;  // whole pages
    void* pages = reinterpret_cast<void*>(base);  // read only: the buffer refuses writes
    const uint32_t types = ctx.hostPointerMemoryTypes(pages);
    if (types == 0) return b;
    b.mCtx = &ctx;
    b.mName = std::move(name);
    b.mSize = bytes;
    b.mOffset = at - base;
    b.mImported = true;
    VkExternalMemoryBufferCreateInfo external{VK_STRUCTURE_TYPE_EXTERNAL_MEMORY_BUFFER_CREATE_INFO};
    external.handleTypes = VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_ALLOCATION_BIT_EXT;
    VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, &external};
    bci.size = size;
    bci.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    if (vkCreateBuffer(ctx.device(), &bci, nullptr, &b.mBuffer) != VK_SUCCESS) return Buffer();
    VkMemoryRequirements req{};
    vkGetBufferMemoryRequirements(ctx.device(), b.mBuffer, &req);
    const uint32_t usable = req.memoryTypeBits & types;
    if (usable == 0 || req.size > size) return Buffer();  // b releases the VkBuffer
    VkImportMemoryHostPointerInfoEXT import{VK_STRUCTURE_TYPE_IMPORT_MEMORY_HOST_POINTER_INFO_EXT};
    import.handleType = VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_ALLOCATION_BIT_EXT;
    import.pHostPointer = pages;
    VkMemoryAllocateFlagsInfo flagsInfo{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO, &import};
    flagsInfo.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
    VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, &flagsInfo};
    mai.allocationSize = size;
    mai.memoryTypeIndex = ctx.findMemoryType(usable, 0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (vkAllocateMemory(ctx.device(), &mai, nullptr, &b.mMemory) != VK_SUCCESS) return Buffer();
    AMRVK_VK_CHECK(vkBindBufferMemory(ctx.device(), b.mBuffer, b.mMemory, 0));
    VkBufferDeviceAddressInfo ai{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    ai.buffer = b.mBuffer;
    b.mAddress = vkGetBufferDeviceAddress(ctx.device(), &ai) + b.mOffset;
    ctx.setDebugName(VK_OBJECT_TYPE_BUFFER, uint64_t(b.mBuffer), b.mName);
    ctx.memory().add(b.mName, size);
    b.mAllocated = size;
    return b;
}

Buffer::~Buffer() { release(); }

void Buffer::release() {
    if (!mCtx) return;
    if (mBuffer) vkDestroyBuffer(mCtx->device(), mBuffer, nullptr);
    if (mMemory) vkFreeMemory(mCtx->device(), mMemory, nullptr);
    if (mAllocated) mCtx->memory().remove(mName, mAllocated);
    mAllocated = 0;
    mBuffer = VK_NULL_HANDLE;
    mMemory = VK_NULL_HANDLE;
    mMapped = nullptr;
    mOffset = 0;
    mImported = false;
    mCtx = nullptr;
}

Buffer::Buffer(Buffer&& o) noexcept { *this = std::move(o); }

Buffer& Buffer::operator=(Buffer&& o) noexcept {
    if (this != &o) {
        release();
        mCtx = std::exchange(o.mCtx, nullptr);
        mBuffer = std::exchange(o.mBuffer, VK_NULL_HANDLE);
        mMemory = std::exchange(o.mMemory, VK_NULL_HANDLE);
        mAddress = std::exchange(o.mAddress, 0);
        mSize = std::exchange(o.mSize, 0);
        mAllocated = std::exchange(o.mAllocated, 0);
        mOffset = std::exchange(o.mOffset, 0);
        mImported = std::exchange(o.mImported, false);
        mMapped = std::exchange(o.mMapped, nullptr);
        mCoherent = o.mCoherent;
        mName = std::move(o.mName);
    }
    return *this;
}

void Buffer::upload(const void* data, uint64_t bytes, uint64_t offset) {
    AMRVK_CHECK(offset + bytes <= mSize, "upload of ", bytes, " bytes at ", offset, " overflows buffer '",
                mName, "' of ", mSize, " bytes");
    AMRVK_CHECK(!mImported, "buffer '", mName, "' shares host memory with its source: it is read-only");
    if (bytes == 0) return;
    if (mMapped) {
        parallelCopy(static_cast<char*>(mMapped) + offset, data, bytes);  // large: on every core
        if (!mCoherent) {
            VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
            range.memory = mMemory;
            range.size = VK_WHOLE_SIZE;
            AMRVK_VK_CHECK(vkFlushMappedMemoryRanges(mCtx->device(), 1, &range));
        }
        return;
    }
    // Through one staging buffer of at most kStagingBytes, so a 4 GB upload (the values of 10^9
    // cells) takes 64 MiB of host memory beside the data, not another 4 GB.
    uploadStaged(data, bytes, offset, kStagingBytes);
}

void Buffer::uploadStaged(const void* data, uint64_t bytes, uint64_t offset, uint64_t chunkBytes) {
    AMRVK_CHECK(offset + bytes <= mSize && chunkBytes > 0, "staged upload of ", bytes, " bytes at ", offset,
                " overflows buffer '", mName, "' of ", mSize, " bytes");
    AMRVK_CHECK(!mImported, "buffer '", mName, "' shares host memory with its source: it is read-only");
    if (bytes == 0) return;
    const uint64_t chunk = std::min(bytes, chunkBytes);
    Buffer staging(*mCtx, chunk, MemoryKind::HostRead, mName + ".staging");
    for (uint64_t done = 0; done < bytes; done += chunk) {
        const uint64_t n = std::min(chunk, bytes - done);
        staging.upload(static_cast<const char*>(data) + done, n);
        mCtx->submitAndWait([&](VkCommandBuffer cmd) {
            VkBufferCopy copy{0, offset + done, n};
            vkCmdCopyBuffer(cmd, staging.handle(), mBuffer, 1, &copy);
        });
    }
}

void Buffer::download(void* data, uint64_t bytes, uint64_t offset) const {
    AMRVK_CHECK(offset <= mSize && bytes <= mSize - offset, "download of ", bytes, " bytes at ", offset,
                " from buffer '", mName, "' of ", mSize, " bytes");
    if (bytes == 0) return;
    if (mMapped) {
        if (!mCoherent) {
            VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
            range.memory = mMemory;
            range.size = VK_WHOLE_SIZE;
            AMRVK_VK_CHECK(vkInvalidateMappedMemoryRanges(mCtx->device(), 1, &range));
        }
        std::memcpy(data, static_cast<const char*>(mMapped) + offset, bytes);
        return;
    }
    downloadStaged(data, bytes, kStagingBytes, offset);
}

void Buffer::downloadStaged(void* data, uint64_t bytes, uint64_t chunkBytes, uint64_t offset) const {
    AMRVK_CHECK(offset <= mSize && bytes <= mSize - offset && chunkBytes > 0, "staged download of ", bytes,
                " bytes at ", offset, " from buffer '", mName, "' of ", mSize, " bytes");
    if (bytes == 0) return;
    const uint64_t chunk = std::min(bytes, chunkBytes);
    Buffer staging(*mCtx, chunk, MemoryKind::HostRead, mName + ".readback");
    for (uint64_t done = 0; done < bytes; done += chunk) {
        const uint64_t n = std::min(chunk, bytes - done);
        mCtx->submitAndWait([&](VkCommandBuffer cmd) {
            VkBufferCopy copy{mOffset + offset + done, 0, n};
            vkCmdCopyBuffer(cmd, mBuffer, staging.handle(), 1, &copy);
        });
        staging.download(static_cast<char*>(data) + done, n);
    }
}

void Buffer::fillZero() {
    AMRVK_CHECK(!mImported, "buffer '", mName, "' shares host memory with its source: it is read-only");
    mCtx->submitAndWait([&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, mBuffer, 0, VK_WHOLE_SIZE, 0); });
}

}  // namespace amrvk::gpu
