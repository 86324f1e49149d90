#pragma once
// Sub-majorants: where a transfer function makes a macrocell's majorant loose (a narrow peak of
// the TF inside the macrocell's value range: its alpha maximum M far above the alpha of most of
// the macrocell), the macrocell is split into n^3 equal sub-boxes (n = 2, 4, 8 or 16) with
// majorants of their own, built per TF from their exact value ranges (accel::SubRangeMaker).
// The tracker still steps with the macrocell's M. At a tentative collision it draws the uniform u
// of the acceptance test first and reads the sub-box's majorant m <= M: where u M >= m the
// collision is null whatever the field there (sigma <= m), so its lookup is skipped. The
// decisions, and so the picture, are those of delta tracking with M alone; only lookups go
// (lib/sub_majorants.glsl). Ratio tracking thins its collisions to those with u M < m and
// weights them with m: ratio tracking against the piecewise-constant majorant m.
//
// Which macrocells: a macrocell of majorant M (alpha) whose alpha averages m over its value range
// (its values taken as spread evenly) is R = M / m loose; a chord through it meets tau = M x its
// mean chord (in finest cells) tentative collisions, of which about tau max(1 / R, 1 / n) need a
// lookup once it is divided n per axis (a thin shell's sub-boxes are about n times tighter). The
// divisions are doubled where a byte saves the most lookups, loosest and deepest first, while a
// doubling saves at least kMinSavedLookups per chord (a smooth TF, or an optically thin
// macrocell, is left alone), up to the configuration's cap and the byte budget.
// GPU layout (MajorantsGpu::subRefinement, subMajorants): per macrocell a uint32 word,
// kNotRefined or (byte offset / 8) << 2 | (log2 n - 1); per refined macrocell n^3 bytes (x fastest)
// q = ceil(255 (1 + kHeadroom) a / M) clamped to [0, 255], a = the sub-box's alpha maximum:
// m = M q / 255 >= a, with room for the GPU's float rounding of M and of q / 255.
#include <atomic>
#include <cstdint>
#include <utility>
#include <vector>

#include "accel/range_grid.h"
#include "scene/transfer_function.h"

namespace amrvk::scene {

inline constexpr uint32_t kNotRefined = 0xffffffffu;
inline constexpr double kMinSavedLookups = 0.5;
inline constexpr double kHeadroom = 1e-4;

struct SubMajorantGrid {
    std::vector<uint32_t> words;  // per macrocell (empty: none refined)
    std::vector<uint32_t> bytes;  // the sub-boxes' q, four to a word, little end first
    uint64_t refined = 0;         // macrocells refined
    uint64_t subBoxes = 0;        // their sub-boxes
    uint64_t wanted = 0;          // bytes the looseness asked for before the budget
    bool cancelled = false;       // SubMajorantOptions::cancel stopped the build (nothing refined)
    double buildSeconds = 0;
    uint64_t memoryBytes() const { return (words.size() + bytes.size()) * sizeof(uint32_t); }
    // The refinement (n, 1 <= n <= 16; 1: not refined) and byte offset of macrocell `cell`.
    std::pair<int, uint64_t> refinementOf(size_t cell) const;
    // Sub-box s's q (0..255) of a refined macrocell `cell`, s in x-fastest order.
    uint32_t q(size_t cell, size_t s) const;
};

// The mean of the TF's alpha over the value interval [lo, hi] (its integral / (hi - lo); alpha(lo)
// where lo == hi), from prefix integrals at the nodes: O(log nodes) per call.
class AlphaMean {
public:
    explicit AlphaMean(const TransferFunction& tf);
    double operator()(float lo, float hi) const;

private:
    double integralTo(double v) const;  // of alpha from the first node to v (negative below it)
    const TransferFunction& mTf;
    std::vector<double> mPrefix;  // integral from node 0 to node i
};

struct SubMajorantOptions {
    int maxDivision = 8;       // largest n (2, 4, 8 or 16)
    // Checked between macrocells: once set, the build stops and returns what has no refinement.
    const std::atomic<bool>* cancel = nullptr;
    uint64_t budgetBytes = 0;  // the sub-boxes' bytes at most
    double chordInFinestCells = 1;  // a macrocell's mean chord in finest cell widths (chordOf)
};
// The mean chord of a macrocell of `grid` (2/3 of its mean side, a cube's mean chord) in widths of
// the finest cells (`finestCellWidth` voxel units): what an alpha-1 majorant costs a chord.
double chordOf(const accel::RangeGrid& grid, double finestCellWidth);

// Sub-majorants of `grid`'s macrocells under `tf` (ranges from `maker`, over the same layout).
SubMajorantGrid buildSubMajorants(const accel::RangeGrid& grid, const accel::SubRangeMaker& maker,
                                  const TransferFunction& tf, const SubMajorantOptions& options);

// The default budget: 16 MiB of sub-boxes whatever the grid, which bounds a TF edit's host work
// (about 0.2 us a sub-box on two cores: 3 s at most; docs/benchmarks.md section 27). A finer grid
// has tighter macrocells, so it needs the bytes less.
inline constexpr uint64_t kDefaultSubMajorantBudget = uint64_t(16) << 20;

}  // namespace amrvk::scene
