#include "gpu/acceleration_structure.h"

#include <algorithm>
#include <utility>

#include "gpu/compute_pipeline.h"
#include "gpu/vk_check.h"

namespace amrvk::gpu {

namespace {

constexpr uint64_t kAabbBytes = sizeof(VkAabbPositionsKHR);  // 6 floats

template <typename Fn>
Fn deviceFunction(VkDevice device, const char* name) {
    auto fn = reinterpret_cast<Fn>(vkGetDeviceProcAddr(device, name));
    AMRVK_CHECK(fn, name, " is not available although VK_KHR_acceleration_structure is enabled");
    return fn;
}

VkAccelerationStructureGeometryKHR aabbGeometry(VkDeviceAddress data) {
    VkAccelerationStructureGeometryKHR g{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
    g.geometryType = VK_GEOMETRY_TYPE_AABBS_KHR;
    g.geometry.aabbs = {VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_AABBS_DATA_KHR};
    g.geometry.aabbs.data.deviceAddress = data;
    g.geometry.aabbs.stride = kAabbBytes;
    g.flags = 0;  // not opaque: every AABB candidate goes back to the shader
    return g;
}

VkAccelerationStructureGeometryKHR instanceGeometry(VkDeviceAddress data) {
    VkAccelerationStructureGeometryKHR g{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
    g.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
    g.geometry.instances = {VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR};
    g.geometry.instances.arrayOfPointers = VK_FALSE;
    g.geometry.instances.data.deviceAddress = data;
    g.flags = 0;
    return g;
}

VkAccelerationStructureBuildGeometryInfoKHR buildInfo(VkAccelerationStructureTypeKHR type,
                                                      const VkAccelerationStructureGeometryKHR* geometry) {
    VkAccelerationStructureBuildGeometryInfoKHR info{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
    info.type = type;
    info.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
    info.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
    info.geometryCount = 1;
    info.pGeometries = geometry;
    return info;
}

}  // namespace

AabbAccelerationStructure::AabbAccelerationStructure(Context& ctx, uint32_t count, std::string name)
    : mCtx(&ctx), mCount(count), mName(std::move(name)) {
    AMRVK_CHECK(ctx.hasRayQuery(), "acceleration structure '", mName, "': device '", ctx.deviceReport().name,
                "' has no VK_KHR_ray_query + VK_KHR_acceleration_structure (ray queries unavailable)");
    try {
        VkDevice dev = ctx.device();
        mFn.create = deviceFunction<PFN_vkCreateAccelerationStructureKHR>(dev, "vkCreateAccelerationStructureKHR");
        mFn.destroy = deviceFunction<PFN_vkDestroyAccelerationStructureKHR>(dev, "vkDestroyAccelerationStructureKHR");
        mFn.buildSizes = deviceFunction<PFN_vkGetAccelerationStructureBuildSizesKHR>(
            dev, "vkGetAccelerationStructureBuildSizesKHR");
        mFn.address = deviceFunction<PFN_vkGetAccelerationStructureDeviceAddressKHR>(
            dev, "vkGetAccelerationStructureDeviceAddressKHR");
        mFn.cmdBuild = deviceFunction<PFN_vkCmdBuildAccelerationStructuresKHR>(dev, "vkCmdBuildAccelerationStructuresKHR");

        VkPhysicalDeviceAccelerationStructurePropertiesKHR asProps{
            VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
        VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &asProps};
        vkGetPhysicalDeviceProperties2(ctx.physicalDevice(), &props);
        AMRVK_CHECK(count <= asProps.maxPrimitiveCount, "acceleration structure '", mName, "': ", count,
                    " boxes exceed the device limit of ", asProps.maxPrimitiveCount, " primitives");
        const uint64_t scratchAlign = std::max<uint64_t>(asProps.minAccelerationStructureScratchOffsetAlignment, 1);

        // Sizes for the worst case (count boxes, one instance); rebuilds reuse the same memory.
        auto buildSizes = [&](VkAccelerationStructureTypeKHR type, VkAccelerationStructureGeometryKHR g,
                              uint32_t primitives) {
            VkAccelerationStructureBuildSizesInfoKHR sizes{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
            const VkAccelerationStructureBuildGeometryInfoKHR info = buildInfo(type, &g);
            mFn.buildSizes(dev, VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &info, &primitives, &sizes);
            return sizes;
        };
        VkAccelerationStructureBuildSizesInfoKHR blasSizes{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
        if (count > 0) blasSizes = buildSizes(VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, aabbGeometry(0), count);
        const auto tlasSizes = buildSizes(VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR, instanceGeometry(0), count > 0);

        auto createStructure = [&](Buffer& storage, uint64_t bytes, VkAccelerationStructureTypeKHR type,
                                   const std::string& suffix) {
            storage = Buffer(ctx, std::max<uint64_t>(bytes, 256), MemoryKind::Device, mName + suffix,
                             VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR);
            VkAccelerationStructureCreateInfoKHR ci{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR};
            ci.buffer = storage.handle();
            ci.offset = 0;
            ci.size = storage.size();
            ci.type = type;
            VkAccelerationStructureKHR as = VK_NULL_HANDLE;
            AMRVK_VK_CHECK(mFn.create(dev, &ci, nullptr, &as));
            ctx.setDebugName(VK_OBJECT_TYPE_ACCELERATION_STRUCTURE_KHR, uint64_t(as), mName + suffix);
            return as;
        };
        auto structureAddress = [&](VkAccelerationStructureKHR as) {
            VkAccelerationStructureDeviceAddressInfoKHR ai{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR};
            ai.accelerationStructure = as;
            return mFn.address(dev, &ai);
        };

        // One scratch buffer serves both builds (they are serialised by a barrier).
        const uint64_t scratchBytes = std::max(blasSizes.buildScratchSize, tlasSizes.buildScratchSize);
        mScratch = Buffer(ctx, std::max<uint64_t>(scratchBytes, 16) + scratchAlign, MemoryKind::Device,
                          mName + ".scratch");
        mScratchAddress = (mScratch.address() + scratchAlign - 1) / scratchAlign * scratchAlign;

        VkAccelerationStructureInstanceKHR instance{};
        if (count > 0) {
            mBlas = createStructure(mBlasBuffer, blasSizes.accelerationStructureSize,
                                    VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, ".blas");
            instance.transform.matrix[0][0] = instance.transform.matrix[1][1] = instance.transform.matrix[2][2] = 1.0f;
            instance.instanceCustomIndex = 0;
            instance.mask = 0xFF;
            instance.instanceShaderBindingTableRecordOffset = 0;
            instance.flags = 0;  // no force-opaque
            instance.accelerationStructureReference = structureAddress(mBlas);
        }
        mInstances = Buffer(ctx, sizeof instance, MemoryKind::Device, mName + ".instances",
                            VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR);
        mInstances.upload(&instance, sizeof instance);

        mTlas = createStructure(mTlasBuffer, tlasSizes.accelerationStructureSize,
                                VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR, ".tlas");
        mTlasAddress = structureAddress(mTlas);
    } catch (...) {
        release();
        throw;
    }
}

AabbAccelerationStructure::~AabbAccelerationStructure() { release(); }

void AabbAccelerationStructure::release() {
    if (!mCtx) return;
    if (mTlas) mFn.destroy(mCtx->device(), mTlas, nullptr);
    if (mBlas) mFn.destroy(mCtx->device(), mBlas, nullptr);
    mTlas = mBlas = VK_NULL_HANDLE;
    mTlasAddress = mScratchAddress = 0;
    mBlasBuffer = Buffer();
    mTlasBuffer = Buffer();
    mScratch = Buffer();
    mInstances = Buffer();
    mCtx = nullptr;
}

AabbAccelerationStructure::AabbAccelerationStructure(AabbAccelerationStructure&& o) noexcept { *this = std::move(o); }

AabbAccelerationStructure& AabbAccelerationStructure::operator=(AabbAccelerationStructure&& o) noexcept {
    if (this != &o) {
        release();
        mCtx = std::exchange(o.mCtx, nullptr);
        mFn = o.mFn;
        mCount = std::exchange(o.mCount, 0);
        mName = std::move(o.mName);
        mBlas = std::exchange(o.mBlas, VK_NULL_HANDLE);
        mTlas = std::exchange(o.mTlas, VK_NULL_HANDLE);
        mBlasBuffer = std::move(o.mBlasBuffer);
        mTlasBuffer = std::move(o.mTlasBuffer);
        mScratch = std::move(o.mScratch);
        mInstances = std::move(o.mInstances);
        mScratchAddress = std::exchange(o.mScratchAddress, 0);
        mTlasAddress = std::exchange(o.mTlasAddress, 0);
    }
    return *this;
}

uint64_t AabbAccelerationStructure::memoryBytes() const {
    return mBlasBuffer.allocatedBytes() + mTlasBuffer.allocatedBytes() + mScratch.allocatedBytes() +
           mInstances.allocatedBytes();
}

void AabbAccelerationStructure::build(VkCommandBuffer cmd, const Buffer& aabbBuffer) {
    AMRVK_CHECK(valid(), "build() of an empty (default-constructed or moved-from) acceleration structure");
    constexpr VkPipelineStageFlags2 kBuild = VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR;
    constexpr VkAccessFlags2 kAsRead = VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR;
    constexpr VkAccessFlags2 kAsWrite = VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;

    AMRVK_CHECK(mCount == 0 || (aabbBuffer.valid() && aabbBuffer.size() >= uint64_t(mCount) * kAabbBytes),
                "acceleration structure '", mName, "': AABB buffer '", aabbBuffer.name(), "' holds ",
                aabbBuffer.size(), " bytes, ", uint64_t(mCount) * kAabbBytes, " needed for ", mCount, " boxes");

    // Inputs written by transfers or compute shaders, earlier builds (scratch, structures) and
    // earlier ray queries (write-after-read) all complete before this build.
    memoryBarrier(cmd,
                  VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | kBuild,
                  VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_WRITE_BIT | kAsWrite, kBuild,
                  VK_ACCESS_2_SHADER_READ_BIT | kAsRead | kAsWrite);

    auto record = [&](VkAccelerationStructureTypeKHR type, VkAccelerationStructureGeometryKHR g,
                      VkAccelerationStructureKHR dst, uint32_t primitives) {
        VkAccelerationStructureBuildGeometryInfoKHR info = buildInfo(type, &g);
        info.dstAccelerationStructure = dst;
        info.scratchData.deviceAddress = mScratchAddress;
        const VkAccelerationStructureBuildRangeInfoKHR range{primitives, 0, 0, 0};
        const VkAccelerationStructureBuildRangeInfoKHR* ranges = &range;
        mFn.cmdBuild(cmd, 1, &info, &ranges);
    };
    if (mCount > 0) {
        record(VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, aabbGeometry(aabbBuffer.address()), mBlas, mCount);
        // The top level reads the bottom level and reuses the scratch memory.
        memoryBarrier(cmd, kBuild, kAsWrite, kBuild, kAsRead | kAsWrite);
    }
    record(VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR, instanceGeometry(mInstances.address()), mTlas, mCount > 0);

    memoryBarrier(cmd, kBuild, kAsWrite, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, kAsRead);
}

uint64_t maxAccelerationPrimitives(const Context& ctx) {
    if (!ctx.hasRayQuery()) return 0;
    VkPhysicalDeviceAccelerationStructurePropertiesKHR asProps{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &asProps};
    vkGetPhysicalDeviceProperties2(ctx.physicalDevice(), &props);
    return asProps.maxPrimitiveCount;
}

}  // namespace amrvk::gpu
