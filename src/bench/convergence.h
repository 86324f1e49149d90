#pragma once
// Error of an image against a reference, and how it falls with samples and time. Images are
// linear RGB; errors are over every pixel and channel. When the reference's own per-pixel sample
// variance is known (its sum of squares), its expected contribution to the mean squared error is
// subtracted, so a noisy reference does not put a floor under the measured error.
#include <cstdint>
#include <optional>
#include <vector>

#include "core/image_io.h"

namespace amrvk::bench {

struct ReferenceImage {
    Image mean;
    std::vector<float> meanVariance;  // per pixel and channel (3 per pixel): variance of the mean; empty = unknown
    uint32_t spp = 0;
};

struct ImageError {
    double mse = 0;     // mean over pixels and channels of (x - r)^2, minus the reference's variance
    double relMse = 0;  // mean of (x - r)^2 / (r^2 + 0.01), minus the reference's share
    double rmse() const;
};
// Throws when the sizes differ.
ImageError imageError(const Image& image, const ReferenceImage& reference);

// One point of a convergence curve.
struct ErrorSample {
    uint32_t spp = 0;
    double seconds = 0;  // GPU seconds spent to reach spp
    double rmse = 0, relMse = 0;
};

// Least-squares slope of log(y) against log(x) over the points with x, y > 0; nullopt when
// fewer than two such points.
std::optional<double> logLogSlope(const std::vector<double>& x, const std::vector<double>& y);

// Seconds to reach `target` RMSE: interpolated in log-log between the first bracketing pair of
// samples (measured), or, when the last sample is still above it, extrapolated from the last
// sample along the slope (only for slope < 0); nullopt when neither applies.
struct TimeToTarget {
    double seconds = 0;
    bool extrapolated = false;
};
std::optional<TimeToTarget> timeToTarget(const std::vector<ErrorSample>& curve, double target, double slope);

}  // namespace amrvk::bench
