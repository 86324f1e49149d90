#include "core/file_io.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <algorithm>
#include <map>
#include <mutex>
#include <optional>
#include <thread>

#include "core/checked_size.h"
#include "core/error.h"
#include "core/parallel.h"

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
    checkAllocation(in.size(), path.string());
    std::string text(in.size(), '\0');
    in.read(text.data(), text.size());
    return text;
}

BinaryReader::BinaryReader(const fs::path& path) : mPath(path) {
    mSize = fileSize(path);
    mFile = std::fopen(path.c_str(), "rb");
    AMRVK_CHECK(mFile, path.string(), ": cannot open (", std::strerror(errno), ")");
    noteInputFile(path);
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

void adviseHugePages(void* p, size_t bytes) {
    if (bytes < kHugePageAdviceBytes) return;
    constexpr uintptr_t kHuge = uintptr_t{2} << 20;
    const uintptr_t lo = (reinterpret_cast<uintptr_t>(p) + kHuge - 1) & ~(kHuge - 1);
    const uintptr_t hi = (reinterpret_cast<uintptr_t>(p) + bytes) & ~(kHuge - 1);
    if (hi > lo) madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_HUGEPAGE);  // advice: failure is harmless
}

void prefaultForWrite(void* p, size_t bytes) {
#ifdef MADV_POPULATE_WRITE
    const uintptr_t page = uintptr_t(sysconf(_SC_PAGESIZE));
    const uintptr_t lo = (reinterpret_cast<uintptr_t>(p) + page - 1) & ~(page - 1);
    const uintptr_t hi = (reinterpret_cast<uintptr_t>(p) + bytes) & ~(page - 1);
    if (hi > lo) madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_POPULATE_WRITE);  // failure is harmless
#else
    (void)p;
    (void)bytes;
#endif
}

void prepareStorage(void* p, size_t bytes) {
    if (bytes >= kHugePageAdviceBytes) parallelZero(p, bytes);
}

// pread until `bytes` are in; returns how many arrived before an error or the end of the file.
static uint64_t preadFully(int fd, void* dst, uint64_t bytes, uint64_t offset) {
    uint64_t at = 0;
    while (at < bytes) {
        const ssize_t got = pread(fd, static_cast<char*>(dst) + at, size_t(bytes - at), off_t(offset + at));
        if (got <= 0) break;
        at += uint64_t(got);
    }
    return at;
}

void BinaryReader::readAt(uint64_t offset, void* dst, uint64_t bytes) const {
    const uint64_t got = preadFully(fileno(mFile), dst, bytes, offset);
    AMRVK_CHECK(got == bytes, mPath.string(), ": read error at byte ", offset + got);
}

void BinaryReader::readInChunks(void* dst, uint64_t bytes) {
    // Fixed 8 MiB chunks at explicit offsets (pread), each written (and its pages first touched)
    // by whichever core takes it; the FILE's position and buffer are reset past them afterwards.
    constexpr uint64_t kChunk = uint64_t{8} << 20;
    const int fd = fileno(mFile);
    const uint64_t chunks = (bytes + kChunk - 1) / kChunk;
    std::atomic<uint64_t> failedAt{UINT64_MAX};
    parallelFor(0, size_t(chunks), [&](size_t k) {
        const uint64_t at = uint64_t(k) * kChunk, n = std::min(bytes, at + kChunk) - at;
        const uint64_t got = preadFully(fd, static_cast<char*>(dst) + at, n, mOffset + at);
        if (got == n) return;
        uint64_t expected = UINT64_MAX;
        while (at + got < expected && !failedAt.compare_exchange_weak(expected, at + got)) {
        }
    });
    AMRVK_CHECK(failedAt.load() == UINT64_MAX, mPath.string(), ": read error at byte ", mOffset + failedAt.load());
    seek(mOffset + bytes);
}

void BinaryReader::read(void* dst, uint64_t bytes) {
    requireBytes(bytes);
    if (bytes >= kParallelReadBytes) return readInChunks(dst, bytes);
    size_t got = std::fread(dst, 1, bytes, mFile);
    AMRVK_CHECK(got == bytes, mPath.string(), ": read error at byte ", mOffset + got);
    mOffset += bytes;
}

