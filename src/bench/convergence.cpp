#include "bench/convergence.h"

#include <cmath>

#include "core/error.h"

namespace amrvk::bench {

namespace {
constexpr double kRelEpsilon = 0.01;  // relMSE denominator floor (dark pixels)
}

double ImageError::rmse() const { return std::sqrt(std::max(0.0, mse)); }

ImageError imageError(const Image& image, const ReferenceImage& reference) {
    const Image& ref = reference.mean;
    AMRVK_CHECK(image.width == ref.width && image.height == ref.height, "image ", image.width, "x", image.height,
                " and reference ", ref.width, "x", ref.height, " differ in size");
    const bool haveVar = reference.meanVariance.size() == ref.pixels.size() * 3;
    double se = 0, rel = 0;
    for (size_t i = 0; i < ref.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double r = ref.pixels[i][c];
            const double d = double(image.pixels[i][c]) - r;
            const double v = haveVar ? double(reference.meanVariance[3 * i + size_t(c)]) : 0.0;
            se += d * d - v;
            rel += (d * d - v) / (r * r + kRelEpsilon);
        }
    const double n = double(ref.pixels.size()) * 3.0;
    return {n > 0 ? se / n : 0.0, n > 0 ? rel / n : 0.0};
}

std::optional<double> logLogSlope(const std::vector<double>& x, const std::vector<double>& y) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int n = 0;
    for (size_t i = 0; i < x.size() && i < y.size(); ++i) {
        if (!(x[i] > 0) || !(y[i] > 0) || !std::isfinite(x[i]) || !std::isfinite(y[i])) continue;
        const double lx = std::log(x[i]), ly = std::log(y[i]);
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
        ++n;
    }
    const double den = n * sxx - sx * sx;
    if (n < 2 || !(std::abs(den) > 1e-12)) return std::nullopt;
    return (n * sxy - sx * sy) / den;
}

std::optional<TimeToTarget> timeToTarget(const std::vector<ErrorSample>& curve, double target, double slope) {
    if (curve.empty() || !(target > 0)) return std::nullopt;
    if (curve.front().rmse <= target) return TimeToTarget{curve.front().seconds, false};
    for (size_t i = 1; i < curve.size(); ++i) {
        const ErrorSample& a = curve[i - 1];
        const ErrorSample& b = curve[i];
        if (b.rmse > target) continue;
        if (!(a.seconds > 0 && b.seconds > 0 && a.rmse > 0 && b.rmse > 0) || a.rmse == b.rmse)
            return TimeToTarget{b.seconds, false};
        const double f = std::log(target / a.rmse) / std::log(b.rmse / a.rmse);
        return TimeToTarget{std::exp(std::log(a.seconds) + f * std::log(b.seconds / a.seconds)), false};
    }
    const ErrorSample& last = curve.back();
    if (!(slope < -1e-3) || !(last.rmse > 0) || !(last.seconds > 0)) return std::nullopt;
    // rmse ~ seconds^slope  =>  seconds = last.seconds * (target / last.rmse)^(1 / slope)
    return TimeToTarget{last.seconds * std::pow(target / last.rmse, 1.0 / slope), true};
}

}  // namespace amrvk::bench
