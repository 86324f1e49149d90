#include "accel/majorant_bounds.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "accel/bvh.h"

namespace amrvk::accel {

double positionMargin(double longestExtent) { return std::ldexp(std::max(longestExtent, 1.0), -18); }

double positionMargin(const amr::Box3l& bounds) {
    const glm::i64vec3 e = bounds.upper - bounds.lower;
    return positionMargin(double(std::max({e.x, e.y, e.z})));
}

int64_t marginHalfUnits(double margin) { return margin > 0 ? int64_t(std::floor(2.0 * margin)) : 0; }

ValueRange padForGpu(double lo, double hi, double maxAbs) {
    if (!(lo <= hi)) return {};
    maxAbs = std::max({maxAbs, std::abs(lo), std::abs(hi)});
    const double pad = kGpuPadUlps * double(std::numeric_limits<float>::epsilon()) * maxAbs;
    return ValueRange(roundDown(lo - pad), roundUp(hi + pad));
}

ValueRange padForGpu(const ValueRange& r) { return r.empty() ? r : padForGpu(double(r.lo), double(r.hi), 0.0); }

}  // namespace amrvk::accel
