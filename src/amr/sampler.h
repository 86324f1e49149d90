#pragma once
// CPU reference reconstruction (exabrick-reference.md 3.1), evaluated by brute force:
//   f(P) = sum_i phi_i(P) v_i / sum_i phi_i(P),  phi_i(P) = prod_d max(0, 1 - |P_d - c_i,d| / w_i)
// over every leaf cell i (centre c_i, width w_i). Candidates are found per level through an exact
// (lower, level) hash: on level l only the 2x2x2 cells with floor(P / w - 0.5) + {0,1} can reach P.
#include <glm/glm.hpp>

#include "amr/cell_hash.h"
#include "amr/model.h"

namespace amrvk::amr {

// A reconstructed value: weightSum == 0 (P outside every cell support) means "no data", value 0.
struct Sample {
    double value = 0;
    double weightSum = 0;
    bool valid() const { return weightSum > 0; }
    // From the sums of phi and phi * v: value = wv / w, or 0 when w == 0.
    static Sample fromSums(double w, double wv) { return {w > 0 ? wv / w : 0.0, w}; }
};

// Tent weight of a cell at voxel-space point p (0 outside its support).
double tentWeight(const Cell& cell, glm::dvec3 p);

// Indexes the model's cells by position: build bricks (which reorder the model) first; a sampler
// used after its model was reordered throws instead of reading the wrong cells.
class ReferenceSampler {
public:
    ReferenceSampler(const Model& model, const Field& field);
    // P in voxel space. NaN values (a model loaded with --nan drop has none) are skipped.
    Sample sample(glm::dvec3 p) const;
    // True when p lies in a leaf cell (closed box), i.e. in the medium.
    bool insideLeafCell(glm::dvec3 p) const;
    // Range of the values of the cells with positive weight at p (empty: lo > hi).
    void contributingRange(glm::dvec3 p, float& lo, float& hi) const;

private:
    template <typename Visit>
    void forEachContributing(glm::dvec3 p, Visit&& visit) const;
    void checkOrder() const;
    const Model& mModel;
    const Field& mField;
    CellHash mHash;
    uint64_t mCellOrder;  // model.cellOrder when the hash was built
};

}  // namespace amrvk::amr
