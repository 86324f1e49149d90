#pragma once
// A closed interval of field values; empty when lo > hi (the default).
#include <algorithm>
#include <limits>

namespace amrvk::accel {

struct ValueRange {
    float lo = std::numeric_limits<float>::infinity();
    float hi = -std::numeric_limits<float>::infinity();
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

}  // namespace amrvk::accel
