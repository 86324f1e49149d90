// Hostile input (robustness issue): each test is named after a defect a hostile-input campaign
// found, rebuilds its input and checks the one-line error that replaced the crash, hang or lie.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <future>

#include "accel/bricks.h"
#include "accel/bricks_file.h"
#include "amr/readers.h"
#include "core/error.h"
#include "core/stats.h"
#include "core/strings.h"
#include "scene/structure_config.h"
#include "scene/volume.h"
#include "test_data.h"

namespace fs = std::filesystem;
using namespace amrvk;
using namespace amrvk::test;

namespace {

amr::Model oneCellModel() {
    amr::Model m;
    m.source = "one";
    m.cells = {{{0, 0, 0}, 0}};
    m.fields = {{"v", {1.0f}}};
    return m;
}

// A .bricks record: size, lower corner, level, then the cell ids.
std::string brickRecord(glm::ivec3 size, glm::ivec3 lower, int level, const std::vector<int32_t>& ids) {
    const int32_t header[7] = {size.x, size.y, size.z, lower.x, lower.y, lower.z, level};
    std::string out(reinterpret_cast<const char*>(header), sizeof header);
    return out.append(reinterpret_cast<const char*>(ids.data()), ids.size() * sizeof(int32_t));
}

// Runs f, which must throw amrvk::Error within 10 s; a FIFO it blocks on is opened for writing
// (which releases the reader) so that a regression fails the test instead of hanging it.
std::string errorWithin10s(const std::function<void()>& f, const std::vector<fs::path>& fifos) {
    auto pending = std::async(std::launch::async, [&] { return errorOf(f); });
    if (pending.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
        ADD_FAILURE() << "blocked for 10 s on a FIFO";
        for (const fs::path& p : fifos) close(open(p.c_str(), O_WRONLY | O_NONBLOCK));
    }
    return pending.get();
}

}  // namespace

TEST(HostileInput, BrickWhoseCellCountWrapsIsRejected) {
    // 2^21 x 2^21 x 2^22 cells = 2^64: the count wrapped to 0, the brick was accepted beside a
    // valid one and the ABR value ranges read out of bounds.
    const fs::path file = scratchDir() / "wrap.bricks";
    writeAll(file, brickRecord({1, 1, 1}, {0, 0, 0}, 0, {0}) +
                       brickRecord({1 << 21, 1 << 21, 1 << 22}, {0, 0, 0}, 0, {}));
    expectError([&] { accel::readBricksFile(file, oneCellModel()); },
                {file.string(), "brick at byte 32: 2097152 x 2097152 x 4194304 overflows 64 bits"});
}

TEST(HostileInput, BricksFileClaimingMoreCellsThanItHoldsFailsBeforeAllocating) {
    // 40 bytes claiming 1024^3 cells: 4 GB were allocated (16 s) before "truncated".
    const fs::path file = scratchDir() / "big.bricks";
    writeAll(file, brickRecord({1024, 1024, 1024}, {0, 0, 0}, 0, {0, 0, 0}));
    const uint64_t peakBefore = peakResidentBytes();
    expectError([&] { accel::readBricksFile(file, oneCellModel()); }, {file.string(), "truncated at byte 40"});
    EXPECT_LT(peakResidentBytes(), peakBefore + (uint64_t{512} << 20)) << "allocated before checking the size";
}

TEST(HostileInput, FifoInputFailsInsteadOfBlocking) {
    // Format detection opened its input to peek at magic bytes before checking it was a regular
    // file: a FIFO (no writer) blocked forever.
    const fs::path dir = scratchDir();
    fs::create_directories(dir / "plt");
    const std::vector<fs::path> fifos = {dir / "data", dir / "data.hdf5", dir / "plt" / "Header", dir / "d.cells"};
    for (const fs::path& p : fifos) ASSERT_EQ(mkfifo(p.c_str(), 0600), 0) << p;
    for (const fs::path& p : {dir / "data", dir / "data.hdf5", dir / "plt", dir / "d.cells"}) {
        SCOPED_TRACE(p.string());
        const std::string msg = errorWithin10s([&] { amr::readModel(p, {}); }, fifos);
        expectContains(msg, "not a regular file");
    }
}

