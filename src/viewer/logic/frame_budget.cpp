#include "viewer/logic/frame_budget.h"

#include <algorithm>
#include <cmath>

namespace amrvk::viewer {

void FrameBudget::record(double seconds, uint64_t pixelSamples) {
    if (!(seconds > 0) || pixelSamples == 0) return;
    const double cost = seconds / double(pixelSamples);
    // Follow the measurement quickly (scenes and views change what a sample costs).
    mCost = mMeasured ? 0.5 * mCost + 0.5 * cost : cost;
    mMeasured = true;
}

void FrameBudget::recordRows(double seconds, uint32_t firstRow, uint32_t rows, int width, int height) {
    if (!(seconds > 0) || rows == 0 || width <= 0 || height <= 0) return;
    record(seconds, uint64_t(rows) * uint64_t(width));
    if (mRowWidth != width || mRowCost.size() != size_t(height)) {
        mRowWidth = width;
        mRowCost.assign(size_t(height), 0.0);
    }
    const uint32_t end = std::min(firstRow + rows, uint32_t(height));
    for (uint32_t r = firstRow; r < end; ++r) mRowCost[r] = seconds / double(rows);
}

void FrameBudget::recordOtherWork(double seconds) {
    if (!(seconds >= 0)) return;
    mOther = 0.8 * mOther + 0.2 * seconds;
    mBudget = std::max(0.1 * mFrame, mFrame - mOther);
}

int FrameBudget::previewScale(int width, int height) const {
    const double pixels = double(std::max(width, 1)) * double(std::max(height, 1));
    int scale = 1;
    while (scale < 32 && pixels / double(scale * scale) * mCost > mBudget) scale *= 2;
    return scale;
}

uint32_t FrameBudget::rowsPerFrame(int width, int height, uint32_t firstRow) const {
    const uint32_t h = uint32_t(std::max(height, 1));
    if (firstRow >= h) return 1;
    const double meanRow = double(std::max(width, 1)) * mCost;
    const bool profiled = mRowWidth == width && mRowCost.size() == size_t(h);
    double spent = 0;
    uint32_t r = firstRow;
    for (; r < h; ++r) {
        const double c = profiled && mRowCost[r] > 0 ? mRowCost[r] : meanRow;
        if (spent + c > mBudget) break;
        spent += c;
    }
    return std::max(r - firstRow, 1u);
}

}  // namespace amrvk::viewer
