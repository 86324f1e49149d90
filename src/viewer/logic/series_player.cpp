#include "viewer/logic/series_player.h"

#include <cmath>

#include "core/error.h"

namespace amrvk::viewer {

SeriesPlayer::SeriesPlayer(size_t steps, double fps) : mSteps(steps), mFps(0) {
    AMRVK_CHECK(steps >= 1, "internal: a series of no step");
    setFps(fps);
}

void SeriesPlayer::seek(size_t k) {
    AMRVK_CHECK(k < mSteps, "step ", k, " is outside the series (steps 0..", mSteps - 1, ")");
    if (k != mStep) mOnScreen = false;
    mStep = k;
}

size_t SeriesPlayer::stepOn(int delta) const {
    const long long n = (long long)mSteps;
    return size_t((((long long)mStep + delta) % n + n) % n);
}

void SeriesPlayer::setPlaying(bool on) { mPlaying = on; }

void SeriesPlayer::setFps(double fps) {
    AMRVK_CHECK(std::isfinite(fps) && fps > 0 && fps <= kSeriesMaxFps, "--series-fps: ", fps, " is outside (0, ",
                kSeriesMaxFps, "] steps per second");
    mFps = fps;
}

void SeriesPlayer::onScreen(double now) {
    if (mOnScreen) return;
    mOnScreen = true;
    mShownAt = now;
}

bool SeriesPlayer::due(double now) const { return mPlaying && mSteps > 1 && mOnScreen && now - mShownAt >= 1.0 / mFps; }

std::vector<size_t> SeriesPlayer::ahead(uint64_t budgetBytes, uint64_t bytesPerStep) const {
    std::vector<size_t> out;
    const uint64_t fit = bytesPerStep == 0 ? mSteps : budgetBytes / bytesPerStep;
    for (int d = 1; out.size() < fit && size_t(d) < mSteps; ++d)
        for (int delta : {d, -d}) {
            const size_t k = stepOn(delta);
            bool seen = k == mStep;
            for (size_t s : out) seen = seen || s == k;
            if (!seen && out.size() < fit) out.push_back(k);
        }
    return out;
}

}  // namespace amrvk::viewer
