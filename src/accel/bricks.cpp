#include "accel/bricks.h"

#include <algorithm>
#include <limits>

namespace amrvk::accel {

amr::Box3l Brick::bounds() const {
    glm::i64vec3 lo(lower);
    return {lo, lo + glm::i64vec3(size) * cellWidth()};
}

std::vector<float> brickOrderValues(const BrickSet& bricks, const amr::Field& field) {
    if (bricks.cellIds.empty()) return field.values;
    std::vector<float> out(bricks.slotCount());
    for (size_t i = 0; i < out.size(); ++i) {
        uint32_t id = bricks.cellIds[i];
        out[i] = id == BrickSet::kEmptySlot ? std::numeric_limits<float>::quiet_NaN()
                                            : field.values[id];
    }
    return out;
}

BrickStats computeBrickStats(const BrickSet& bricks) {
    BrickStats s;
    s.brickCount = bricks.bricks.size();
    for (const Brick& b : bricks.bricks) {
        s.singleCellBricks += b.cellCount() == 1;
        s.largestBrickCells = std::max(s.largestBrickCells, b.cellCount());
    }
    s.averageCellsPerBrick = s.brickCount ? double(bricks.slotCount()) / double(s.brickCount) : 0;
    return s;
}

}  // namespace amrvk::accel
