#pragma once
// The non-interactive majorant kd-tree ("offline binned-SAH kd-tree", exabrick-reference.md 4.2):
// disjoint boxes tiling the data bounds, each with the exact value range of the cells whose tent
// support reaches it and the alpha majorant of that range under ONE transfer function (rebuild it
// when the TF changes). Voxel space; every split plane lies on an integer voxel coordinate.
// Greedy: the leaf of largest cost SA(box) * diag(box) * mu(box) is split at the best of 7 binned
// planes per axis, where mu = maxAlpha(range of box); leaves with mu = 0 are never split.
#include <cstdint>
#include <functional>
#include <vector>

#include "accel/bvh.h"
#include "accel/support_range.h"
#include "accel/value_range.h"
#include "amr/model.h"

namespace amrvk::accel {

struct KdTreeParams {
    uint32_t maxLeaves = 4096;  // --kd-leaves; >= 1
};

struct KdTree {
    // Disjoint boxes that tile `bounds` exactly; every plane on an integer voxel coordinate.
    std::vector<BoxD> leaves;
    // The majorant range of the leaf (SupportRangeQuery::majorantRange with positionMargin of the
    // root): every cell whose support reaches the leaf grown by the margin, padded for the GPU.
    std::vector<ValueRange> leafRanges;
    // maxAlpha(leafRanges[i]) with the TF the tree was built for (0 for an empty range).
    std::vector<float> leafMajorants;
    // The root: the union of leaf cells (never an empty default box: the upstream bug).
    amr::Box3l bounds;
    double buildSeconds = 0;
    uint64_t memoryBytes() const {
        return leaves.size() * sizeof(BoxD) + leafRanges.size() * sizeof(ValueRange) +
               leafMajorants.size() * sizeof(float);
    }
};

// maxAlpha(lo, hi): exact maximum of the TF's alpha over [lo, hi] (the renderer passes
// TransferFunction::maxAlpha); called only for non-empty ranges, must return a finite value >= 0.
// bounds: the root box, half-open voxel space; pass the union of the leaf cells
// (amr::summarize(model).bounds). Throws amrvk::Error for an empty bounds box, maxLeaves == 0
// (naming --kd-leaves) or a negative/non-finite maxAlpha. Never more than maxLeaves leaves;
// fewer only when every leaf with mu > 0 is one voxel wide on every axis.
KdTree buildKdTree(const SupportRangeQuery& ranges, const amr::Box3l& bounds,
                   const std::function<float(float, float)>& maxAlpha, const KdTreeParams& params);

}  // namespace amrvk::accel
