// amr::Percentiles (amr/value_percentiles.h): exact percentiles by cell count against known
// distributions (integers, the exponential's order statistics and quantile function), against a
// sort on values that stress the bit selection (negatives, both zeros, denormals, infinities,
// duplicates, NaN); parts whose counts are summed (data-parallel MPI) give the whole's; pooled
// from the parts' percentiles alone (a time series) they are within one percentile of the whole's
// by rank, which a mean of the parts' percentiles is not; the volume's are of its field, also
// under --scale log.
#include "amr/value_percentiles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <random>

#include "model_fixtures.h"
#include "scene/volume.h"
#include "test_data.h"

using namespace amrvk;

namespace {

// numpy's np.percentile(v, k, method="lower") over the non-NaN values, by sorting.
amr::Percentiles bySorting(std::vector<float> v) {
    std::erase_if(v, [](float x) { return std::isnan(x); });
    // -0 before +0, as the selection orders them (std::sort alone leaves them in any order).
    std::sort(v.begin(), v.end(), [](float a, float b) { return a < b || (a == b && std::signbit(a) && !std::signbit(b)); });
    amr::Percentiles p;
    p.count = v.size();
    if (!v.empty())
        for (size_t k = 0; k <= 100; ++k) p.values[k] = v[k * (v.size() - 1) / 100];
    return p;
}

void expectSameBits(const amr::Percentiles& a, const amr::Percentiles& b) {
    EXPECT_EQ(a.count, b.count);
    for (int k = 0; k <= 100; ++k)  // bit for bit: tells -0 from +0
        EXPECT_EQ(std::bit_cast<uint32_t>(a[k]), std::bit_cast<uint32_t>(b[k])) << "P" << k << ": " << a[k] << " vs " << b[k];
}

}  // namespace

TEST(ValuePercentiles, IntegersGiveTheirRanks) {
    // 0..100000 shuffled: the value of rank r is r, and P_k has rank k * 100000 / 100.
    std::vector<float> v(100001);
    std::iota(v.begin(), v.end(), 0.0f);
    std::shuffle(v.begin(), v.end(), std::mt19937(3));
    const amr::Percentiles p = amr::percentilesOf(v);
    EXPECT_EQ(p.count, v.size());
    for (int k = 0; k <= 100; ++k) EXPECT_EQ(p[k], float(1000 * k)) << k;
}

TEST(ValuePercentiles, ExponentialOrderStatisticsAndQuantiles) {
    // Cell values drawn at the midpoints of N equal slices of the exponential distribution, shifted
    // by -3 so signs differ: the sample's order statistics are known in closed form, and P_k lies
    // within a slice of the distribution's quantile -ln(1 - k/100) - 3.
    const size_t n = 123457;
    auto x = [&](size_t r) { return float(-std::log1p(-(double(r) + 0.5) / double(n)) - 3.0); };
    std::vector<float> v(n);
    for (size_t r = 0; r < n; ++r) v[r] = x(r);
    std::shuffle(v.begin(), v.end(), std::mt19937(5));
    const amr::Percentiles p = amr::percentilesOf(v);
    for (int k = 0; k <= 100; ++k) {
        EXPECT_EQ(p[k], x(size_t(k) * (n - 1) / 100)) << k;
        if (k < 100) {
            const double q = -std::log1p(-k / 100.0) - 3.0, slope = 1.0 / (1.0 - k / 100.0);
            EXPECT_NEAR(p[k], q, 2.0 * slope / double(n) + 1e-6) << k;
        }
    }
    EXPECT_LT(p.lo(), 0.0f);
    EXPECT_GT(p.hi(), 0.0f);
}

