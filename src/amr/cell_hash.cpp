#include "amr/cell_hash.h"

#include <algorithm>
#include <bit>

#include "core/error.h"

namespace amrvk::amr {

namespace {
uint64_t hashKey(glm::ivec3 p, int32_t level) {
    uint64_t h = static_cast<uint32_t>(p.x) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<uint32_t>(p.y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= static_cast<uint32_t>(p.z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    h ^= static_cast<uint32_t>(level) * 0x27D4EB2F165667C5ull;
    h ^= h >> 29;
    h *= 0xBF58476D1CE4E5B9ull;
    return h ^ (h >> 32);
}
bool sameKey(const Cell& c, glm::ivec3 p, int32_t level) {
    return c.level == level && c.lower == p;
}
}  // namespace

CellHash::CellHash(const CellArray& cells) : mCells(cells) {
    AMRVK_CHECK(cells.size() < kNone, "too many cells for one model (", cells.size(), ", limit ",
                kNone - 1, ")");
    uint64_t capacity = std::bit_ceil(std::max<uint64_t>(16, cells.size() * 2));
    mSlots.assign(capacity, kNone);
    mMask = capacity - 1;
    uint64_t levelMask = 0;
    for (uint32_t i = 0; i < cells.size(); ++i) {
        const Cell& c = cells[i];
        if (c.level >= 0 && c.level < 64) levelMask |= uint64_t{1} << c.level;
        uint64_t slot = hashKey(c.lower, c.level) & mMask;
        while (mSlots[slot] != kNone) {
            if (sameKey(cells[mSlots[slot]], c.lower, c.level)) {
                if (mDuplicate == kNone) {
                    mDuplicate = i;
                    mDuplicateOf = mSlots[slot];
                }
                break;
            }
            slot = (slot + 1) & mMask;
        }
        if (mSlots[slot] == kNone) mSlots[slot] = i;
    }
    for (int32_t l = 0; l < 64; ++l)
        if (levelMask & (uint64_t{1} << l)) mLevels.push_back(l);
}

uint32_t CellHash::find(glm::ivec3 lower, int32_t level) const {
    uint64_t slot = hashKey(lower, level) & mMask;
    while (mSlots[slot] != kNone) {
        if (sameKey(mCells[mSlots[slot]], lower, level)) return mSlots[slot];
        slot = (slot + 1) & mMask;
    }
    return kNone;
}

}  // namespace amrvk::amr
