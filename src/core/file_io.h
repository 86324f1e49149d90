#pragma once
// Checked binary file access. Every failure throws amrvk::Error naming the file and byte offset;
// writes go to a temporary name in the same directory and are renamed only when complete.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace amrvk {

// Size in bytes of an existing regular file; throws if missing or not a regular file.
uint64_t fileSize(const std::filesystem::path& path);

// Reads a whole text file (its size checked against the memory budget first).
std::string readTextFile(const std::filesystem::path& path);

// Advises the 2 MiB-aligned pages inside [p, p + bytes) onto transparent huge pages, before they
// are first touched; a no-op below kHugePageAdviceBytes or where the kernel refuses.
inline constexpr size_t kHugePageAdviceBytes = size_t{8} << 20;
void adviseHugePages(void* p, size_t bytes);

// Faults in the whole pages inside [p, p + bytes) for writing in one system call
// (MADV_POPULATE_WRITE) instead of one trap per page; a no-op where the kernel refuses (older than
// 5.14, or memory that cannot be populated, such as a device's BAR). Mapped Vulkan memory on
// lavapipe is shared memory on 4 KiB pages: at 10^8 cells its first touch by the upload was about
// 0.4 s of both cores in page-fault traps on a VM.
void prefaultForWrite(void* p, size_t bytes);

// Faults in [p, p + bytes) on every core (huge pages advised, zero-filled) from
// kHugePageAdviceBytes on, so that the resize() that follows does not do it on one.
void prepareStorage(void* p, size_t bytes);

// A vector allocator that leaves elements made without a value (resize) default-initialised:
// uninitialised for trivial types, so no page is touched before a reader writes it. A large
// array read into such a vector is written once, in parallel (BinaryReader::readArray), instead of
// being zero-filled on one core first (the 10^8-cell cloud's 1.7 GB of cells: about 1 s).
// Arrays of kHugePageAdviceBytes or more are also advised onto transparent huge pages where the
// kernel offers them (THP "madvise" or "always"): one fault per 2 MiB instead of per 4 KiB, which
// at 10^8 cells was about a tenth of the first sample's CPU time in page faults on a VM.
template <class T>
struct NoInitAllocator : std::allocator<T> {
    template <class U>
    struct rebind {
        using other = NoInitAllocator<U>;
    };
    NoInitAllocator() noexcept = default;
    template <class U>
    NoInitAllocator(const NoInitAllocator<U>&) noexcept {}
    T* allocate(size_t n) {
        T* p = std::allocator<T>::allocate(n);
        adviseHugePages(p, n * sizeof(T));
        return p;
    }
    template <class U>
    void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

// Sequential reader of a binary file with the current byte offset in every error message.
class BinaryReader {
public:
    explicit BinaryReader(const std::filesystem::path& path);
    ~BinaryReader();
    BinaryReader(const BinaryReader&) = delete;
    BinaryReader& operator=(const BinaryReader&) = delete;

    uint64_t size() const { return mSize; }
    uint64_t offset() const { return mOffset; }
    bool atEnd() const { return mOffset >= mSize; }
    void seek(uint64_t offset);
    // Reads exactly `bytes` bytes or throws "FILE: truncated at byte N (needed M more bytes)".
    // kParallelReadBytes or more are read in chunks on every core (pread).
    void read(void* dst, uint64_t bytes);
    static constexpr uint64_t kParallelReadBytes = uint64_t{32} << 20;
    // Throws the truncation error of read() unless `bytes` more bytes are left.
    void requireBytes(uint64_t bytes) const;
    // Reads `count` values; the file is checked to hold them before anything is allocated.
    template <typename T, typename A>
    void readArray(std::vector<T, A>& out, uint64_t count) {
        requireBytes(count > UINT64_MAX / sizeof(T) ? UINT64_MAX : count * sizeof(T));
        if (out.capacity() < count) {  // fresh storage: its pages faulted in on every core
            std::vector<T, A>().swap(out);
            out.reserve(count);
            // (resize() of a NoInitAllocator vector touches nothing: the read is the first touch.)
            if constexpr (std::is_trivially_default_constructible_v<T> && !std::is_same_v<A, NoInitAllocator<T>>)
                prepareStorage(out.data(), count * sizeof(T));
        }
        out.resize(count);
        read(out.data(), count * sizeof(T));
    }
    // Reads `bytes` bytes at absolute `offset` without moving the reader (pread), from any thread;
    // the caller checked that they exist. Throws "FILE: read error at byte N".
    void readAt(uint64_t offset, void* dst, uint64_t bytes) const;
    const std::filesystem::path& path() const { return mPath; }

private:
    void readInChunks(void* dst, uint64_t bytes);  // read() from kParallelReadBytes on