TEST(ValuePercentiles, EqualsSortingOnHardValues) {
    const float denormal = std::numeric_limits<float>::denorm_min();
    const std::vector<float> special = {0.0f,      -0.0f,     denormal, -denormal, 1e-38f,    -1e-38f, 3.0e38f,
                                        -3.0e38f,  INFINITY,  -INFINITY, NAN,       1.0f,     -1.0f,   1.0000001f,
                                        0.9999999f};
    std::mt19937 rng(11);
    // 300001 values: counted in several chunks.
    for (size_t n : {size_t(1), size_t(2), size_t(3), size_t(7), size_t(100), size_t(101), size_t(1000), size_t(65537),
                     size_t(300001)}) {
        for (int kind = 0; kind < 4; ++kind) {
            std::vector<float> v(n);
            for (float& x : v) {
                switch (kind) {
                    case 0: x = std::normal_distribution<float>(0.0f, 1e3f)(rng); break;
                    case 1: x = float(std::uniform_int_distribution<int>(-3, 3)(rng)); break;  // many duplicates
                    case 2: x = special[std::uniform_int_distribution<size_t>(0, special.size() - 1)(rng)]; break;
                    default: x = 42.0f;  // one value
                }
            }
            SCOPED_TRACE("n " + std::to_string(n) + ", kind " + std::to_string(kind));
            expectSameBits(amr::percentilesOf(v), bySorting(v));
        }
    }
}

TEST(ValuePercentiles, NoValuesGiveNoPercentiles) {
    const amr::Percentiles none = amr::percentilesOf({});
    EXPECT_EQ(none.count, 0u);
    EXPECT_EQ(none.hi(), 0.0f);
    const std::vector<float> nan(5, NAN);
    EXPECT_EQ(amr::percentilesOf(nan).count, 0u);
}

TEST(ValuePercentiles, PartsWithSummedCountsGiveTheWhole) {
    // Data-parallel MPI: each rank counts its own cells and the counts are summed; uneven parts, one
    // empty, and a part holding only duplicates of values in another.
    std::mt19937 rng(7);
    std::vector<float> all(30000);
    for (float& x : all) x = std::lognormal_distribution<float>(0.0f, 2.0f)(rng);
    for (size_t i = 0; i < 3000; ++i) all.push_back(all[i]);
    const std::vector<std::span<const float>> parts = {std::span<const float>(all).subspan(0, 5),
                                                        std::span<const float>(all).subspan(5, 0),
                                                        std::span<const float>(all).subspan(5, 29995),
                                                        std::span<const float>(all).subspan(30000)};
    amr::PercentileSelection s;
    int passes = 0;
    while (!s.done()) {
        std::vector<uint64_t> sum;
        for (std::span<const float> part : parts) {
            const std::vector<uint64_t> c = s.count(part);
            if (sum.empty()) sum.assign(c.size(), 0);
            ASSERT_EQ(c.size(), sum.size());
            for (size_t i = 0; i < c.size(); ++i) sum[i] += c[i];
        }
        s.advance(sum);
        ++passes;
    }
    EXPECT_EQ(passes, 3);
    expectSameBits(s.result(), amr::percentilesOf(all));
    expectSameBits(s.result(), bySorting(all));
    // One part's counts alone are another distribution's: not the whole's.
    EXPECT_NE(amr::percentilesOf(parts[2]), amr::percentilesOf(all));
}

