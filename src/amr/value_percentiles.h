#pragma once
// The distribution of a field's cell values by cell count: its percentiles, exact order
// statistics, which the spiky and foggy transfer-function presets are laid over
// (scene/tf_presets.h). Every cell counts once, whatever its level: AMR codes refine where
// the field has structure, so the cells follow the features, while a volume-weighted distribution
// is the coarse background's (the 10^6-cell synthetic cloud: volume-weighted median 0.0053, in
// the empty space around the cloud; cell median 2.65, inside it).
// Computed by an exact selection on the floats' bits in three counting passes
// (PercentileSelection), O(N) each and parallel; counts are integers, so parts of a data set held
// apart (the ranks of data-parallel MPI, each counting the cells it owns) sum their counts and
// get exactly the percentiles of the whole.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace amrvk::amr {

struct Percentiles {
    uint64_t count = 0;  // values counted (NaN values are not)
    // values[k], k = 0..100: the counted value of 0-based rank floor(k (count - 1) / 100) in
    // ascending order (numpy: np.percentile(v, k, method="lower")): [0] the smallest, [100] the
    // largest, non-descending. All 0 when count is 0.
    std::array<float, 101> values{};

    float operator[](int k) const { return values[size_t(k)]; }
    float lo() const { return values[0]; }
    float hi() const { return values[100]; }
    bool operator==(const Percentiles&) const = default;
};

// The exact selection, pass by pass, for values held in one place or in parts:
//   PercentileSelection s;
//   while (!s.done()) {
//       std::vector<uint64_t> c = s.count(myValues);  // every part counts its own values
//       (sum c element-wise over the parts: the same length on every part)
//       s.advance(c);
//   }
//   Percentiles p = s.result();
// Each value is taken as the unsigned integer that orders like the float; pass 1 counts them by
// their top 11 bits, pass 2 by the next 11 bits within each top-11 group that holds a wanted
// rank, pass 3 by the last 10 bits within each such 22-bit group. At most 101 groups per pass, so
// a pass's counts are at most 101 x 2048 integers (1.6 MiB). 10^8 values: 0.4-0.6 s on two
// cores (three passes; the brick build of the same cells takes many times longer).
class PercentileSelection {
public:
    PercentileSelection();
    bool done() const { return mPass == 3; }
    // This pass's counts of `values`; NaN values are skipped. Parallel.
    std::vector<uint64_t> count(std::span<const float> values) const;
    // Takes the counts of the whole data (the sum of count() over the parts) and fixes the next
    // bits of every percentile. Throws when they do not fit this pass (a length or total that differs).
    void advance(const std::vector<uint64_t>& counts);
    // Once done().
    Percentiles result() const;

private:
    int mPass = 0;
    uint64_t mCount = 0;
    std::array<uint32_t, 101> mPrefix{};  // per percentile: the bits fixed so far (right-aligned)
    std::array<uint64_t, 101> mRank{};    // per percentile: its rank among the values with that prefix
    std::vector<uint32_t> mGroups;        // this pass: the prefixes counted, ascending
    std::vector<int32_t> mTopGroup;       // passes 2-3: top 11 bits -> group of pass 2 (-1: none)
    std::vector<int32_t> mMidGroup;       // pass 3: (group of pass 2, next 11 bits) -> group (-1: none)
};

// One process: the selection over all of `values`.
Percentiles percentilesOf(std::span<const float> values);

// The percentiles of several data sets' values together (the outputs of a time series) from each
// one's percentiles, without their values: each part's distribution is taken as linear between its
// percentiles (its cumulative share rising by 1/100 from P_k to P_k+1; a jump where they are
// equal), the parts are weighted by their counts, and P_k is the smallest value where the sum
// reaches k/100. P0 and P100 are exact (the smallest and the largest value); in between, the
// share of all values at or below P_k is within 1/100 (one percentile) of k/100 plus one value
// per part, as each part's true share and its linear stand-in stay within the same percentile
// bracket. One part is returned as it is; parts without values are skipped; none: count 0.
Percentiles pooledPercentiles(std::span<const Percentiles> parts);

}  // namespace amrvk::amr
