#pragma once
// Data-parallel loops on TBB's thread pool. Every parallel step of amrvk goes through these
// helpers; parallel.cpp is the only file that includes TBB.
// Determinism is the caller's side of the contract: a body writes only what its own indices own,
// and parallelReduce folds a caller-fixed number of chunks in chunk order, so results do not
// depend on the thread count or the schedule.
#include <algorithm>
#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

namespace amrvk {

// Worker threads of every parallel step: the machine's cores, or AMRVK_THREADS (1..kMaxThreads,
// read once per process; anything else is a one-line error at the first parallel step).
inline constexpr int kMaxThreads = 4096;
int threadCount();

// Calls fn(lo, hi) on disjoint sub-ranges that together cover [begin, end), concurrently and in
// any order (at least `grain` indices each, unless fewer remain); returns when all have returned.
// An exception thrown by fn is rethrown here after the other calls are cancelled or done.
void parallelForRanges(size_t begin, size_t end, size_t grain,
                       const std::function<void(size_t lo, size_t hi)>& fn);

// Calls fn(i) for every i in [begin, end), concurrently and in any order.
template <class Fn>
void parallelFor(size_t begin, size_t end, Fn&& fn, size_t grain = 1) {
    parallelForRanges(begin, end, grain, [&fn](size_t lo, size_t hi) {
        for (size_t i = lo; i < hi; ++i) fn(i);
    });
}

// memcpy / memset(0) of large arrays in 8 MiB chunks on every core, the destination advised onto
// huge pages first (core/file_io.h): its pages are then faulted in (and cleared by the kernel) on
// every core instead of one. The 10^8-cell first sample spent about 2 s of one core in the
// device upload's memcpy and the field's zero-fill alone.
void parallelCopy(void* dst, const void* src, size_t bytes);
void parallelZero(void* dst, size_t bytes);

// Runs a() and b(), possibly at the same time; returns when both have (rethrows as above).
void parallelInvoke(const std::function<void()>& a, const std::function<void()>& b);

// Cuts [begin, end) into `chunks` consecutive parts of near-equal size (chunk k starts at
// begin + k * size / chunks), computes map(lo, hi) -> T for every part concurrently, then folds
// the parts in chunk order: result = part 0, then combine(result, std::move(part k)) for k = 1...
// The chunk count is the caller's (never the thread count), so the result is the same on every
// machine. Holds all `chunks` partial results at once. chunks >= 1; an empty range still maps
// one empty part.
template <class T, class Map, class Combine>
T parallelReduce(size_t begin, size_t end, size_t chunks, Map&& map, Combine&& combine) {
    const size_t n = end - begin;
    chunks = std::max<size_t>(1, std::min(chunks, std::max<size_t>(n, 1)));
    std::vector<T> parts(chunks);
    auto bound = [&](size_t k) { return begin + k * n / chunks; };
    parallelFor(0, chunks, [&](size_t k) { parts[k] = map(bound(k), bound(k + 1)); });
    T result = std::move(parts[0]);
    for (size_t k = 1; k < chunks; ++k) combine(result, std::move(parts[k]));
    return result;
}

}  // namespace amrvk
