#include "core/file_io.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>

#include "core/error.h"

namespace fs = std::filesystem;

namespace amrvk {

uint64_t fileSize(const fs::path& path) {
    std::error_code ec;
    auto status = fs::status(path, ec);
    AMRVK_CHECK(!ec && fs::exists(status), path.string(), ": no such file");
    AMRVK_CHECK(fs::is_regular_file(status), path.string(), ": not a regular file");
    uint64_t size = fs::file_size(path, ec);
    AMRVK_CHECK(!ec, path.string(), ": cannot read size (", ec.message(), ")");
    return size;
}

std::string readTextFile(const fs::path& path) {
    BinaryReader in(path);
    std::string text(in.size(), '\0');
    in.read(text.data(), text.size());
    return text;
}

BinaryReader::BinaryReader(const fs::path& path) : mPath(path) {
    mSize = fileSize(path);
    mFile = std::fopen(path.c_str(), "rb");
    AMRVK_CHECK(mFile, path.string(), ": cannot open (", std::strerror(errno), ")");
}

BinaryReader::~BinaryReader() {
    if (mFile) std::fclose(mFile);
}

void BinaryReader::seek(uint64_t offset) {
    AMRVK_CHECK(offset <= mSize, mPath.string(), ": offset ", offset, " is past the end (size ",
                mSize, " bytes)");
    AMRVK_CHECK(fseeko(mFile, static_cast<off_t>(offset), SEEK_SET) == 0, mPath.string(),
                ": cannot seek to byte ", offset);
    mOffset = offset;
}

void BinaryReader::requireBytes(uint64_t bytes) const {
    AMRVK_CHECK(bytes <= mSize - mOffset, mPath.string(), ": truncated at byte ", mSize, " (needed ",
                bytes - (mSize - mOffset), " more bytes at offset ", mOffset, ")");
}

void BinaryReader::read(void* dst, uint64_t bytes) {
    requireBytes(bytes);
    size_t got = std::fread(dst, 1, bytes, mFile);
    AMRVK_CHECK(got == bytes, mPath.string(), ": read error at byte ", mOffset + got);
    mOffset += bytes;
}

namespace {

// Temporary files being written, for the signal handler: fixed slots of NUL-terminated paths
// that the handler reads without locks or allocation (unlink is async-signal-safe).
constexpr int kTempSlots = 64;
constexpr size_t kTempPathBytes = 4096;
char gTempPaths[kTempSlots][kTempPathBytes];
enum SlotState : int { kFree, kClaimed, kReady };  // the handler unlinks kReady slots only
std::atomic<int> gTempState[kTempSlots];

int registerTemporary(const std::string& path) {
    if (path.size() >= kTempPathBytes) return -1;
    for (int i = 0; i < kTempSlots; ++i) {
        int expected = kFree;
        if (!gTempState[i].compare_exchange_strong(expected, kClaimed)) continue;
        std::memcpy(gTempPaths[i], path.c_str(), path.size() + 1);
        gTempState[i].store(kReady);
        return i;
    }
    return -1;  // more than kTempSlots at once: this one is left to the destructor
}

void unregisterTemporary(int& slot) {
    if (slot >= 0) gTempState[slot].store(kFree);
    slot = -1;
}

extern "C" void removeTemporariesAndExit(int sig) {
    for (int i = 0; i < kTempSlots; ++i)
        if (gTempState[i].load() == kReady) ::unlink(gTempPaths[i]);
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

}  // namespace

void removeTemporariesOnSignal() {
    for (int sig : {SIGINT, SIGTERM}) std::signal(sig, removeTemporariesAndExit);
}

AtomicFileWriter::AtomicFileWriter(fs::path path) : mPath(std::move(path)) {
    mTmpPath = mPath;
    mTmpPath += strCat(".tmp-", ::getpid());
    mSlot = registerTemporary(mTmpPath.string());
    mFile = std::fopen(mTmpPath.c_str(), "wb");
    if (!mFile) unregisterTemporary(mSlot);
    AMRVK_CHECK(mFile, mPath.string(), ": cannot write (", std::strerror(errno), ")");
}

AtomicFileWriter::~AtomicFileWriter() {
    if (mFile) std::fclose(mFile);
    if (!mCommitted) {
        std::error_code ec;
        fs::remove(mTmpPath, ec);
    }
    unregisterTemporary(mSlot);
}

void AtomicFileWriter::write(const void* src, uint64_t bytes) {
    AMRVK_CHECK(mFile, mPath.string(), ": write after finish");
    size_t put = std::fwrite(src, 1, bytes, mFile);
    AMRVK_CHECK(put == bytes, mPath.string(), ": write failed at byte ", mBytes + put, " (",
                std::strerror(errno), ")");
    mBytes += bytes;
}

void AtomicFileWriter::finish() {
    if (mFinished) return;
    AMRVK_CHECK(mFile, mPath.string(), ": finished twice");
    bool ok = std::fflush(mFile) == 0;
    ok = (std::fclose(mFile) == 0) && ok;
    mFile = nullptr;
    AMRVK_CHECK(ok, mPath.string(), ": write failed (", std::strerror(errno), ")");
    mFinished = true;
}

void AtomicFileWriter::commit() {
    AMRVK_CHECK(!mCommitted, mPath.string(), ": committed twice");
    finish();
    std::error_code ec;
    fs::rename(mTmpPath, mPath, ec);
    AMRVK_CHECK(!ec, mPath.string(), ": cannot rename temporary file into place (", ec.message(), ")");
    mCommitted = true;
    unregisterTemporary(mSlot);
}

void commitAll(const std::vector<std::unique_ptr<AtomicFileWriter>>& writers) {
    for (const auto& w : writers) w->finish();
    for (const auto& w : writers) w->commit();
}

void writeFileAtomic(const fs::path& path, const std::string& contents) {
    AtomicFileWriter w(path);
    w.write(contents.data(), contents.size());
    w.commit();
}

}  // namespace amrvk
