#pragma once
// How much path tracing one viewer frame may do, so that the UI and the camera stay above 15
// frames/s whatever one sample costs (a second at full resolution on lavapipe, a millisecond on a
// GPU). It keeps a running estimate of the GPU seconds per pixel-sample and answers two questions:
// while the user interacts, how much to shrink the image so a whole preview sample fits in the
// budget; when they stop, how many rows of the full image to trace this frame (time-budgeted
// tiles). Rows of one picture cost very different amounts (empty sky against the dense middle, 10x
// and more), so tiles are sized from the cost of the same rows in the previous sample, not from the
// mean. Window-free; the viewer feeds it the measured GPU time of what it dispatched.
#include <cstdint>
#include <vector>

namespace amrvk::viewer {

class FrameBudget {
public:
    // frameSeconds: the whole frame (default 1/20 s, so >= 15 frames/s with some margin); the path
    // tracer gets what the rest of the frame (UI, display, present) leaves, at least 1/10 of it.
    explicit FrameBudget(double frameSeconds = 0.05) : mFrame(frameSeconds), mBudget(frameSeconds) {}

    // The last dispatch took `seconds` for `pixelSamples` pixel-samples.
    void record(double seconds, uint64_t pixelSamples);
    // The last tile, rows [firstRow, firstRow + rows) of a width x height image, took `seconds`:
    // also kept per row (spread evenly inside the tile) to size the next tiles over those rows.
    void recordRows(double seconds, uint32_t firstRow, uint32_t rows, int width, int height);
    // The last frame spent `seconds` on everything but path tracing.
    void recordOtherWork(double seconds);
    double secondsPerPixelSample() const { return mCost; }
    double budgetSeconds() const { return mBudget; }

    // Downscale factor (1, 2, 4, 8, 16, 32) of a width x height preview so one sample of it fits.
    int previewScale(int width, int height) const;
    // Rows of a width x height image to trace this frame, starting at firstRow: as many as the
    // per-row costs of the previous sample (the mean cost where none was measured) fit in the
    // budget; at least 1, at most height - firstRow.
    uint32_t rowsPerFrame(int width, int height, uint32_t firstRow = 0) const;

private:
    double mFrame, mBudget;
    double mOther = 0;
    double mCost = 2e-6;  // s per pixel-sample until measured: lavapipe-like, so the first frames are short
    bool mMeasured = false;
    int mRowWidth = 0;             // the image the row profile belongs to
    std::vector<double> mRowCost;  // s per row, last measured; 0 = not measured
};

}  // namespace amrvk::viewer
