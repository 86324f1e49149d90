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

}  // namespace amrvk::amr