TEST(HostileInput, DomainSpanningMoreThan2To31IsRejectedNotWrapped) {
    // Two aligned cells 2^32 - 2 voxels apart: valid cells, but the GPU's local coordinates
    // (voxel - lower corner of the data) are int32; they used to wrap and render with exit 0.
    amr::Model m;
    m.source = "far";
    m.cells = {{{INT32_MIN, 0, 0}, 0}, {{INT32_MAX - 1, 0, 0}, 0}};
    m.fields = {{"v", {1.0f, 2.0f}}};
    amr::validate(m);
    expectError([&] { scene::makeVolume(m); }, {"far: the data spans 4294967295 finest cells along axis x, more than 2^31"});
}

TEST(HostileInput, ErrorMessagesEscapeControlBytes) {
    const char bytes[] = "name\nwith\0nul\x1b[2J\r\t\x7f end";
    const std::string raw(bytes, sizeof bytes - 1);
    const std::string msg = Error(raw).what();
    EXPECT_EQ(msg, "name\\nwith\\x00nul\\x1b[2J\\r\\t\\x7f end");
    EXPECT_EQ(Error("plain text: 1 < 2").what(), std::string("plain text: 1 < 2"));
}

// A message quoting a huge name or value stays short: its start and end kept around the count
// (issue 52, point 1: a 20,000-digit number made a 20 KB "one-line" error).
TEST(HostileInput, ErrorMessagesAreBounded) {
    const std::string huge = "file.h5: '" + std::string(100000, '7') + "' is not an index in [-9, 9]";
    const std::string msg = Error(huge).what();
    EXPECT_LE(msg.size(), 1100u);
    EXPECT_EQ(msg.rfind("file.h5: '777", 0), 0u);
    EXPECT_NE(msg.find("is not an index in [-9, 9]"), std::string::npos);
    EXPECT_NE(msg.find("[... " + std::to_string(huge.size() - 1024) + " bytes ...]"), std::string::npos);
    const std::string exact(1024, 'a');
    EXPECT_EQ(Error(exact).what(), exact);  // up to 1 KiB as given
    EXPECT_EQ(elide("short"), "short");
    EXPECT_EQ(elide(std::string(50, 'x'), 4), "xxxx... (50 bytes)");
}

TEST(HostileInput, SparseDataGetsATraversalThatFitsIt) {
    // 20,000 finest cells scattered over a 2^30-wide box: grid-dda (the old default) ran for over
    // 300 s; the fitted default is abr. AMR data that tiles its domain keeps grid-dda.
    amr::Model sparse;
    sparse.source = "scatter";
    uint64_t x = 1;
    for (int i = 0; i < 20000; ++i) {
        glm::ivec3 p;
        for (int a = 0; a < 3; ++a) p[a] = int((x = x * 6364136223846793005u + 1442695040888963407u) >> 34);
        sparse.cells.push_back({p, 0});
    }
    std::string why;
    const amr::ModelSummary s = amr::summarize(sparse);
    EXPECT_EQ(scene::fittingTraversal(s.leafVolume, s.bounds.volume(), &why), scene::TraversalKind::Abr);
    expectContains(why, "traversal abr: the cells fill");
    const amr::Model cloud = amr::readModel(fs::path(AMRVK_SOURCE_DIR) / "assets/samples/cloud.cells", {});
    const amr::ModelSummary c = amr::summarize(cloud);
    why.clear();
    EXPECT_EQ(scene::fittingTraversal(c.leafVolume, c.bounds.volume(), &why), scene::TraversalKind::GridDda);
    EXPECT_EQ(why, "") << "nothing to say for the default";
    // The threshold itself: just above and just below.
    EXPECT_EQ(scene::fittingTraversal(1.001e-3, 1.0), scene::TraversalKind::GridDda);
    EXPECT_EQ(scene::fittingTraversal(0.999e-3, 1.0), scene::TraversalKind::Abr);
}
