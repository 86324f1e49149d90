#include "core/parallel.h"

#include <algorithm>
#include <cstring>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "core/error.h"
#include "core/file_io.h"

namespace amrvk {

namespace {
std::once_flag gThreadsOnce;
std::unique_ptr<tbb::global_control> gThreadLimit;  // set from AMRVK_THREADS, for the process
int gThreads = 0;

void initThreads() {
    std::call_once(gThreadsOnce, [] {
        gThreads = tbb::info::default_concurrency();
        const char* text = std::getenv("AMRVK_THREADS");
        if (text == nullptr || *text == '\0') return;
        char* end = nullptr;
        const long n = std::strtol(text, &end, 10);
        AMRVK_CHECK(*end == '\0' && n >= 1 && n <= kMaxThreads, "AMRVK_THREADS=", text,
                    ": not a thread count in [1, ", kMaxThreads, "]");
        gThreads = int(n);
        gThreadLimit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(n));
    });
}
}  // namespace

int threadCount() {
    initThreads();
    return gThreads;
}

void parallelForRanges(size_t begin, size_t end, size_t grain,
                       const std::function<void(size_t lo, size_t hi)>& fn) {
    initThreads();
    if (begin >= end) return;
    tbb::parallel_for(tbb::blocked_range<size_t>(begin, end, std::max<size_t>(grain, 1)),
                      [&fn](const tbb::blocked_range<size_t>& r) { fn(r.begin(), r.end()); });
}

void parallelInvoke(const std::function<void()>& a, const std::function<void()>& b) {
    initThreads();
    tbb::parallel_invoke(a, b);
}

namespace {
constexpr size_t kCopyChunk = size_t{8} << 20;

// fn(at, n) over [0, bytes) in kCopyChunk pieces on every core, dst advised onto huge pages first
// and each piece faulted in before fn writes it; below two chunks, once on this thread.
template <class Fn>
void inChunks(void* dst, size_t bytes, Fn&& fn) {
    if (bytes < 2 * kCopyChunk) return fn(size_t{0}, bytes);
    adviseHugePages(dst, bytes);
    parallelFor(0, (bytes + kCopyChunk - 1) / kCopyChunk, [&](size_t k) {
        const size_t at = k * kCopyChunk, n = std::min(kCopyChunk, bytes - at);
        prefaultForWrite(static_cast<char*>(dst) + at, n);
        fn(at, n);
    });
}
}  // namespace

void parallelCopy(void* dst, const void* src, size_t bytes) {
    inChunks(dst, bytes, [&](size_t at, size_t n) {
        std::memcpy(static_cast<char*>(dst) + at, static_cast<const char*>(src) + at, n);
    });
}

void parallelZero(void* dst, size_t bytes) {
    inChunks(dst, bytes, [&](size_t at, size_t n) { std::memset(static_cast<char*>(dst) + at, 0, n); });
}

}  // namespace amrvk
