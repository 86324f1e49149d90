#pragma once
// Checked binary file access. Every failure throws amrvk::Error naming the file and byte offset;
// writes go to a temporary name in the same directory and are renamed only when complete.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace amrvk {

// Size in bytes of an existing regular file; throws if missing or not a regular file.
uint64_t fileSize(const std::filesystem::path& path);

// Reads a whole text file.
std::string readTextFile(const std::filesystem::path& path);

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
    void read(void* dst, uint64_t bytes);
    // Throws the truncation error of read() unless `bytes` more bytes are left.
    void requireBytes(uint64_t bytes) const;
    // Reads `count` values; the file is checked to hold them before anything is allocated.
    template <typename T>
    void readArray(std::vector<T>& out, uint64_t count) {
        requireBytes(count > UINT64_MAX / sizeof(T) ? UINT64_MAX : count * sizeof(T));
        out.resize(count);
        read(out.data(), count * sizeof(T));
    }
    const std::filesystem::path& path() const { return mPath; }

private:
    std::filesystem::path mPath;
    std::FILE* mFile = nullptr;
    uint64_t mSize = 0;
    uint64_t mOffset = 0;
};

// Writes a file atomically: data goes to "<path>.tmp-<pid>" and is renamed to `path` by commit().
// A writer destroyed without commit() removes its temporary file, so no half-written output remains.
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
    // Flushes and closes the temporary file (where a full disk shows up); throws on failure.
    void finish();
    // finish() if not yet done, then renames the temporary file to the final path.
    void commit();

private:
    std::filesystem::path mPath;
    std::filesystem::path mTmpPath;
    std::FILE* mFile = nullptr;
    bool mFinished = false, mCommitted = false;
    int mSlot = -1;  // entry in the table of temporaries that SIGINT/SIGTERM remove
    uint64_t mBytes = 0;
};

// Commits several files as one output: every writer is finished before any is renamed, so a write
// error leaves none of them under its final name.
void commitAll(const std::vector<std::unique_ptr<AtomicFileWriter>>& writers);

// Installs SIGINT/SIGTERM handlers that remove every AtomicFileWriter's temporary file, then end
// the process with the signal's default action. main() calls it once.
void removeTemporariesOnSignal();

// Writes a whole text/binary buffer atomically.
void writeFileAtomic(const std::filesystem::path& path, const std::string& contents);

}  // namespace amrvk