TEST(ValuePercentiles, PooledFromThePartsPercentilesAreWithinOnePercentileOfTheWhole) {
    // Outputs of a series: unlike distributions and sizes, one with a plateau (40% zeros), one
    // empty; against the share of all the values at or below each pooled percentile, by counting.
    std::mt19937 rng(11);
    std::vector<std::vector<float>> outputs(5);
    for (int i = 0; i < 20000; ++i) outputs[0].push_back(std::exponential_distribution<float>(1.0f)(rng));
    for (int i = 0; i < 5000; ++i) outputs[1].push_back(std::normal_distribution<float>(50.0f, 5.0f)(rng));
    for (int i = 0; i < 50000; ++i) outputs[2].push_back(std::lognormal_distribution<float>(1.0f, 2.0f)(rng));
    for (int i = 0; i < 10000; ++i)
        outputs[3].push_back(i < 4000 ? 0.0f : std::uniform_real_distribution<float>(-3.0f, 80.0f)(rng));
    std::vector<amr::Percentiles> parts;
    std::vector<float> all;
    for (const std::vector<float>& o : outputs) {
        parts.push_back(amr::percentilesOf(o));
        all.insert(all.end(), o.begin(), o.end());
    }
    std::sort(all.begin(), all.end());
    const double n = double(all.size());
    // How far k/100 lies outside [share below v, share at or below v], in shares.
    auto rankError = [&](float v, int k) {
        const double below = double(std::lower_bound(all.begin(), all.end(), v) - all.begin()) / n;
        const double atOrBelow = double(std::upper_bound(all.begin(), all.end(), v) - all.begin()) / n;
        return std::max({0.0, below - k / 100.0, k / 100.0 - atOrBelow});
    };
    const amr::Percentiles pooled = amr::pooledPercentiles(parts);
    EXPECT_EQ(pooled.count, all.size());
    EXPECT_EQ(pooled.lo(), all.front());
    EXPECT_EQ(pooled.hi(), all.back());
    const double bound = 0.01 + double(parts.size()) / n;
    double worst = 0;
    for (int k = 0; k <= 100; ++k) {
        if (k > 0) {
            EXPECT_GE(pooled[k], pooled[k - 1]);
        }
        worst = std::max(worst, rankError(pooled[k], k));
        EXPECT_LE(rankError(pooled[k], k), bound) << "P" << k << " = " << pooled[k];
    }
    std::printf("pooled percentiles: largest rank error %.4f (bound %.4f)\n", worst, bound);
    // Power: the mean of the parts' percentiles, weighted by count, is far from the whole's.
    double meanWorst = 0;
    for (int k = 0; k <= 100; ++k) {
        double v = 0;
        for (const amr::Percentiles& p : parts) v += double(p.count) * p[k];
        meanWorst = std::max(meanWorst, rankError(float(v / n), k));
    }
    EXPECT_GT(meanWorst, 5 * bound);
    // One part is itself; no part, no values.
    EXPECT_EQ(amr::pooledPercentiles(std::span(parts).subspan(2, 1)), parts[2]);
    EXPECT_EQ(amr::pooledPercentiles(std::span(parts).subspan(4, 1)).count, 0u);
    const std::vector<amr::Percentiles> withEmpty = {parts[4], parts[2], parts[4]};
    EXPECT_EQ(amr::pooledPercentiles(withEmpty), parts[2]) << "the parts without values are skipped";
}

TEST(ValuePercentiles, CountsOfAnotherLengthAreRefused) {
    amr::PercentileSelection s;
    std::vector<uint64_t> c = s.count(std::vector<float>{1.0f, 2.0f});
    c.pop_back();
    test::expectError([&] { s.advance(c); }, {"percentile pass 1", "counts"});
}

TEST(ValuePercentiles, TheVolumeHoldsItsFieldsByCellCount) {
    // A coarse background of low values and a refined region of high ones: by volume the median is
    // the background's, by cell count it lies in the refined region.
    amr::Model m = test::makeRefinedModel(9, glm::ivec3(4, 4, 4), 3, 0.0);
    const size_t coarse = m.cells.size();
    const amr::Cell corner = m.cells.front();
    amr::CellArray rest;
    for (size_t i = 1; i < m.cells.size(); ++i) rest.push_back(m.cells[i]);
    m.cells.swap(rest);
    for (int z = 0; z < 8; ++z)
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 8; ++x) m.cells.push_back({corner.lower + glm::ivec3(x, y, z), 0});
    amr::Field f{"rho", {}};
    for (const amr::Cell& c : m.cells) f.values.push_back(c.level == 0 ? 10.0f + float(c.lower.x) : 0.5f);
    m.fields = {f};
    m.availableFields = {"rho"};
    ASSERT_GT(m.cells.size() - (coarse - 1), 4 * (coarse - 1));  // most cells are fine, most volume is coarse
    const std::shared_ptr<const scene::Volume> v = scene::makeVolume(m);
    expectSameBits(v->percentiles, bySorting(f.values));
    EXPECT_EQ(v->percentiles.lo(), v->valueLo());
    EXPECT_EQ(v->percentiles.hi(), v->valueHi());
    EXPECT_GE(v->percentiles[50], 10.0f);  // a volume-weighted median would be 0.5

    // --scale log: the percentiles are of the logs, the log of each linear percentile (same cells).
    amr::Model logs = m;
    amr::applyFieldScale(logs, amr::FieldScale::Log);
    const std::shared_ptr<const scene::Volume> lv = scene::makeVolume(std::move(logs));
    for (int k = 0; k <= 100; ++k)
        EXPECT_EQ(lv->percentiles[k], float(std::log10(double(v->percentiles[k])))) << k;
}
