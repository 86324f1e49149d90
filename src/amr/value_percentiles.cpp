#include "amr/value_percentiles.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"

namespace amrvk::amr {

namespace {

constexpr int kBits[3] = {11, 11, 10};   // bits fixed by each pass, from the top
constexpr int kShift[3] = {21, 10, 0};   // where each pass's digit starts
constexpr size_t kCountChunks = 16;      // counts are exact integers: any chunking gives the same sums
// Interleaved copies of a chunk's counts, value i counted in copy i % kWays: neighbouring cells
// often share a bin, and one copy per way breaks that chain of increments (3x faster).
constexpr size_t kWays = 4;
constexpr uint64_t kMaxCount = uint64_t(1) << 56;  // k (count - 1) stays below 2^63

// The unsigned integer that orders like the float: negatives reversed below the positives.
uint32_t keyOf(float v) {
    const uint32_t u = std::bit_cast<uint32_t>(v);
    return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
}
float valueOf(uint32_t key) { return std::bit_cast<float>((key & 0x80000000u) ? (key & 0x7FFFFFFFu) : ~key); }

}  // namespace

PercentileSelection::PercentileSelection() : mGroups{0} {}

std::vector<uint64_t> PercentileSelection::count(std::span<const float> values) const {
    AMRVK_CHECK(!done(), "internal: percentile selection counted after its last pass");
    const int pass = mPass;
    const size_t bins = size_t(1) << kBits[pass];
    const size_t size = mGroups.size() * bins;
    // At least 2^16 values a chunk (each chunk zeroes its own counts), below 2^32 (32-bit counts).
    const size_t chunks = std::max(std::clamp<size_t>(values.size() >> 16, 1, kCountChunks), (values.size() >> 31) + 1);
    return parallelReduce<std::vector<uint64_t>>(
        0, values.size(), chunks,
        [&](size_t from, size_t to) {
            std::vector<uint32_t> ways(kWays * size, 0);
            const uint32_t mask = uint32_t(bins - 1);
            const int shift = kShift[pass];
            // The bin of value i in its way's counts, or -1 (NaN, or no wanted rank in its group).
            auto binOf = [&](float v) -> int64_t {
                if (std::isnan(v)) return -1;
                const uint32_t key = keyOf(v);
                int64_t g = 0;
                if (pass >= 1) g = mTopGroup[key >> 21];
                if (pass == 2 && g >= 0) g = mMidGroup[size_t(g) * 2048 + ((key >> 10) & 0x7FFu)];
                return g < 0 ? -1 : g * int64_t(bins) + int64_t((key >> shift) & mask);
            };
            size_t i = from;
            for (; i + kWays <= to; i += kWays)
                for (size_t w = 0; w < kWays; ++w)
                    if (const int64_t b = binOf(values[i + w]); b >= 0) ++ways[w * size + size_t(b)];
            for (; i < to; ++i)
                if (const int64_t b = binOf(values[i]); b >= 0) ++ways[size_t(b)];
            std::vector<uint64_t> c(size, 0);
            for (size_t w = 0; w < kWays; ++w)
                for (size_t b = 0; b < size; ++b) c[b] += ways[w * size + b];
            return c;
        },
        [](std::vector<uint64_t>& a, std::vector<uint64_t>&& b) {
            for (size_t i = 0; i < a.size(); ++i) a[i] += b[i];
        });
}

void PercentileSelection::advance(const std::vector<uint64_t>& counts) {
    AMRVK_CHECK(!done(), "internal: percentile selection advanced after its last pass");
    const int pass = mPass;
    const size_t bins = size_t(1) << kBits[pass];
    AMRVK_CHECK(counts.size() == mGroups.size() * bins, "internal: percentile pass ", pass + 1, " got ",
                counts.size(), " counts, expected ", mGroups.size() * bins);
    if (pass == 0) {
        mCount = 0;
        for (uint64_t c : counts) mCount += c;
        AMRVK_CHECK(mCount < kMaxCount, "internal: ", mCount, " values are too many for the percentile selection");
        if (mCount == 0) {
            mPass = 3;
            return;
        }
        for (size_t k = 0; k <= 100; ++k) mRank[k] = uint64_t(k) * (mCount - 1) / 100;
    }
    for (size_t k = 0; k <= 100; ++k) {
        const auto it = std::lower_bound(mGroups.begin(), mGroups.end(), mPrefix[k]);
        const size_t g = size_t(it - mGroups.begin());
        size_t d = 0;
        for (; d < bins; ++d) {
            const uint64_t c = counts[g * bins + d];
            if (mRank[k] < c) break;
            mRank[k] -= c;
        }
        AMRVK_CHECK(d < bins, "internal: percentile pass ", pass + 1, ": the counts hold fewer values than pass 1's");
        mPrefix[k] = (mPrefix[k] << kBits[pass]) | uint32_t(d);
    }
    mGroups.assign(mPrefix.begin(), mPrefix.end());
    std::sort(mGroups.begin(), mGroups.end());
    mGroups.erase(std::unique(mGroups.begin(), mGroups.end()), mGroups.end());
    if (pass == 0) {
        mTopGroup.assign(2048, -1);
        for (size_t i = 0; i < mGroups.size(); ++i) mTopGroup[mGroups[i]] = int32_t(i);
    } else if (pass == 1) {
        size_t topGroups = 0;
        for (int32_t g : mTopGroup) topGroups += g >= 0 ? 1 : 0;
        mMidGroup.assign(topGroups * 2048, -1);
        for (size_t i = 0; i < mGroups.size(); ++i) {
            const int32_t top = mTopGroup[mGroups[i] >> 11];
            mMidGroup[size_t(top) * 2048 + (mGroups[i] & 0x7FFu)] = int32_t(i);
        }
    }
    ++mPass;
}

Percentiles PercentileSelection::result() const {
    AMRVK_CHECK(done(), "internal: percentiles asked for before the last pass");
    Percentiles p;
    p.count = mCount;
    if (mCount > 0)
        for (size_t k = 0; k <= 100; ++k) p.values[k] = valueOf(mPrefix[k]);
    return p;
}

Percentiles percentilesOf(std::span<const float> values) {
    PercentileSelection s;
    while (!s.done()) s.advance(s.count(values));
    return s.result();
}

namespace {

// Part p's cumulative share at x (linear between its percentiles), from the right: every
// percentile at or below x counts, so a run of equal ones is a jump at their value.
double shareAtOrBelow(const Percentiles& p, double x) {
    if (x < p.values[0]) return 0.0;
    if (x >= p.values[100]) return 1.0;
    // The last k with P_k <= x (k < 100 here, and P_k < P_k+1).
    const auto it = std::upper_bound(p.values.begin(), p.values.end(), x, [](double v, float e) { return v < e; });
    const size_t k = size_t(it - p.values.begin()) - 1;
    const double a = p.values[k], b = p.values[k + 1];
    return (double(k) + (x - a) / (b - a)) / 100.0;
}

// The same from the left (the limit as x is approached from below).
double shareBelow(const Percentiles& p, double x) {
    if (x <= p.values[0]) return 0.0;
    if (x > p.values[100]) return 1.0;
    // The last k with P_k < x (k < 100 here, and P_k+1 >= x).
    const auto it = std::lower_bound(p.values.begin(), p.values.end(), x, [](float e, double v) { return e < v; });
    const size_t k = size_t(it - p.values.begin()) - 1;
    const double a = p.values[k], b = p.values[k + 1];
    return (double(k) + (x - a) / (b - a)) / 100.0;
}

}  // namespace

Percentiles pooledPercentiles(std::span<const Percentiles> parts) {
    std::vector<Percentiles> used;
    for (const Percentiles& p : parts)
        if (p.count > 0) used.push_back(p);
    if (used.size() <= 1) return used.empty() ? Percentiles{} : used.front();
    Percentiles out;
    for (const Percentiles& p : used) out.count += p.count;
    auto share = [&](double x, bool below) {
        double s = 0;
        for (const Percentiles& p : used) s += double(p.count) * (below ? shareBelow(p, x) : shareAtOrBelow(p, x));
        return s / double(out.count);
    };
    // Between two neighbouring values of any part's percentiles every part's share is linear.
    std::vector<double> knots;
    for (const Percentiles& p : used) knots.insert(knots.end(), p.values.begin(), p.values.end());
    std::sort(knots.begin(), knots.end());
    knots.erase(std::unique(knots.begin(), knots.end()), knots.end());
    std::vector<double> at(knots.size());  // the pooled share at or below each knot
    for (size_t i = 0; i < knots.size(); ++i) at[i] = share(knots[i], false);
    for (int k = 0; k <= 100; ++k) {
        const double want = k / 100.0;
        // The first knot whose share reaches k/100 (the last knot's share is 1).
        const size_t m = size_t(std::lower_bound(at.begin(), at.end() - 1, want - 1e-12) - at.begin());
        double x = knots[m];
        if (m > 0 && k > 0) {
            // Reached inside (knots[m-1], knots[m]) where the share is linear, or at knots[m] by a jump.
            const double lo = at[m - 1], hiLeft = share(knots[m], true);
            if (hiLeft >= want && hiLeft > lo)
                x = knots[m - 1] + (want - lo) / (hiLeft - lo) * (knots[m] - knots[m - 1]);
        }
        out.values[size_t(k)] = float(x);
    }
    // Exact ends, and non-descending after the rounding to float.
    out.values[0] = float(knots.front());
    out.values[100] = float(knots.back());
    for (size_t k = 1; k <= 100; ++k) out.values[k] = std::max(out.values[k], out.values[k - 1]);
    return out;
}

}  // namespace amrvk::amr
