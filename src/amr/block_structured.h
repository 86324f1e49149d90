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

// The steps every block-structured reader shares around its format-specific parsing:

// Selects the fields to load from model.availableFields (selectFields, errors naming
// model.source), appends an empty entry per selected field to model.fields and returns the
// selected fields' indices in model.availableFields (the components to read), in order.
std::vector<size_t> addSelectedFields(Model& model, const std::vector<std::string>& requested);

// ratios.size() + 1 empty levels, each with its cell width in finest-level cells set
// (BlockLevel::cellWidth): the product of the refinement ratios from that level down to the
// finest; ratios[l] refines level l into l + 1. Checked from the finest ratio down; throws
// "SOURCE: refinement ratio R from level L to L+1 is not a power of two" or "SOURCE: refinement
// ratios multiply to more than 2^30".
std::vector<BlockLevel> levelsWithCellWidths(const std::vector<int>& ratios, const std::string& source);

// The values of a box of `dims` cells that starts `offset` cells into a stored box of `stored`
// cells (ghost cells, a FAB's grown box), x fastest; valueAt(i) converts stored element i (the
// stored box's own x-fastest index) to float.
template <class ValueAt>
std::vector<float> cropBox(glm::ivec3 stored, glm::ivec3 offset, glm::ivec3 dims, ValueAt&& valueAt) {
    std::vector<float> values;
    values.reserve(size_t(dims.x) * size_t(dims.y) * size_t(dims.z));
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x)
                values.push_back(valueAt((size_t(z + offset.z) * size_t(stored.y) + size_t(y + offset.y)) *
                                             size_t(stored.x) +
                                         size_t(x + offset.x)));
    return values;
}

// Number of blocks of each level, in `levels` order (the boxes/grids per level attribute).
std::vector<size_t> blockCounts(const std::vector<BlockLevel>& levels);

}  // namespace amrvk::amr
