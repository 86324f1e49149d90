// Buffers: upload/download round trips, device addresses, and memory accounting per resource.
#include <algorithm>
#include <numeric>

#include "core/error.h"
#include "gpu/buffer.h"
#include "gpu_fixture.h"

using namespace amrvk;

class Buffer : public test::GpuTest {};

TEST_F(Buffer, RoundTripAndAddresses) {
    std::vector<uint32_t> data(100000);
    std::iota(data.begin(), data.end(), 7u);
    gpu::Buffer b = gpu::makeBuffer<uint32_t>(ctx(), data, "roundTrip");
    EXPECT_NE(b.address(), 0u);
    EXPECT_EQ(b.download<uint32_t>(), data);
    b.fillZero();
    for (uint32_t v : b.download<uint32_t>()) ASSERT_EQ(v, 0u);
    EXPECT_THROW(gpu::Buffer(ctx(), 0, gpu::MemoryKind::Device, "empty"), Error);
    EXPECT_THROW(b.upload(data.data(), data.size() * 4 + 4), Error);
}

TEST_F(Buffer, MemoryIsAccountedPerResource) {
    auto& mem = ctx().memory();
    const uint64_t before = mem.currentBytes();
    {
        gpu::Buffer a(ctx(), 1 << 20, gpu::MemoryKind::Device, "accountingA");
        gpu::Buffer b(ctx(), 1 << 18, gpu::MemoryKind::Device, "accountingB");
        EXPECT_GE(mem.currentBytes(), before + (1 << 20) + (1 << 18));
        EXPECT_GE(mem.perResource().at("accountingA").current, uint64_t(1) << 20);
        gpu::Buffer moved = std::move(a);  // moving keeps one owner and one count
        EXPECT_GE(mem.perResource().at("accountingA").current, uint64_t(1) << 20);
    }
    EXPECT_EQ(mem.currentBytes(), before);
    EXPECT_EQ(mem.perResource().at("accountingA").current, 0u);
    EXPECT_GE(mem.perResource().at("accountingA").peak, uint64_t(1) << 20);
    EXPECT_GE(mem.peakBytes(), before + (1 << 20) + (1 << 18));
}

// Unmapped (device-local) buffers are filled and read through one staging buffer, a chunk at a
// time, so a 4 GB upload needs 64 MiB beside it: every chunk lands at its offset, the last one short.
TEST_F(Buffer, StagedCopiesGoChunkByChunk) {
    std::vector<uint32_t> data(100003);
    std::iota(data.begin(), data.end(), 11u);
    gpu::Buffer b(ctx(), (data.size() + 5) * sizeof(uint32_t), gpu::MemoryKind::Device, "staged");
    b.fillZero();
    b.uploadStaged(data.data(), data.size() * sizeof(uint32_t), 5 * sizeof(uint32_t), 4096);
    std::vector<uint32_t> back(data.size() + 5);
    b.downloadStaged(back.data(), back.size() * sizeof(uint32_t), 1000);
    for (size_t i = 0; i < 5; ++i) EXPECT_EQ(back[i], 0u);
    EXPECT_TRUE(std::equal(data.begin(), data.end(), back.begin() + 5));
    EXPECT_THROW(b.uploadStaged(data.data(), data.size() * sizeof(uint32_t), 24, 4096), Error);
    EXPECT_EQ(gpu::kStagingBytes, uint64_t{64} << 20);
}
