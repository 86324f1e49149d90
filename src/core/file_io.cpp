#include "core/file_io.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

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
    fileSize(path);
    std::ifstream in(path, std::ios::binary);
    AMRVK_CHECK(in, path.string(), ": cannot open (", std::strerror(errno), ")");
    std::ostringstream os;
    os << in.rdbuf();
    return os.str();
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

AtomicFileWriter::AtomicFileWriter(fs::path path) : mPath(std::move(path)) {
    mTmpPath = mPath;
    mTmpPath += strCat(".tmp-", ::getpid());
    mFile = std::fopen(mTmpPath.c_str(), "wb");
    AMRVK_CHECK(mFile, mPath.string(), ": cannot write (", std::strerror(errno), ")");
}

AtomicFileWriter::~AtomicFileWriter() {
    if (mFile) {
        std::fclose(mFile);
        std::error_code ec;
        fs::remove(mTmpPath, ec);
    }
}

void AtomicFileWriter::write(const void* src, uint64_t bytes) {
    AMRVK_CHECK(mFile, mPath.string(), ": write after commit");
    size_t put = std::fwrite(src, 1, bytes, mFile);
    AMRVK_CHECK(put == bytes, mPath.string(), ": write failed at byte ", mBytes + put, " (",
                std::strerror(errno), ")");
    mBytes += bytes;
}

void AtomicFileWriter::commit() {
    AMRVK_CHECK(mFile, mPath.string(), ": committed twice");
    bool ok = std::fflush(mFile) == 0;
    ok = (std::fclose(mFile) == 0) && ok;
    mFile = nullptr;
    if (!ok) {
        std::error_code ec;
        fs::remove(mTmpPath, ec);
        AMRVK_CHECK(false, mPath.string(), ": write failed (", std::strerror(errno), ")");
    }
    std::error_code ec;
    fs::rename(mTmpPath, mPath, ec);
    if (ec) {
        fs::remove(mTmpPath, ec);
        AMRVK_CHECK(false, mPath.string(), ": cannot rename temporary file into place");
    }
}

void writeFileAtomic(const fs::path& path, const std::string& contents) {
    AtomicFileWriter w(path);
    w.write(contents.data(), contents.size());
    w.commit();
}

}  // namespace amrvk
