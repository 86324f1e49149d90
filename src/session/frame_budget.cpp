#include "session/frame_budget.h"

#include <algorithm>
#include <cmath>

namespace amrvk::session {

void FrameBudget::record(double seconds, uint64_t pixelSamples) {
    if (!(seconds > 0) || pixelSamples == 0) return;
    const double cost = seconds / double(pixelSamples);
    // Follow the measurement quickly (scenes and views change what a sample costs).
    mCost = mMeasured ? 0.5 * mCost + 0.5 * cost : cost;
    mMeasured = true;
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

uint32_t FrameBudget::rowsPerFrame(int width, int height) const {
    const double rowCost = double(std::max(width, 1)) * mCost;
    const double rows = std::floor(mBudget / rowCost);
    return uint32_t(std::clamp(rows, 1.0, double(std::max(height, 1))));
}

}  // namespace amrvk::session
