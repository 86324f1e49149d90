#include "scene/sub_majorants.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"
#include "core/stats.h"

namespace amrvk::scene {

std::pair<int, uint64_t> SubMajorantGrid::refinementOf(size_t cell) const {
    if (words.empty() || words[cell] == kNotRefined) return {1, 0};
    return {2 << (words[cell] & 3u), uint64_t(words[cell] >> 2) * 8};
}

uint32_t SubMajorantGrid::q(size_t cell, size_t s) const {
    const uint64_t byte = refinementOf(cell).second + s;
    return (bytes[byte / 4] >> (8 * (byte % 4))) & 255u;
}

AlphaMean::AlphaMean(const TransferFunction& tf) : mTf(tf) {
    const auto& p = tf.positions();
    const auto& c = tf.colors();
    mPrefix.assign(p.size(), 0.0);
    for (size_t i = 1; i < p.size(); ++i)
        mPrefix[i] = mPrefix[i - 1] + 0.5 * (double(c[i - 1].a) + double(c[i].a)) * (double(p[i]) - double(p[i - 1]));
}

double AlphaMean::integralTo(double v) const {
    const auto& p = mTf.positions();
    const auto& c = mTf.colors();
    if (v <= double(p.front())) return (v - double(p.front())) * double(c.front().a);
    if (v >= double(p.back())) return mPrefix.back() + (v - double(p.back())) * double(c.back().a);
    // Node i with p[i] <= v < p[i + 1] (the last of equal positions: a step's right node).
    const size_t i = size_t(std::upper_bound(p.begin(), p.end(), float(v)) - p.begin()) - 1;
    const double x0 = p[i], x1 = p[i + 1], a0 = c[i].a, a1 = c[i + 1].a;
    const double f = x1 > x0 ? (v - x0) / (x1 - x0) : 0.0;
    const double av = a0 + f * (a1 - a0);
    return mPrefix[i] + 0.5 * (a0 + av) * (v - x0);
}

double AlphaMean::operator()(float lo, float hi) const {
    if (!(lo < hi)) return double(mTf.evaluate(lo).a);
    return std::max(0.0, (integralTo(hi) - integralTo(lo)) / (double(hi) - double(lo)));
}

double chordOf(const accel::RangeGrid& grid, double finestCellWidth) {
    const glm::dvec3 s = grid.cellSize;
    return 2.0 / 3.0 * std::cbrt(s.x * s.y * s.z) / finestCellWidth;
}

namespace {

// Where the TF's alpha can be above 0: the closed value intervals between nodes with an end of
// alpha > 0 (merged), so that most sub-boxes of a spiky TF need no maxAlpha.
class AlphaSupport {
public:
    explicit AlphaSupport(const TransferFunction& tf) {
        const auto& p = tf.positions();
        const auto& c = tf.colors();
        auto add = [&](float lo, float hi) {
            if (!mLo.empty() && lo <= mHi.back()) mHi.back() = std::max(mHi.back(), hi);
            else {
                mLo.push_back(lo);
                mHi.push_back(hi);
            }
        };
        if (c.front().a > 0) add(-INFINITY, p.front());
        for (size_t i = 0; i + 1 < p.size(); ++i)
            if (c[i].a > 0 || c[i + 1].a > 0) add(p[i], p[i + 1]);
        if (c.back().a > 0) add(p.back(), INFINITY);
        if (p.size() == 1 && c[0].a > 0) add(-INFINITY, INFINITY);
    }
    // Whether [lo, hi] meets an interval (a NaN end: yes, as maxAlpha takes every node).
    bool meets(float lo, float hi) const {
        if (lo != lo || hi != hi) return true;
        if (lo > hi) return false;
        // The first interval ending at or above lo.
        const size_t i = size_t(std::lower_bound(mHi.begin(), mHi.end(), lo) - mHi.begin());
        return i < mLo.size() && mLo[i] <= hi;
    }

private:
    std::vector<float> mLo, mHi;  // ascending, disjoint
};

// The q of a sub-box of alpha maximum a in a macrocell of majorant M > 0.
uint32_t quantize(float a, float M) {
    if (!(a > 0.0f)) return 0;
    const double q = std::ceil(255.0 * (1.0 + kHeadroom) * double(a) / double(M));
    return uint32_t(std::clamp(q, 1.0, 255.0));
}

}  // namespace

SubMajorantGrid buildSubMajorants(const accel::RangeGrid& grid, const accel::SubRangeMaker& maker,
                                  const TransferFunction& tf, const SubMajorantOptions& options) {
    AMRVK_CHECK(options.maxDivision >= 2 && options.maxDivision <= accel::kMaxSubdivision &&
                    std::has_single_bit(unsigned(options.maxDivision)),
                "sub-majorants: a largest division of ", options.maxDivision, " is not 2, 4, 8 or 16");
    Timer timer;
    SubMajorantGrid out;
    // The loose macrocells and the division each asks for.
    struct Candidate {
        uint32_t cell;
        int n;             // division given so far (1: none)
        double looseness;  // R
        double depth;      // tau: the expected tentative collisions of a chord at the majorant
    };
    const AlphaMean mean(tf);
    const AlphaSupport support(tf);
    std::vector<Candidate> candidates;
    // Lookups a chord of a macrocell takes at division n: tau max(1 / R, 1 / n) (a thin shell's
    // sub-boxes are about n times tighter, down to the macrocell's mean alpha).
    auto lookups = [](const Candidate& c, int n) { return c.depth * std::max(1.0 / c.looseness, 1.0 / n); };
    auto wantsMore = [&](const Candidate& c) {
        return c.n < options.maxDivision && lookups(c, c.n) - lookups(c, 2 * c.n) >= kMinSavedLookups;
    };
    for (size_t i = 0; i < grid.ranges.size(); ++i) {
        const accel::ValueRange& r = grid.ranges[i];
        const float M = tf.maxAlpha(r.lo, r.hi);
        if (!(M > 0.0f) || !(r.lo < r.hi)) continue;
        const double m = mean(r.lo, r.hi);
        Candidate c{uint32_t(i), 1, m > 0 ? std::min(double(M) / m, 1e9) : 1e9, double(M) * options.chordInFinestCells};
        if (!wantsMore(c)) continue;
        candidates.push_back(c);
        int want = 2;
        while (want < options.maxDivision && lookups(c, want) - lookups(c, 2 * want) >= kMinSavedLookups) want *= 2;
        out.wanted += uint64_t(want) * uint64_t(want) * uint64_t(want);
    }
    // Divisions doubled where a byte saves the most lookups, until the budget is spent: doubling n
    // saves lookups(n) - lookups(2n) per chord for 7 n^3 more bytes. Each macrocell stops where a
    // doubling would save less than kMinSavedLookups per chord, or at the cap.
    auto gain = [&](const Candidate& c) { return (lookups(c, c.n) - lookups(c, 2 * c.n)) / (7.0 * c.n * c.n * c.n); };
    auto lower = [&](uint32_t a, uint32_t b) { return gain(candidates[a]) < gain(candidates[b]); };
    std::vector<uint32_t> heap;
    for (uint32_t k = 0; k < candidates.size(); ++k) heap.push_back(k);
    std::make_heap(heap.begin(), heap.end(), lower);
    uint64_t used = 0;  // bytes, each macrocell's rounded up to whole 8-byte words
    auto bytesOf = [](int n) { return n > 1 ? (uint64_t(n) * n * n + 7) / 8 * 8 : 0; };
    while (!heap.empty()) {
        std::pop_heap(heap.begin(), heap.end(), lower);
        Candidate& c = candidates[heap.back()];
        const uint64_t more = bytesOf(2 * c.n) - bytesOf(c.n);
        if (used + more > options.budgetBytes) {  // the largest steps stop first; smaller ones may fit
            heap.pop_back();
            continue;
        }
        used += more;
        c.n *= 2;
        if (wantsMore(c)) std::push_heap(heap.begin(), heap.end(), lower);
        else heap.pop_back();
    }
    std::vector<std::pair<Candidate, uint64_t>> chosen;  // with byte offsets (multiples of 8)
    uint64_t next = 0;
    for (const Candidate& c : candidates) {
        if (c.n < 2) continue;
        chosen.emplace_back(c, next);
        next += bytesOf(c.n);
    }
    if (chosen.empty()) {
        out.buildSeconds = timer.seconds();
        return out;
    }
    AMRVK_CHECK(used / 8 < (uint64_t(1) << 30), "sub-majorants: ", used, " bytes exceed the 8 GiB a word addresses");
    out.words.assign(grid.ranges.size(), kNotRefined);
    out.bytes.assign(used / 4, 0u);
    for (const auto& [c, offset] : chosen) {
        out.words[c.cell] = uint32_t(offset / 8) << 2 | uint32_t(std::countr_zero(unsigned(c.n)) - 1);
        out.subBoxes += uint64_t(c.n) * c.n * c.n;
    }
    out.refined = chosen.size();
    // Each macrocell's sub-boxes write their own bytes (offsets are multiples of 8: whole words).
    auto cancelled = [&] { return options.cancel && options.cancel->load(std::memory_order_relaxed); };
    parallelForRanges(0, chosen.size(), 1, [&](size_t begin, size_t end) {
        std::vector<accel::ValueRange> sub;
        for (size_t k = begin; k < end && !cancelled(); ++k) {
            const auto& [c, offset] = chosen[k];
            maker.ranges(c.cell, c.n, sub);
            const accel::ValueRange& r = grid.ranges[c.cell];
            const float M = tf.maxAlpha(r.lo, r.hi);
            for (size_t s = 0; s < sub.size(); ++s) {
                if (!support.meets(sub[s].lo, sub[s].hi)) continue;  // alpha 0 there: q = 0
                const uint64_t byte = offset + s;
                out.bytes[byte / 4] |= quantize(tf.maxAlpha(sub[s].lo, sub[s].hi), M) << (8 * (byte % 4));
            }
        }
    });
    if (cancelled()) {
        SubMajorantGrid none;
        none.cancelled = true;
        return none;
    }
    out.buildSeconds = timer.seconds();
    return out;
}

}  // namespace amrvk::scene
