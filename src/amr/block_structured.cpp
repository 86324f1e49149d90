#include "amr/block_structured.h"

#include <algorithm>
#include <bit>
#include <string_view>
#include <unordered_map>

#include "core/error.h"
#include "core/strings.h"

namespace amrvk::amr {

namespace {

// Half-open box in finest-level units.
struct FinestBox {
    glm::i64vec3 lo, hi;
};

FinestBox finestBox(const Block& b, const BlockLevel& level) {
    const glm::i64vec3 origin(level.indexOrigin);
    return {(glm::i64vec3(b.lo) - origin) * level.cellWidth,
            (glm::i64vec3(b.hi) + int64_t{1} - origin) * level.cellWidth};
}

// Checks widths, boxes and value counts of every block before any cell is appended.
void checkLevels(const Model& model, const std::vector<BlockLevel>& levels, bool planar) {
    const size_t fieldCount = model.fields.size();
    for (size_t li = 0; li < levels.size(); ++li) {
        const BlockLevel& level = levels[li];
        AMRVK_CHECK(
            level.cellWidth > 0 && std::has_single_bit(static_cast<uint64_t>(level.cellWidth)),
            model.source, ": level ", li, " has cell width ", level.cellWidth,
            " finest cells, not a power of two (refinement ratios must be powers of 2)");
        for (size_t bi = 0; bi < level.blocks.size(); ++bi) {
            const Block& block = level.blocks[bi];
            const glm::ivec3 d = block.dims();
            AMRVK_CHECK(d.x > 0 && d.y > 0 && d.z > 0, model.source, ": level ", li, " block ", bi,
                        " has an empty box");
            AMRVK_CHECK(!planar || d.z == 1, model.source, ": level ", li, " block ", bi, " is ",
                        d.z, " cells thick in z (2-D blocks must be one cell thick)");
            const size_t n = size_t(d.x) * size_t(d.y) * size_t(d.z);
            AMRVK_CHECK(block.values.size() == fieldCount, model.source, ": level ", li, " block ",
                        bi, " has ", block.values.size(), " fields, expected ", fieldCount);
            for (const auto& v : block.values)
                AMRVK_CHECK(v.size() == n, model.source, ": level ", li, " block ", bi, " has ",
                            v.size(), " values for ", n, " cells");
        }
    }
}

}  // namespace

std::vector<std::string> selectFields(const std::vector<std::string>& available,
                                      const std::vector<std::string>& requested,
                                      const std::string& source) {
    if (requested.empty()) return available;
    for (const std::string& r : requested)
        AMRVK_CHECK(std::find(available.begin(), available.end(), r) != available.end(), source,
                    ": unknown field '", r, "' (available: ", join(available, ", "), ")");
    return requested;
}

std::vector<size_t> addSelectedFields(Model& model, const std::vector<std::string>& requested) {
    const std::vector<std::string> selected = selectFields(model.availableFields, requested, model.source);
    // Each name's first index, found in one pass: a file naming tens of thousands of components
    // (RAMSES's nvar, AMReX's ncomp) costs linear time, not quadratic.
    std::unordered_map<std::string_view, size_t> index;
    for (size_t i = 0; i < model.availableFields.size(); ++i) index.emplace(model.availableFields[i], i);
    std::vector<size_t> components;
    for (const std::string& name : selected) {
        components.push_back(index.at(name));
        model.fields.push_back({name, {}});
    }
    return components;
}

std::vector<BlockLevel> levelsWithCellWidths(const std::vector<int>& ratios, const std::string& source) {
    std::vector<BlockLevel> levels(ratios.size() + 1);  // cellWidth 1 each
    for (size_t l = ratios.size(); l-- > 0;) {
        const int r = ratios[l];
        AMRVK_CHECK(r > 0 && std::has_single_bit(static_cast<unsigned>(r)), source, ": refinement ratio ", r,
                    " from level ", l, " to ", l + 1, " is not a power of two");
        levels[l].cellWidth = levels[l + 1].cellWidth * r;
        AMRVK_CHECK(levels[l].cellWidth <= (int64_t{1} << kMaxLevel), source,
                    ": refinement ratios multiply to more than 2^", kMaxLevel);
    }
    return levels;
}

std::vector<size_t> blockCounts(const std::vector<BlockLevel>& levels) {
    std::vector<size_t> counts;
    for (const BlockLevel& level : levels) counts.push_back(level.blocks.size());
    return counts;
}

void appendLeafCells(Model& model, const std::vector<BlockLevel>& levels, bool planar) {
    checkLevels(model, levels, planar);
    const size_t fieldCount = model.fields.size();
    const int axes = planar ? 2 : 3;  // axes that coverage and alignment look at
    for (size_t li = 0; li < levels.size(); ++li) {
        const BlockLevel& level = levels[li];
        const int64_t w = level.cellWidth;
        const int32_t exaLevel = std::countr_zero(static_cast<uint64_t>(w));
        // The next finer level: the largest cell width below this one (0: none).
        int64_t nextWidth = 0;
        for (const BlockLevel& other : levels)
            if (other.cellWidth < w) nextWidth = std::max(nextWidth, other.cellWidth);

        for (size_t bi = 0; bi < level.blocks.size(); ++bi) {
            const Block& block = level.blocks[bi];
            const glm::ivec3 d = block.dims();
            const size_t n = size_t(d.x) * size_t(d.y) * size_t(d.z);
            const FinestBox me = finestBox(block, level);

            // Coverage mask: 1 where a block of the next finer level covers the cell.
            std::vector<uint8_t> covered(n, 0);
            for (size_t lj = 0; lj < levels.size() && nextWidth > 0; ++lj) {
                if (levels[lj].cellWidth != nextWidth) continue;
                for (size_t fi = 0; fi < levels[lj].blocks.size(); ++fi) {
                    const FinestBox f = finestBox(levels[lj].blocks[fi], levels[lj]);
                    // Overlap relative to this block's corner, finest units (z whole if planar).
                    glm::i64vec3 lo(0), hi(me.hi - me.lo);
                    for (int a = 0; a < axes; ++a) {
                        lo[a] = std::max(f.lo[a], me.lo[a]) - me.lo[a];
                        hi[a] = std::min(f.hi[a], me.hi[a]) - me.lo[a];
                    }
                    if (lo.x >= hi.x || lo.y >= hi.y || lo.z >= hi.z) continue;
                    for (int a = 0; a < axes; ++a)
                        AMRVK_CHECK(lo[a] % w == 0 && hi[a] % w == 0, model.source,
                                    ": a finer block covers a level ", li, " cell of block ", bi,
                                    " only partly (level ", lj, " block ", fi, " of cell width ",
                                    nextWidth, " is not aligned to cell width ", w, ")");
                    const glm::i64vec3 c0 = lo / w, c1 = hi / w;  // cells [c0, c1) of this block
                    for (int64_t z = c0.z; z < c1.z; ++z)
                        for (int64_t y = c0.y; y < c1.y; ++y)
                            std::fill_n(covered.begin() + (z * d.y + y) * d.x + c0.x, c1.x - c0.x,
                                        uint8_t{1});
                }
            }

            for (int32_t z = 0; z < d.z; ++z)
                for (int32_t y = 0; y < d.y; ++y)
                    for (int32_t x = 0; x < d.x; ++x) {
                        const size_t i =
                            (size_t(z) * size_t(d.y) + size_t(y)) * size_t(d.x) + size_t(x);
                        if (covered[i]) continue;
                        glm::i64vec3 lower = me.lo + glm::i64vec3(x, y, z) * w;
                        if (planar) lower.z = 0;
                        AMRVK_CHECK(
                            glm::all(glm::greaterThanEqual(lower, glm::i64vec3(INT32_MIN))) &&
                                glm::all(glm::lessThan(lower, glm::i64vec3(INT32_MAX))),
                            model.source, ": cell corner outside the 32-bit voxel range");
                        model.cells.push_back({glm::ivec3(lower), exaLevel});
                        for (size_t f = 0; f < fieldCount; ++f)
                            model.fields[f].values.push_back(block.values[f][i]);
                    }
        }
    }
}

}  // namespace amrvk::amr