namespace {

// A temporary beside `target`: its name + ".tmp-" + suffix, the name cut so that the whole fits in
// NAME_MAX (255 bytes): a valid 250-byte output name is not refused for its temporary's sake.
std::string temporarySibling(const fs::path& target, const std::string& suffix) {
    constexpr size_t kNameMax = 255;
    const std::string tail = ".tmp-" + suffix;
    std::string name = target.filename().string();
    if (name.size() + tail.size() > kNameMax) name.resize(kNameMax - tail.size());
    return (target.parent_path() / (name + tail)).string();
}

// Temporary files being written, for the signal handler: fixed slots of NUL-terminated paths
// that the handler reads without locks or allocation (unlink is async-signal-safe). BSS: pages
// are touched only when used.
constexpr int kTempSlots = 1024;
constexpr size_t kTempPathBytes = 4096;
char gTempPaths[kTempSlots][kTempPathBytes];
enum SlotState : int { kFree, kClaimed, kReady };  // the handler unlinks kReady slots only
std::atomic<int> gTempState[kTempSlots];

int registerTemporary(const std::string& path) {
    AMRVK_CHECK(path.size() < kTempPathBytes, path, ": temporary file name longer than ", kTempPathBytes - 1,
                " bytes");
    for (int i = 0; i < kTempSlots; ++i) {
        int expected = kFree;
        if (!gTempState[i].compare_exchange_strong(expected, kClaimed)) continue;
        std::memcpy(gTempPaths[i], path.c_str(), path.size() + 1);
        gTempState[i].store(kReady);
        return i;
    }
    AMRVK_CHECK(false, "more than ", kTempSlots, " output files open at once");
    return -1;
}

void unregisterTemporary(int& slot) {
    if (slot >= 0) gTempState[slot].store(kFree);
    slot = -1;
}

extern "C" void removeTemporariesAndExit(int sig) {
    removeTemporariesNow();
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

// Six random characters of [A-Za-z0-9], as mkostemp's.
std::string randomSuffix() {
    static constexpr char kChars[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
    unsigned char bytes[6];
    AMRVK_CHECK(::getrandom(bytes, sizeof bytes, 0) == ssize_t(sizeof bytes), "cannot make a temporary file name (",
                std::strerror(errno), ")");
    std::string s;
    for (const unsigned char b : bytes) s += kChars[b % 62];
    return s;
}

// Test hook (tests/cli/hostile.sh): AMRVK_TEST_TEMPORARY_DELAY_MS=N pauses N ms right after each
// temporary output file is created, so that a test can send a signal there.
void pauseAfterCreatingTemporary() {
    static const long ms = [] {
        const char* env = std::getenv("AMRVK_TEST_TEMPORARY_DELAY_MS");
        return env ? std::strtol(env, nullptr, 10) : 0L;
    }();
    if (ms > 0) std::this_thread::sleep_for(std::chrono::milliseconds(ms));
}

// The process's umask, read once (umask() can only be read by setting it).
mode_t processUmask() {
    static const mode_t mask = [] {
        const mode_t m = ::umask(022);
        ::umask(m);
        return m;
    }();
    return mask;
}

// Files opened for reading (canonical paths, in order).
std::mutex gInputsMutex;
std::vector<fs::path> gInputs;
std::vector<std::vector<fs::path>*> gRecorders;  // every live InputFileRecorder's list

// How an output path is written (see AtomicFileWriter); throws for what is refused.
enum class OutputKind { New, Replace, WriteThrough };
OutputKind outputKind(const fs::path& path, const std::string& option, struct stat& target) {
    const std::string what = option.empty() ? path.string() : option + " " + path.string();
    struct stat link {};
    if (::lstat(path.c_str(), &link) != 0) {
        AMRVK_CHECK(errno == ENOENT, what, ": cannot write (", std::strerror(errno), ")");
        fs::path dir = path.parent_path();
        if (dir.empty()) dir = ".";
        struct stat d {};
        AMRVK_CHECK(::stat(dir.c_str(), &d) == 0 && S_ISDIR(d.st_mode), what, ": cannot write (directory ",
                    dir.string(), " is missing)");
        return OutputKind::New;
    }
    if (S_ISLNK(link.st_mode)) {
        AMRVK_CHECK(::stat(path.c_str(), &target) == 0, what,
                    ": a symbolic link to nothing (refused as an output: it would be replaced)");
    } else {
        target = link;
    }
    AMRVK_CHECK(!S_ISDIR(target.st_mode), what, ": is a directory");
    if (S_ISCHR(target.st_mode) || S_ISFIFO(target.st_mode)) return OutputKind::WriteThrough;
    AMRVK_CHECK(S_ISREG(target.st_mode), what, ": not a regular file, character device or FIFO (refused as an output)");
    return OutputKind::Replace;
}

}  // namespace

void removeTemporariesNow() {
    for (int i = 0; i < kTempSlots; ++i)
        if (gTempState[i].load() == kReady) ::unlink(gTempPaths[i]);
}

void noteInputFile(const fs::path& path) {
    std::error_code ec;
    const fs::path canonical = fs::canonical(path, ec);
    if (ec) return;
    std::lock_guard lock(gInputsMutex);
    if (std::find(gInputs.begin(), gInputs.end(), canonical) == gInputs.end()) gInputs.push_back(canonical);
    for (std::vector<fs::path>* files : gRecorders)
        if (std::find(files->begin(), files->end(), canonical) == files->end()) files->push_back(canonical);
}

InputFileRecorder::InputFileRecorder() {
    std::lock_guard lock(gInputsMutex);
    gRecorders.push_back(&mFiles);
}

InputFileRecorder::~InputFileRecorder() {
    std::lock_guard lock(gInputsMutex);
    gRecorders.erase(std::find(gRecorders.begin(), gRecorders.end(), &mFiles));
}

std::vector<NamedPath> InputFileRecorder::files(const std::string& option) const {
    std::lock_guard lock(gInputsMutex);
    std::vector<NamedPath> out;
    for (const fs::path& p : mFiles) out.push_back({option, p});
    return out;
}

std::vector<NamedPath> inputFilesRead() {
    std::lock_guard lock(gInputsMutex);
    std::vector<NamedPath> out;
    for (const fs::path& p : gInputs) out.push_back({"(read)", p});
    return out;
}

void removeTemporariesOnSignal() {
    processUmask();  // read now, before any thread could create a file meanwhile
    for (int sig : {SIGHUP, SIGINT, SIGQUIT, SIGTERM}) std::signal(sig, removeTemporariesAndExit);
}

AtomicFileWriter::AtomicFileWriter(fs::path path) : mPath(std::move(path)) {
    struct stat target {};
    const OutputKind kind = outputKind(mPath, "", target);
    if (kind == OutputKind::WriteThrough) {
        const int fd = ::open(mPath.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
        AMRVK_CHECK(fd >= 0, mPath.string(), ": cannot write (", std::strerror(errno), ")");
        mFile = ::fdopen(fd, "wb");
        if (!mFile) ::close(fd);
        AMRVK_CHECK(mFile, mPath.string(), ": cannot write (", std::strerror(errno), ")");
        mTarget = mPath;
        return;
    }
    mode_t mode = 0666 & ~processUmask();
    if (kind == OutputKind::Replace) {
        std::error_code ec;
        mTarget = fs::canonical(mPath, ec);  // a link stays a link: its target is replaced
        AMRVK_CHECK(!ec, mPath.string(), ": cannot resolve (", ec.message(), ")");
        mode = target.st_mode & 07777;
    } else {
        mTarget = mPath;
    }
    // An unpredictable name, created exclusively (O_EXCL: never a planted file or link), registered
    // for the signal handler before it exists, so that no signal can leave it behind (unlinking a
    // name not made yet does nothing; a name that exists is never registered).
    int fd = -1;
    for (int attempt = 0; fd < 0; ++attempt) {
        AMRVK_CHECK(attempt < 100, mPath.string(), ": cannot write (no free temporary file name)");
        const std::string name = temporarySibling(mTarget, randomSuffix());
        struct stat taken {};
        if (::lstat(name.c_str(), &taken) == 0) continue;
        mSlot = registerTemporary(name);
        fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOCTTY | O_CLOEXEC, 0600);
        if (fd >= 0) {
            mTmpPath = name;
            break;
        }
        const int error = errno;
        unregisterTemporary(mSlot);
        AMRVK_CHECK(error == EEXIST, mPath.string(), ": cannot write (", std::strerror(error), ")");
    }
    pauseAfterCreatingTemporary();
    ::fchmod(fd, mode);
    mFile = ::fdopen(fd, "wb");
    if (!mFile) {
        ::close(fd);
        ::unlink(mTmpPath.c_str());
        unregisterTemporary(mSlot);
    }
    AMRVK_CHECK(mFile, mPath.string(), ": cannot write (", std::strerror(errno), ")");
}

AtomicFileWriter::~AtomicFileWriter() {
    if (mFile) std::fclose(mFile);
    if (!mCommitted && !mTmpPath.empty()) ::unlink(mTmpPath.c_str());
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

namespace {
thread_local OutputTransaction* tTransaction = nullptr;  // the thread's open OutputTransaction
}

OutputTransaction::OutputTransaction() {
    AMRVK_CHECK(tTransaction == nullptr, "internal: nested output transactions");
    tTransaction = this;
}

OutputTransaction::~OutputTransaction() {
    tTransaction = nullptr;
    if (mCommitted) return;
    for (Pending& p : mPending) {
        ::unlink(p.tmp.c_str());
        unregisterTemporary(p.slot);
    }
}

void OutputTransaction::commit() {
    tTransaction = nullptr;
    mCommitted = true;
    for (Pending& p : mPending) {
        const bool renamed = ::rename(p.tmp.c_str(), p.target.c_str()) == 0;
        const int error = errno;
        if (!renamed) ::unlink(p.tmp.c_str());
        unregisterTemporary(p.slot);
        AMRVK_CHECK(renamed, p.path.string(), ": cannot rename temporary file into place (", std::strerror(error), ")");
    }
}

void AtomicFileWriter::commit() {
    AMRVK_CHECK(!mCommitted, mPath.string(), ": committed twice");
    finish();
    if (tTransaction && !mTmpPath.empty()) {  // renamed with the transaction's other outputs
        tTransaction->mPending.push_back({mPath, mTmpPath, mTarget, mSlot});
        mSlot = -1;
        mCommitted = true;
        return;
    }
    if (!mTmpPath.empty()) {
        AMRVK_CHECK(::rename(mTmpPath.c_str(), mTarget.c_str()) == 0, mPath.string(),
                    ": cannot rename temporary file into place (", std::strerror(errno), ")");
    }
    mCommitted = true;
    unregisterTemporary(mSlot);
}

void checkOutputs(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs) {
    // Each input resolved once (a missing input is reported when it is read), and the outputs seen
    // by the file they write (links followed; a new file: its canonical directory + name), the first
    // kept: a series checks thousands of frames against its inputs.
    struct In {
        const NamedPath* named;
        fs::path canonical;
        bool directory;
    };
    std::vector<In> resolved;
    for (const NamedPath& in : inputs) {
        if (in.path.empty()) continue;
        std::error_code ec;
        fs::path input = fs::canonical(in.path, ec);
        if (!ec) resolved.push_back({&in, input, fs::is_directory(input)});
    }
    std::map<fs::path, const NamedPath*> seen;
    for (const NamedPath& o : outputs) {
        if (o.path.empty()) continue;
        const std::string what = o.option + " " + o.path.string();
        struct stat target {};
        const OutputKind kind = outputKind(o.path, o.option, target);
        std::error_code ec;
        fs::path canonical;
        if (kind == OutputKind::New) {
            fs::path dir = o.path.parent_path();
            if (dir.empty()) dir = ".";
            canonical = fs::canonical(dir, ec) / o.path.filename();
        } else {
            canonical = fs::canonical(o.path, ec);
        }
        AMRVK_CHECK(!ec, what, ": cannot resolve (", ec.message(), ")");
        if (kind != OutputKind::WriteThrough)
            AMRVK_CHECK(::access(canonical.parent_path().c_str(), W_OK) == 0, what, ": cannot write (directory ",
                        canonical.parent_path().string(), " is not writable)");
        if (kind != OutputKind::WriteThrough)
            if (const auto same = seen.find(canonical); same != seen.end())
                AMRVK_CHECK(false, what, " and ", same->second->option, " ", same->second->path.string(),
                            " are the same file");
        for (const In& in : resolved) {
            // "the input good.cells", "the input --tf tf.json" (not "the input input good.cells")
            const std::string input = in.named->option == "input"
                                          ? in.named->path.string()
                                          : in.named->option + " " + in.named->path.string();
            AMRVK_CHECK(in.canonical != canonical, what, " is the input ", input,
                        " (refused: it would be overwritten)");
            if (in.directory) {
                const auto [end, _] =
                    std::mismatch(in.canonical.begin(), in.canonical.end(), canonical.begin(), canonical.end());
                AMRVK_CHECK(end != in.canonical.end(), what, " lies inside the input ", input, " (refused)");
            }
        }
        seen.emplace(canonical, &o);
    }
}

void commitAll(const std::vector<std::unique_ptr<AtomicFileWriter>>& writers) {
    for (const auto& w : writers) w->finish();
    for (const auto& w : writers) w->commit();
}

fs::path makeTemporaryDirectory(const fs::path& path) {
    std::string name = temporarySibling(path, "XXXXXX");
    AMRVK_CHECK(::mkdtemp(name.data()), path.string(), ": cannot write (", std::strerror(errno), ")");
    ::chmod(name.c_str(), 0777 & ~processUmask());
    return name;
}

void writeFileAtomic(const fs::path& path, const std::string& contents) {
    AtomicFileWriter w(path);
    w.write(contents.data(), contents.size());
    w.commit();
}

}  // namespace amrvk
