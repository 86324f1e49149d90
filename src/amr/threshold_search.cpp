#include "amr/threshold_search.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace amrvk::amr {

namespace {

constexpr uint64_t kBestFirstLeaves = 32768;  // exact count curve up to this many leaves
constexpr int kMaxPasses = 40;
constexpr double kDefaultSlope = -0.5;        // log t per log count when one sample is known

double logCount(const ThresholdSample& s) {
    return std::log(static_cast<double>(std::max<uint64_t>(s.count, 1)));
}

// The (t, count) samples measured so far and the thresholds they predict.
class ThresholdSearch {
public:
    void add(ThresholdSample s) { mSamples.push_back(s); }

    uint64_t maxExactCount() const {
        uint64_t m = 0;
        for (const ThresholdSample& s : mSamples)
            if (!s.capped) m = std::max(m, s.count);
        return m;
    }

    bool reached(uint64_t target) const {
        for (const ThresholdSample& s : mSamples)
            if (s.count >= target) return true;
        return false;
    }

    // Two exact samples at clearly different t with one count below `target`: the domain is full.
    bool saturated(uint64_t target) const {
        for (const ThresholdSample& a : mSamples)
            for (const ThresholdSample& b : mSamples)
                if (!a.capped && !b.capped && a.count == b.count && a.count < target && b.t > 1.5 * a.t) return true;
        return false;
    }

    // Threshold predicted to give `target` cells. With `accept` set, a measured threshold whose
    // count already lies in [target / 1.4, 1.4 target] is returned as it is (passes are exact).
    double predict(uint64_t target, bool accept) const {
        const double lt = std::log(static_cast<double>(target));
        if (accept) {
            const ThresholdSample* best = nullptr;
            for (const ThresholdSample& s : mSamples)
                if (!s.capped && std::abs(logCount(s) - lt) <= std::log(kCountTolerance) &&
                    (!best || std::abs(logCount(s) - lt) < std::abs(logCount(*best) - lt)))
                    best = &s;
            if (best) return best->t;
        }
        // Bracket: the largest t giving too many cells, the smallest t giving too few.
        const ThresholdSample* lo = nullptr;
        const ThresholdSample* hi = nullptr;
        for (const ThresholdSample& s : mSamples) {
            if (s.count >= target) {
                if (!lo || s.t > lo->t) lo = &s;
            } else if (!s.capped && (!hi || s.t < hi->t)) {
                hi = &s;
            }
        }
        if (lo && hi) {
            // Log-log interpolation inside the bracket (a capped count is a lower bound), kept
            // 15% away from its ends so the bracket shrinks on every pass.
            const double a = std::log(lo->t), b = std::log(hi->t), span = b - a;
            const double ca = logCount(*lo), cb = logCount(*hi);
            const double f = ca > cb ? (ca - lt) / (ca - cb) : 0.5;
            return std::exp(a + span * std::clamp(f, 0.15, 0.85));
        }
        // Extrapolation from the nearest exact sample with the slope to the next one.
        std::vector<ThresholdSample> exact;
        for (const ThresholdSample& s : mSamples)
            if (!s.capped && s.count > 0) exact.push_back(s);
        if (exact.empty()) return lo ? lo->t * 4.0 : hi ? hi->t / 4.0 : 1.0;
        auto dist = [&](const ThresholdSample& s) { return std::abs(logCount(s) - lt); };
        std::sort(exact.begin(), exact.end(),
                  [&](const ThresholdSample& x, const ThresholdSample& y) { return dist(x) < dist(y); });
        const ThresholdSample& a = exact[0];
        double slope = kDefaultSlope;
        for (size_t i = 1; i < exact.size(); ++i) {
            const ThresholdSample& b = exact[i];
            if (b.count == a.count || b.t == a.t) continue;
            double sl = (std::log(b.t) - std::log(a.t)) / (logCount(b) - logCount(a));
            if (std::isfinite(sl) && sl < 0) slope = std::max(sl, -4.0);
            break;
        }
        double guess = std::log(a.t) + slope * (lt - logCount(a));
        if (lo) guess = std::max(guess, std::log(lo->t) + std::log(1.05));
        if (hi) guess = std::min(guess, std::log(hi->t) - std::log(1.05));
        return std::exp(guess);
    }

private:
    std::vector<ThresholdSample> mSamples;
};

}  // namespace

void searchAndGenerate(const RefinementPasses& passes, int blockShift, const SyntheticParams& params,
                       SyntheticStats& stats) {
    constexpr uint64_t kUnlimited = std::numeric_limits<uint64_t>::max() - 1;
    const uint64_t target = std::max<uint64_t>(params.cells, 1);
    const uint64_t leafCells = uint64_t{1} << (3 * blockShift);
    const uint64_t targetLeaves = std::max<uint64_t>(target / leafCells, 1);
    const uint64_t hiCount = static_cast<uint64_t>(std::floor(static_cast<double>(target) * kCountTolerance));
    const uint64_t loCount = static_cast<uint64_t>(std::ceil(static_cast<double>(target) / kCountTolerance));
    ThresholdSearch search;

    bool exhausted = false;
    std::vector<float> scores = passes.bestFirst(std::min(targetLeaves, kBestFirstLeaves), exhausted);
    // Exact count at threshold scores[k]: every expanded node with a score >= it.
    auto exactAt = [&](size_t k) {
        size_t n = static_cast<size_t>(std::upper_bound(scores.begin(), scores.end(), scores[k],
                                                        std::greater<float>()) - scores.begin());
        return ThresholdSample{scores[k], leafCells * (1 + 7 * static_cast<uint64_t>(n)), false};
    };
    double threshold;
    bool exact = true;  // the best-first curve alone decides: accept its count as it is
    if (scores.empty()) {
        threshold = std::numeric_limits<double>::infinity();  // nothing to refine: one block
    } else if (exhausted || targetLeaves <= kBestFirstLeaves) {
        // The curve covers the target (or all there is): the count nearest N in log scale.
        size_t best = 0;
        double bestDist = std::numeric_limits<double>::infinity();
        for (size_t k = 0; k < scores.size(); ++k) {
            double d = std::abs(std::log(static_cast<double>(leafCells * (1 + 7 * (k + 1)))) -
                                std::log(static_cast<double>(target)));
            if (d < bestDist) bestDist = d, best = k;
        }
        threshold = scores[best];
    } else {
        exact = false;
        for (size_t k = scores.size(); k >= 1; k /= 2) search.add(exactAt(k - 1));
        // Counting stages at 8x the largest exact count until N / 8 is covered.
        while (search.maxExactCount() * 8 < target && !search.reached(target) &&
               !search.saturated(target) && stats.countingPasses < kMaxPasses) {
            const uint64_t stage = std::min(target, search.maxExactCount() * 8);
            const double t = search.predict(stage, false);
            search.add(passes.count(t, 4 * stage, stage, strCat("counting pass ", stats.countingPasses + 1)));
            ++stats.countingPasses;
        }
        threshold = search.predict(target, true);
    }
    for (int attempt = 0;; ++attempt) {
        const bool last = exact || attempt >= 8 || stats.countingPasses >= kMaxPasses ||
                          search.saturated(target);
        stats.threshold = threshold;
        FinalPass r = passes.write(static_cast<float>(threshold), last ? kUnlimited : hiCount,
                                   last ? uint64_t{0} : loCount);
        if (r.committed) break;
        ++stats.countingPasses;
        search.add({threshold, r.count, r.stopped});
        threshold = search.predict(target, true);
    }
}

}  // namespace amrvk::amr
