#include "picture/first_frame.h"

#include "scene/render_output.h"

namespace amrvk::picture {

FirstFrame renderFirstFrame(render::Renderer& renderer) {
    const scene::RenderSettings asGiven = renderer.settings();
    scene::RenderSettings dvr = asGiven;
    dvr.mode = scene::Mode::Dvr;
    FirstFrame f;
    double lastSeconds = 0;
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
        ++f.frames;
        // Another frame at half the step costs about twice this one's samples.
        if (!(f.noise > kFirstFrameNoise) || dvr.dvrStep / 2 < kFirstFrameMinDt ||
            f.gpuSeconds + 2 * lastSeconds > kFirstFrameGpuSeconds)
            break;
        dvr.dvrStep /= 2;
    }
    renderer.setSettings(asGiven);
    renderer.resetAccumulation();  // the picture's own mode and step, no sample
    return f;
}

}  // namespace amrvk::picture
