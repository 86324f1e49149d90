#pragma once
// Which picture a front end shows while the path tracer converges: never a worse one than it
// replaces. The preview (the same TF ray-marched: picture/first_frame.h, the viewer's previews) is
// clean at once where the path-traced estimate of a haze is grainy for many samples, so the
// preview stays on screen until the estimate's measured noise (scene::meanRelativeError, the mean
// relative standard error of the visible pixels) is at most the preview's, or at most
// kNoVisibleNoise where the preview's is lower (below it no grain shows), or until the estimate
// has the samples the user asked for (their spp: the picture they asked for). Once the estimate is
// shown it stays until the picture changes. The estimate's noise is measured at 2 samples and then
// where it is predicted to reach the threshold (noise falls as 1 / sqrt(spp)), at most at each
// doubling: a readback every few samples, not every frame. Used by the viewer, the Python widget
// and the MPI viewer alike; window- and Vulkan-free.
#include <cstdint>
#include <optional>

namespace amrvk::scene {

// Mean relative standard error below which an image shows no visible grain.
inline constexpr double kNoVisibleNoise = 0.05;

enum class Shown : uint8_t {
    Nothing,   // no preview and no complete sample yet
    Preview,   // the ray-marched preview
    Estimate,  // the path-traced estimate
};
const char* shownName(Shown s);  // "nothing", "preview", "estimate"

class PreviewHold {
public:
    // A new picture (any edit that resets the estimate): nothing measured, nothing shown.
    void reset() { *this = PreviewHold(); }
    // The current picture's preview is ready with its measured noise (>= 0).
    void previewReady(double noise);
    bool hasPreview() const { return mPreviewNoise.has_value(); }
    std::optional<double> previewNoise() const { return mPreviewNoise; }
    // The noise the estimate must reach to replace the preview: max(preview's, kNoVisibleNoise).
    double threshold() const;
    // Whether the estimate, now at `spp` complete samples, is to be measured (a readback).
    bool wantsMeasure(uint32_t spp) const;
    // The estimate's measured noise at `spp` complete samples (>= 2).
    void estimateMeasured(uint32_t spp, double noise);
    std::optional<double> estimateNoise() const { return mEstimateNoise; }
    uint32_t estimateSpp() const { return mEstimateSpp; }  // where it was last measured
    // What to show with the estimate at `spp` complete samples, of `limit` asked for (0: no limit).
    Shown shown(uint32_t spp, uint32_t limit) const;

private:
    std::optional<double> mPreviewNoise;
    std::optional<double> mEstimateNoise;
    uint32_t mEstimateSpp = 0;
    uint32_t mNextMeasure = 2;  // the spp at which the estimate is next measured
    bool mReplaced = false;     // the estimate reached the threshold: shown from then on
};

}  // namespace amrvk::scene
