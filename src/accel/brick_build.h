#pragma once
// The brick build: the kd build over the model's own arrays that makes its bricks (accel/bricks.h)
// and puts the model in brick order. Its split choice is accel/brick_split.h, its planned top
// levels accel/brick_plan.h.
#include <cstddef>

#include "accel/bricks.h"
#include "amr/model.h"

namespace amrvk::accel {

// Builds bricks with the exaBuilder SAH-alike kd split: partition at coarse-cell planes where the
// level set or fullness changes, minimising halfArea(L) * volume(L) * levels(L) + same(R); a node
// becomes a brick when it is one level, completely filled, and at most kMaxBrickCells per axis.
// Reorders model.cells and every field, in place, into brick order (x fastest inside a brick), so
// no per-cell copy is made and cellIds stays empty. Finds overlapping cells on the way (cells in
// different bricks lie in disjoint kd regions; within a brick two cells on one slot, or a node
// inside one cell of its own) and throws "SOURCE: overlapping cells: (lower ..) lies inside (..)";
// the model is then some permutation of itself. The order is a function of the set of cells, so
// building again (or from any file order) gives the same model and bricks.
//
// Where a node's cube grid (its cells' statistics per coarsest cell) decides its top levels, the
// build plans them on the grid and moves the cells once (a multi-way partition) instead of once per
// level; the bricks and the order are the same either way.
struct BrickBuildTuning {
    size_t planCells = size_t{1} << 16;  // nodes of at least this many cells are planned; SIZE_MAX: never
};
// `known`: the model's summary where the caller has it (scene::makeVolume), which saves the
// build's first pass over the cells; it must be summarize(model).
BrickSet buildBricks(amr::Model& model, const BrickBuildTuning& tuning = {}, const amr::ModelSummary* known = nullptr);

}  // namespace amrvk::accel
