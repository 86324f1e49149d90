#include "core/gpu_deadline.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "core/error.h"

namespace amrvk {

namespace {

double floorFromEnvironment() {
    const char* env = std::getenv("AMRVK_TEST_GPU_TIMEOUT_FLOOR");
    if (!env || !*env) return GpuDeadline::kFloorSeconds;
    char* end = nullptr;
    errno = 0;
    const double s = std::strtod(env, &end);
    AMRVK_CHECK(end && *end == '\0' && errno == 0 && std::isfinite(s) && s > 0 && s <= 1e6,
                "AMRVK_TEST_GPU_TIMEOUT_FLOOR: '", env, "' is not a number of seconds in (0, 1e6]");
    return s;
}

}  // namespace

GpuDeadline::GpuDeadline() : mFloor(floorFromEnvironment()) {}

GpuDeadline::GpuDeadline(double floorSeconds) : mFloor(floorSeconds) {}

double GpuDeadline::limit(uint64_t paths) const {
    return std::max(mFloor, kMargin * mSecondsPerPath * double(std::max<uint64_t>(paths, 1)));
}

void GpuDeadline::record(double seconds, uint64_t paths) {
    if (paths == 0 || !(seconds >= 0)) return;
    // 1e-12: measured, even where the clock saw no time pass.
    mSecondsPerPath = std::max({mSecondsPerPath, seconds / double(paths), 1e-12});
}

std::vector<GpuDeadline::Part> GpuDeadline::submissions(uint64_t work, uint64_t probe) const {
    std::vector<Part> parts;
    uint64_t next = measured() ? work : std::max<uint64_t>(probe, 1);
    for (uint64_t first = 0; first < work; next *= 4) {
        const uint64_t count = std::min(next, work - first);
        parts.push_back({first, count});
        first += count;
    }
    return parts;
}

}  // namespace amrvk
