#include "amr/block_structured.h"

#include <algorithm>
#include <bit>

#include "core/error.h"

namespace amrvk::amr {

namespace {
struct FinestBox {
    glm::i64vec3 lo, hi;  // half-open, finest units
};
FinestBox finestBox(const Block& b, const BlockLevel& level) {
    glm::i64vec3 lo = (glm::i64vec3(b.lo) - glm::i64vec3(level.indexOrigin)) * level.cellWidth;
    glm::i64vec3 hi = (glm::i64vec3(b.hi) + int64_t{1} - glm::i64vec3(level.indexOrigin)) *
                      level.cellWidth;
    return {lo, hi};
}
int64_t floorDiv(int64_t a, int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
}  // namespace

std::vector<std::string> selectFields(const std::vector<std::string>& available,
                                      const std::vector<std::string>& requested,
                                      const std::string& source) {
    if (requested.empty()) return available;
    for (const std::string& r : requested) {
        if (std::find(available.begin(), available.end(), r) != available.end()) continue;
        std::string list;
        for (const auto& a : available) list += (list.empty() ? "" : ", ") + a;
        AMRVK_CHECK(false, source, ": unknown field '", r, "' (available: ", list, ")");
    }
    return requested;
}

void appendLeafCells(Model& model, const std::vector<BlockLevel>& levels) {
    const size_t fieldCount = model.fields.size();
    for (size_t li = 0; li < levels.size(); ++li) {
        const BlockLevel& level = levels[li];
        AMRVK_CHECK(level.cellWidth > 0 && std::has_single_bit(static_cast<uint64_t>(level.cellWidth)),
                    model.source, ": level ", li, " has cell width ", level.cellWidth,
                    " finest cells, not a power of two (refinement ratios must be powers of 2)");
        const int32_t exaLevel = std::countr_zero(static_cast<uint64_t>(level.cellWidth));
        for (size_t bi = 0; bi < level.blocks.size(); ++bi) {
            const Block& block = level.blocks[bi];
            glm::ivec3 d = block.dims();
            AMRVK_CHECK(d.x > 0 && d.y > 0 && d.z > 0, model.source, ": level ", li, " block ", bi,
                        " has an empty box");
            const size_t n = size_t(d.x) * size_t(d.y) * size_t(d.z);
            AMRVK_CHECK(block.values.size() == fieldCount, model.source, ": level ", li,
                        " block ", bi, " has ", block.values.size(), " fields, expected ",
                        fieldCount);
            for (const auto& v : block.values)
                AMRVK_CHECK(v.size() == n, model.source, ": level ", li, " block ", bi, " has ",
                            v.size(), " values for ", n, " cells");
            // Mark the cells covered by finer blocks.
            std::vector<uint8_t> covered(n, 0);
            const FinestBox me = finestBox(block, level);
            for (const BlockLevel& finer : levels) {
                if (finer.cellWidth >= level.cellWidth) continue;
                for (const Block& fb : finer.blocks) {
                    FinestBox f = finestBox(fb, finer);
                    glm::i64vec3 lo = glm::max(f.lo, me.lo), hi = glm::min(f.hi, me.hi);
                    if (lo.x >= hi.x || lo.y >= hi.y || lo.z >= hi.z) continue;
                    const int64_t w = level.cellWidth;
                    for (int a = 0; a < 3; ++a)
                        AMRVK_CHECK((lo[a] - me.lo[a]) % w == 0 && (hi[a] - me.lo[a]) % w == 0,
                                    model.source, ": a finer block covers a level ", li,
                                    " cell of block ", bi, " only partly (not aligned)");
                    glm::i64vec3 c0, c1;
                    for (int a = 0; a < 3; ++a) {
                        c0[a] = floorDiv(lo[a] - me.lo[a], w);
                        c1[a] = floorDiv(hi[a] - me.lo[a], w);
                    }
                    for (int64_t z = c0.z; z < c1.z; ++z)
                        for (int64_t y = c0.y; y < c1.y; ++y)
                            for (int64_t x = c0.x; x < c1.x; ++x)
                                covered[size_t((z * d.y + y) * d.x + x)] = 1;
                }
            }
            for (int32_t z = 0; z < d.z; ++z)
                for (int32_t y = 0; y < d.y; ++y)
                    for (int32_t x = 0; x < d.x; ++x) {
                        size_t i = (size_t(z) * d.y + y) * d.x + x;
                        if (covered[i]) continue;
                        glm::i64vec3 lower = me.lo + glm::i64vec3(x, y, z) * level.cellWidth;
                        AMRVK_CHECK(glm::all(glm::greaterThanEqual(lower, glm::i64vec3(INT32_MIN))) &&
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
