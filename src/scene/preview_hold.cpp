#include "scene/preview_hold.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace amrvk::scene {

const char* shownName(Shown s) {
    switch (s) {
        case Shown::Nothing:
            return "nothing";
        case Shown::Preview:
            return "preview";
        case Shown::Estimate:
            return "estimate";
    }
    return "?";
}

void PreviewHold::previewReady(double noise) {
    AMRVK_CHECK(noise >= 0, "internal: a preview's noise must be >= 0 (got ", noise, ")");
    mPreviewNoise = noise;
}

double PreviewHold::threshold() const { return std::max(mPreviewNoise.value_or(0.0), kNoVisibleNoise); }

bool PreviewHold::wantsMeasure(uint32_t spp) const { return mPreviewNoise && !mReplaced && spp >= mNextMeasure; }

void PreviewHold::estimateMeasured(uint32_t spp, double noise) {
    AMRVK_CHECK(spp >= 2 && noise >= 0, "internal: an estimate is measured at >= 2 spp (got ", spp, ", noise ", noise,
                ")");
    mEstimateNoise = noise;
    mEstimateSpp = spp;
    const double t = threshold();
    if (noise <= t) {
        mReplaced = true;
        return;
    }
    // noise ~ 1 / sqrt(spp): the threshold is predicted at spp * (noise / t)^2; measured there,
    // or at the next doubling where that is further (the prediction is itself noisy).
    const double predicted = std::ceil(double(spp) * (noise / t) * (noise / t));
    mNextMeasure = uint32_t(std::clamp(predicted, double(spp) + 1.0, 2.0 * double(spp)));
}

Shown PreviewHold::shown(uint32_t spp, uint32_t limit) const {
    if (!mPreviewNoise) return spp >= 1 ? Shown::Estimate : Shown::Nothing;
    if (mReplaced || (limit > 0 && spp >= limit)) return Shown::Estimate;
    return Shown::Preview;
}

}  // namespace amrvk::scene
