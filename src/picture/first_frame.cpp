#include "picture/first_frame.h"

#include <algorithm>
#include <cmath>
#include <exception>

#include "scene/render_output.h"

namespace amrvk::picture {

double firstFrameBudgetSeconds(double firstFrameSeconds) {
    return std::clamp(kFirstFrameBudgetFactor * firstFrameSeconds, kFirstFrameGpuSeconds, kFirstFrameMaxGpuSeconds);
}

FirstFrame renderFirstFrame(render::Renderer& renderer, AfterFirstFrame after) {
    const scene::RenderSettings asGiven = renderer.settings();
    scene::RenderSettings dvr = asGiven;
    dvr.mode = scene::Mode::Dvr;
    FirstFrame f;
    double lastSeconds = 0, budget = 0;
    // A frame that throws (Ctrl-C, a device error) still leaves the renderer in its own settings
    // when they are to be restored: a caller must never be left in dvr unawares.
    struct RestoreOnThrow {
        render::Renderer& r;
        const scene::RenderSettings& given;
        bool armed;
        ~RestoreOnThrow() {
            if (!armed || std::uncaught_exceptions() == 0) return;
            try {
                r.setSettings(given);
                r.resetAccumulation();
            } catch (...) {  // the first error is the one reported
            }
        }
    } guard{renderer, asGiven, after == AfterFirstFrame::Restore};
    for (;;) {
        renderer.setSettings(dvr);
        renderer.resetAccumulation();
        renderer.accumulate(kFirstFrameSpp);
        const scene::RenderOutput out = renderer.output();
        f.image = out.mean;
        f.dt = dvr.dvrStep;
        f.noise = scene::meanRelativeError(out);
        lastSeconds = renderer.stats().gpuSeconds;
        f.gpuSeconds += lastSeconds;
        if (f.frames++ == 0) budget = firstFrameBudgetSeconds(lastSeconds);
        if (!(f.noise > kFirstFrameNoise)) break;
        // Aliasing noise falls about 2x per halving of the step (PeleLM: 0.22, 0.078, 0.034), so
        // jump by the halvings that bring it to the target, fewer where they do not fit the time
        // left (a frame at dt / 2^k costs about 2^k times this one) or the finest step.
        int halvings = std::max(1, int(std::lround(std::log2(f.noise / kFirstFrameNoise))));
        auto fits = [&](int k) {
            return f.gpuSeconds + lastSeconds * std::ldexp(1.0, k) <= budget &&
                   std::ldexp(dvr.dvrStep, -k) >= kFirstFrameMinDt;
        };
        while (halvings > 1 && !fits(halvings)) --halvings;
        if (!fits(halvings)) break;
        dvr.dvrStep = std::ldexp(dvr.dvrStep, -halvings);
    }
    if (after == AfterFirstFrame::Restore) {
        renderer.setSettings(asGiven);
        renderer.resetAccumulation();  // the picture's own mode and step, no sample
    }
    return f;
}

}  // namespace amrvk::picture
