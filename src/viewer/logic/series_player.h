#pragma once
// The viewer's time series (`amrvk view` over several outputs), window-free: which step is shown,
// playing at a frame rate (steps per second) and stepping, and which neighbouring steps to read
// ahead within a memory budget. The viewer (viewer_series.cpp) reads, builds and shows what this
// decides.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace amrvk::viewer {

inline constexpr double kSeriesMaxFps = 120;

class SeriesPlayer {
public:
    // steps >= 1; fps in (0, kSeriesMaxFps] (a one-line error naming --series-fps otherwise).
    SeriesPlayer(size_t steps, double fps);
    size_t steps() const { return mSteps; }
    size_t step() const { return mStep; }
    // Step k is shown (k < steps(); an error names the step and the count otherwise).
    void seek(size_t k);
    // The step `delta` steps on, wrapping at the ends as a movie loops.
    size_t stepOn(int delta) const;
    bool playing() const { return mPlaying; }
    void setPlaying(bool on);
    double fps() const { return mFps; }
    void setFps(double fps);
    // The shown step's picture reached the screen at `now` (seconds, any steady clock): playing
    // advances 1 / fps after it, so no step is skipped unseen however long one takes to build.
    void onScreen(double now);
    // Playing, the shown step on screen for 1 / fps by `now`: the next step is due.
    bool due(double now) const;
    // The steps to read ahead of the shown one, nearest first, the direction of play first
    // (k+1, k-1, k+2, k-2, ... wrapping), as many as `budgetBytes` holds at `bytesPerStep` each.
    std::vector<size_t> ahead(uint64_t budgetBytes, uint64_t bytesPerStep) const;

private:
    size_t mSteps;
    size_t mStep = 0;
    double mFps;
    bool mPlaying = false;
    bool mOnScreen = false;  // the shown step's picture has been on screen since mShownAt
    double mShownAt = 0;
};

}  // namespace amrvk::viewer