    std::filesystem::path mPath;
    std::FILE* mFile = nullptr;
    uint64_t mSize = 0;
    uint64_t mOffset = 0;
};

// How an output path is written, so that no output ever destroys what it is not meant to replace:
//  - nothing there, or a regular file (also behind symbolic links: the link stays a link and its
//    target is replaced): the data goes to a temporary created exclusively beside the target
//    (O_CREAT|O_EXCL with a random suffix, as mkostemp, so a link planted at a predictable name
//    is never followed), which commit() renames over the target;
//  - a character device or FIFO (/dev/null, /dev/stdout, a pipe): written through, nothing renamed;
//  - a directory, a socket, a block device or a link to nothing: refused.
// (That no output is an input of the command is checkOutputs' job, before any work.) A writer destroyed without commit() removes its temporary;
// SIGHUP, SIGINT, SIGQUIT and SIGTERM remove every open temporary (removeTemporariesOnSignal); a
// temporary is registered for that before it is created, so no signal can leave one behind.
class AtomicFileWriter {
public:
    explicit AtomicFileWriter(std::filesystem::path path);
    ~AtomicFileWriter();
    AtomicFileWriter(const AtomicFileWriter&) = delete;
    AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

    void write(const void* src, uint64_t bytes);
    template <typename T>
    void writeSpan(std::span<const T> values) {
        write(values.data(), values.size_bytes());
    }
    uint64_t bytesWritten() const { return mBytes; }
    // The temporary file that commit() renames (empty when written through): where another program
    // may write the data after finish() (a movie by ffmpeg); removed like the writer's own data.
    const std::filesystem::path& temporaryPath() const { return mTmpPath; }
    // Flushes and closes the temporary file (where a full disk shows up); throws on failure.
    void finish();
    // finish() if not yet done, then renames the temporary file to the final path.
    void commit();

private:
    std::filesystem::path mPath;     // as named (for messages)
    std::filesystem::path mTarget;   // the file replaced: mPath with links followed
    std::filesystem::path mTmpPath;  // empty when written through
    std::FILE* mFile = nullptr;
    bool mFinished = false, mCommitted = false;
    int mSlot = -1;  // entry in the table of temporaries that the signal handler removes
    uint64_t mBytes = 0;
};

// Commits several files as one output: every writer is finished before any is renamed, so a write
// error leaves none of them under its final name.
void commitAll(const std::vector<std::unique_ptr<AtomicFileWriter>>& writers);

// A command's outputs as one: while one lives (at most one per thread), AtomicFileWriter::commit()
// finishes its file (where a full disk shows up) but keeps it as a temporary; commit() renames them
// all into place, and the destructor without commit() removes them. So `render -o a.png --json X`
// leaves no a.png when X cannot be written (a file written through, such as /dev/full, is written
// at its finish and cannot be taken back: it is the one output that may be left).
class OutputTransaction {
public:
    OutputTransaction();
    ~OutputTransaction();
    OutputTransaction(const OutputTransaction&) = delete;
    OutputTransaction& operator=(const OutputTransaction&) = delete;
    void commit();

private:
    friend class AtomicFileWriter;
    struct Pending {
        std::filesystem::path path, tmp, target;
        int slot;
    };
    std::vector<Pending> mPending;
    bool mCommitted = false;
};

// Removes every open AtomicFileWriter temporary now; async-signal-safe (for a process that must end
// at once: a signal, a runaway GPU dispatch).
void removeTemporariesNow();

// Installs SIGHUP, SIGINT, SIGQUIT and SIGTERM handlers that remove every AtomicFileWriter's
// temporary file, then end the process with the signal's default action. main() calls it once.
void removeTemporariesOnSignal();

// A file a command reads or writes, named by the option that names it (for messages).
struct NamedPath {
    std::string option;  // e.g. "-o", "--json", "input"
    std::filesystem::path path;
};
// Checks every output of a command before any work: each can be written as AtomicFileWriter
// writes it (its directory exists and is writable; not a directory, socket, block device or link
// to nothing), no two outputs are the same file, and none is one of `inputs` (the same file after
// links are followed, or a file inside an input directory). Throws one line naming the option(s).
void checkOutputs(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs);

// Records a file opened for reading (BinaryReader, readTextFile and the HDF5 readers call it), so
// a command can check its outputs against every file its data set is made of once it is read
// (checkOutputs(outputs, inputFilesRead())), not only against the path it was given.
void noteInputFile(const std::filesystem::path& path);
std::vector<NamedPath> inputFilesRead();

// Records, while it lives, every file noteInputFile sees (from any thread; canonical paths, each
// once): the files one data set is made of, for front ends that read several (Python).
class InputFileRecorder {
public:
    InputFileRecorder();
    ~InputFileRecorder();
    InputFileRecorder(const InputFileRecorder&) = delete;
    InputFileRecorder& operator=(const InputFileRecorder&) = delete;
    std::vector<NamedPath> files(const std::string& option) const;  // each named by `option`

private:
    std::vector<std::filesystem::path> mFiles;
};

// Makes a new directory named `path` + ".tmp-XXXXXX" (mkdtemp: an unpredictable name, created
// exclusively) with the mode mkdir gives (0777 less the umask), for output that is renamed into
// place only when complete; returns its name. Throws one line naming `path`.
std::filesystem::path makeTemporaryDirectory(const std::filesystem::path& path);

// Writes a whole text/binary buffer atomically.
void writeFileAtomic(const std::filesystem::path& path, const std::string& contents);

}  // namespace amrvk
