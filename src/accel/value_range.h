#pragma once
// A closed interval of field values; empty when lo > hi (the default). The layout is the GPU's
// (shared::ValueRangeGpu), so arrays of ranges upload as they are.
#include <algorithm>
#include <limits>

#include "shared/amr_gpu.h"

namespace amrvk::accel {

struct ValueRange : shared::ValueRangeGpu {
    ValueRange() : shared::ValueRangeGpu{std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity()} {}
    ValueRange(float low, float high) : shared::ValueRangeGpu{low, high} {}
    bool empty() const { return lo > hi; }
    void extend(float v) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    void extend(const ValueRange& r) {
        lo = std::min(lo, r.lo);
        hi = std::max(hi, r.hi);
    }
    bool contains(double v) const { return v >= lo && v <= hi; }
};
static_assert(sizeof(ValueRange) == sizeof(shared::ValueRangeGpu));

}  // namespace amrvk::accel
