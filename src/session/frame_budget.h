#pragma once
// How much path tracing one viewer frame may do, so that the UI and the camera stay above 15
// frames/s whatever one sample costs (a second at full resolution on lavapipe, a millisecond on a
// GPU). It keeps a running estimate of the GPU seconds per pixel-sample and answers two questions:
// while the user interacts, how much to shrink the image so a whole preview sample fits in the
// budget; when they stop, how many rows of the full image to trace this frame (time-budgeted
// tiles). Window-free; the viewer feeds it the measured GPU time of what it dispatched.
#include <cstdint>

namespace amrvk::session {

class FrameBudget {
public:
    // budgetSeconds: path-tracing time per frame (default 1/20 s: with the UI, >= 15 frames/s).
    explicit FrameBudget(double budgetSeconds = 0.05) : mBudget(budgetSeconds) {}

    // The last dispatch took `seconds` for `pixelSamples` pixel-samples.
    void record(double seconds, uint64_t pixelSamples);
    double secondsPerPixelSample() const { return mCost; }
    double budgetSeconds() const { return mBudget; }

    // Downscale factor (1, 2, 4, 8, 16, 32) of a width x height preview so one sample of it fits.
    int previewScale(int width, int height) const;
    // Rows of a width x height image to trace this frame: at least 1, at most height.
    uint32_t rowsPerFrame(int width, int height) const;

private:
    double mBudget;
    double mCost = 2e-6;  // s per pixel-sample until measured: lavapipe-like, so the first frames are short
    bool mMeasured = false;
};

}  // namespace amrvk::session
