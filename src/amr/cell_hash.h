#pragma once
// Exact lookup of a leaf cell by (lower corner, level): open addressing over cell indices,
// 2-4 x 4 bytes per cell. Used by validation (overlaps) and the brute-force reconstruction.
#include <cstdint>
#include <span>
#include <vector>

#include "amr/model.h"

namespace amrvk::amr {

class CellHash {
public:
    static constexpr uint32_t kNone = UINT32_MAX;

    explicit CellHash(const CellArray& cells);  // held by reference

    // Index of the cell with exactly this lower corner and level, or kNone.
    uint32_t find(glm::ivec3 lower, int32_t level) const;
    // Index of a cell that was inserted with the same key before `index`, or kNone (duplicates).
    uint32_t firstDuplicate() const { return mDuplicate; }
    uint32_t duplicateOf() const { return mDuplicateOf; }
    // Sorted distinct levels present.
    const std::vector<int32_t>& levels() const { return mLevels; }

private:
    const CellArray& mCells;
    std::vector<uint32_t> mSlots;
    uint64_t mMask = 0;
    std::vector<int32_t> mLevels;
    uint32_t mDuplicate = kNone, mDuplicateOf = kNone;
};

}  // namespace amrvk::amr
