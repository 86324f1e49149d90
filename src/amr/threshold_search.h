#pragma once
// Choosing the refinement threshold t of a synthetic field for a target cell count (the three
// steps of amr/synthetic.h: best-first curve, depth-first counting passes, the writing pass as
// the last check). Knows nothing of the field: it drives the passes it is given.
// All counts are cells (blockCells^3 per leaf).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "amr/synthetic.h"

namespace amrvk::amr {

constexpr double kCountTolerance = 1.4;  // accepted count range [N / 1.4, 1.4 N]

// One measured point of the count-versus-threshold curve.
struct ThresholdSample {
    double t;
    uint64_t count;
    bool capped;  // the pass stopped early: count is a lower bound
};

struct FinalPass {
    uint64_t count;
    bool stopped;    // passed the cap: abandoned
    bool committed;  // accepted and kept
};

// The passes over one field (amr/octree_refine.h) that the search runs.
struct RefinementPasses {
    // Scores of the best-first expansion up to maxLeaves leaves (bestFirstScores).
    std::function<std::vector<float>(uint64_t maxLeaves, bool& exhausted)> bestFirst;
    // A depth-first counting pass at threshold t that stops past `cap` cells; `expected` and
    // `phase` are for progress. Returns the sample {t, count, stopped}.
    std::function<ThresholdSample(double t, uint64_t cap, uint64_t expected, const std::string& phase)> count;
    // The writing pass: keeps its result only when it neither passed `cap` nor fell below
    // `minAccept`, and reports what happened.
    std::function<FinalPass(float t, uint64_t cap, uint64_t minAccept)> write;
};

// Chooses the threshold for params.cells, then runs passes.write until one result is kept,
// retried with a corrected t. Sets stats.threshold and adds to stats.countingPasses.
void searchAndGenerate(const RefinementPasses& passes, int blockShift, const SyntheticParams& params,
                       SyntheticStats& stats);

}  // namespace amrvk::amr
