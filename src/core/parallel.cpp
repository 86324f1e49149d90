#include "core/parallel.h"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

namespace amrvk {

void parallelForRanges(size_t begin, size_t end, size_t grain,
                       const std::function<void(size_t lo, size_t hi)>& fn) {
    if (begin >= end) return;
    tbb::parallel_for(tbb::blocked_range<size_t>(begin, end, std::max<size_t>(grain, 1)),
                      [&fn](const tbb::blocked_range<size_t>& r) { fn(r.begin(), r.end()); });
}

void parallelInvoke(const std::function<void()>& a, const std::function<void()>& b) {
    tbb::parallel_invoke(a, b);
}

}  // namespace amrvk
