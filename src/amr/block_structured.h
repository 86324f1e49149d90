#pragma once
// Block-structured AMR (AMReX, Chombo, Enzo) -> leaf cells. A coarse cell covered by a block of
// any finer level is dropped, so only leaf cells remain (the ExaBrick convention).
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "amr/model.h"

namespace amrvk::amr {

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

// Appends the leaf cells of `levels` (any order) and their values to model.cells / model.fields
// (model.fields must already hold one entry per field, values empty). Throws if a cell width is
// not a power of two, if a block's value count does not match its box, or if a finer block covers
// a coarse cell only partly.
void appendLeafCells(Model& model, const std::vector<BlockLevel>& levels);

// Fields to load: all of `available` when `requested` is empty, else `requested` in order.
// Throws "SOURCE: unknown field 'X' (available: ...)" for a name not in `available`.
std::vector<std::string> selectFields(const std::vector<std::string>& available,
                                      const std::vector<std::string>& requested,
                                      const std::string& source);

}  // namespace amrvk::amr
