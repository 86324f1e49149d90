// Buffers: upload/download round trips, device addresses, and memory accounting per resource.
#include <algorithm>
#include <numeric>
#include <span>

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
// time, so a 4 GB upload needs 64 MiB beside it: every chunk lands at its offset, the last one
// short; a part is read back from its offset.
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
    // A part read back from an offset, staged and plainly; past the end is an error.
    std::vector<uint32_t> part(7), plain(7);
    b.downloadStaged(part.data(), part.size() * sizeof(uint32_t), 12, (5 + 100) * sizeof(uint32_t));
    b.download(plain.data(), plain.size() * sizeof(uint32_t), (5 + 100) * sizeof(uint32_t));
    EXPECT_TRUE(std::equal(part.begin(), part.end(), data.begin() + 100));
    EXPECT_EQ(part, plain);
    EXPECT_THROW(b.download(part.data(), part.size() * sizeof(uint32_t), b.size() - 8), Error);
    EXPECT_EQ(gpu::kStagingBytes, uint64_t{64} << 20);
}

// On a CPU device (lavapipe) a large read-only array is handed to the device where it lies: the
// device reads the caller's memory (a later host write shows through), at the caller's address
// inside the imported pages (an unaligned start), refuses writes, and counts the whole pages. A
// context that disables the import copies instead, with the same content.
TEST_F(Buffer, HostMemoryIsSharedOnACpuDevice) {
    if (ctx().deviceReport().type != "CPU") GTEST_SKIP() << "host memory is imported on CPU devices only";
    const uint64_t align = ctx().hostImportAlignment();
    ASSERT_GT(align, 0u) << "lavapipe offers VK_EXT_external_memory_host";
    std::vector<uint32_t> data(100003);
    std::iota(data.begin(), data.end(), 5u);
    const std::span<const uint32_t> part(data.data() + 3, 100000);  // not page-aligned
    gpu::Buffer b = gpu::Buffer::importHost(ctx(), part.data(), part.size_bytes(), "imported");
    ASSERT_TRUE(b.valid());
    EXPECT_TRUE(b.imported());
    EXPECT_EQ(b.size(), part.size_bytes());
    EXPECT_EQ(b.download<uint32_t>(), std::vector<uint32_t>(part.begin(), part.end()));  // a device copy
    data[3 + 777] = 424242u;  // shared, not copied: the device sees the host's write
    EXPECT_EQ(b.download<uint32_t>()[777], 424242u);
    EXPECT_THROW(b.upload(part.data(), 16), Error);
    EXPECT_THROW(b.fillZero(), Error);
    const uint64_t counted = ctx().memory().perResource().at("imported").current;
    EXPECT_GE(counted, part.size_bytes());
    EXPECT_EQ(counted % align, 0u);
    EXPECT_TRUE(gpu::shareOrCopyBuffer<uint32_t>(ctx(), part, "sharedOrCopied").imported());

    gpu::ContextOptions o;
    o.validation = true;
    o.disableHostImport = true;
    gpu::Context copying(o);
    EXPECT_EQ(copying.hostImportAlignment(), 0u);
    const gpu::Buffer c = gpu::shareOrCopyBuffer<uint32_t>(copying, part, "copied");
    EXPECT_FALSE(c.imported());
    EXPECT_EQ(c.download<uint32_t>(), std::vector<uint32_t>(part.begin(), part.end()));
    EXPECT_EQ(copying.validationErrors(), 0u) << copying.lastValidationMessage();
}
