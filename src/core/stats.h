#pragma once
// Wall-clock timing and process memory, for build statistics and benchmarks.
#include <chrono>
#include <cstdint>

namespace amrvk {

class Timer {
public:
    Timer() : mStart(std::chrono::steady_clock::now()) {}
    // Seconds since construction.
    double seconds() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - mStart).count();
    }

private:
    std::chrono::steady_clock::time_point mStart;
};

// Peak resident set size of this process in bytes (getrusage ru_maxrss).
uint64_t peakResidentBytes();

}  // namespace amrvk
