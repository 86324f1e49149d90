#pragma once
// Block-structured AMR (AMReX, Chombo, Enzo) -> leaf cells in the ExaBrick convention.
//
// Nesting assumption (proper nesting, as AMReX, Chombo and Enzo guarantee): every block lies
// inside the blocks of the next coarser level. So a level's cells are covered only by the blocks
// of the NEXT finer level (the level with the largest cell width below its own); deeper levels
// are not consulted and need only be aligned to the cells of their own next coarser level (an
// Enzo level-2 grid sits on level-1 cell boundaries, not necessarily on level-0 ones). A covered
// cell is dropped, so only leaf cells remain. Data that is not properly nested yields overlapping
// leaves, which validate() reports.
#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "amr/model.h"

namespace amrvk::amr {

// Inclusive integer box in one level's index space; 2-D boxes have z = 0..0.
struct IndexBox {
    glm::ivec3 lo{0}, hi{0};
    glm::ivec3 dims() const { return hi - lo + 1; }
    size_t cellCount() const {
        const glm::ivec3 d = dims();
        return size_t(d.x) * size_t(d.y) * size_t(d.z);
    }
    bool contains(const IndexBox& o) const {
        return glm::all(glm::lessThanEqual(lo, o.lo)) && glm::all(glm::greaterThanEqual(hi, o.hi));
    }
};

struct Block {
    glm::ivec3 lo{0}, hi{0};                 // inclusive cell index bounds in the level's index space
    std::vector<std::vector<float>> values;  // [field][cell], x fastest, then y, then z
    glm::ivec3 dims() const { return hi - lo + 1; }
};

struct BlockLevel {
    int64_t cellWidth = 1;       // width of this level's cells in finest-level units (power of 2)
    glm::ivec3 indexOrigin{0};   // index of the domain's lower corner on this level (subtracted)
    std::vector<Block> blocks;
};

// Appends the leaf cells of `levels` (any order; levels of equal width act as one level) and
// their values to model.cells / model.fields (model.fields must already hold one entry per field).
// Cells are appended level by level in `levels` order, block by block, x fastest.
// planar: 2-D data as a one-cell-thick slab. Every block is one cell thick in z and each of its
// cells is one cell of its own level thick (z in [0, cellWidth)); coverage and alignment use x
// and y only.
// Throws if a cell width is not a power of two, if a block's value count does not match its box,
// if a planar block is thicker than one cell, or if a block of the next finer level covers a cell
// only partly. Cell widths, boxes and value counts are all checked before any cell is appended.
void appendLeafCells(Model& model, const std::vector<BlockLevel>& levels, bool planar = false);

// Fields to load: all of `available` when `requested` is empty, else `requested` in order.
// Throws "SOURCE: unknown field 'X' (available: ...)" for a name not in `available`.
std::vector<std::string> selectFields(const std::vector<std::string>& available,
                                      const std::vector<std::string>& requested,
                                      const std::string& source);

}  // namespace amrvk::amr
