#pragma once
// Space partitions of AMR data over MPI ranks (data-parallel rendering, docs/mpi.md): a census of
// the cells (streamed: bounds, levels, the field's range and cell counts on a grid of bins aligned
// to the coarsest cells), boxes that split the domain into `parts` with about equal cell counts
// (recursive bisection, any number of parts), and the cells a part needs: those whose tent support
// reaches into its box (its own and a halo of neighbours' cells near its faces). Boxes are in
// voxel space, aligned to the bins; a face may cut through cells of any level.
#include <filesystem>
#include <vector>

#include "amr/model.h"
#include "amr/readers.h"

namespace amrvk::amr {

struct CellCensus {
    uint64_t cells = 0;
    Box3l bounds;  // union of the cells (voxel space)
    int minLevel = kMaxLevel, maxLevel = 0;
    float valueLo = 0, valueHi = 0;  // the field's range
    FieldScale scale = FieldScale::Linear;  // the scale resolved (amr::resolvedScale), for readPart too
    double logFloor = 0;             // --scale log: the floor used (amr::logFloorOf), for readPart too
    Model head;                      // the source's metadata (no cells)
    // Cells counted by the bin holding their lower corner: bins of binWidth voxels (a power of two)
    // from binOrigin, at most kMaxBins per axis.
    static constexpr int kMaxBins = 128;
    glm::i64vec3 binOrigin{0};
    int64_t binWidth = 1;
    glm::ivec3 bins{0};
    std::vector<uint64_t> counts;  // x fastest
};

// Two streamed passes over the cells of `path` (amr::visitCells): bounds and levels, then the bin
// counts and the field's range. Memory: one chunk and the bins.
CellCensus censusOf(const std::filesystem::path& path, const ReadOptions& options);
// The same for cells in memory (tests; the Python module).
CellCensus censusOf(const Model& model);

// `parts` boxes (in bins of the census, converted to voxel space) that cover the census bounds
// without overlap, with cell counts as equal as bin-aligned faces allow: the longest axis of a box
// is cut where the cells left of the plane come closest to parts_left / parts of the box's cells.
// Throws a one-line error when the data has fewer occupied bins than parts.
std::vector<Box3l> partitionByCells(const CellCensus& census, int parts);

// Whether the tent support of cell c (its box grown by half its width, open) meets `box`: the cells
// the reconstruction inside `box` uses.
inline bool supportMeets(const Cell& c, const Box3l& box) {
    const int64_t w = cellWidth(c.level);
    for (int a = 0; a < 3; ++a) {  // in doubled units: support (2 lo - w, 2 lo + 3 w)
        const int64_t lo2 = 2 * int64_t(c.lower[a]);
        if (lo2 - w >= 2 * box.upper[a] || lo2 + 3 * w <= 2 * box.lower[a]) return false;
    }
    return true;
}
// Whether `box` holds the cell's lower corner (each cell has one owner among disjoint boxes).
inline bool ownsCell(const Box3l& box, const Cell& c) {
    const glm::i64vec3 lo(c.lower);
    return glm::all(glm::greaterThanEqual(lo, box.lower)) && glm::all(glm::lessThan(lo, box.upper));
}

// The cells of `path` whose support meets `box`, with the one field options.fields names, read by
// streaming (amr::visitCells): an ExaBrick file is never held whole.
Model readPart(const std::filesystem::path& path, const ReadOptions& options, const Box3l& box);

}  // namespace amrvk::amr
