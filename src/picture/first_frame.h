#pragma once
// The first frame of a picture: what a front end shows before the path tracer has a sample (the
// Python Renderer inline and as image(), `render --first-frame`; the viewer's previews are its
// one-sample, reduced-size kin). The same description ray-marched (dvr: emission-absorption of the same TF, no global
// light), clean in about a second where path tracing a haze is grainy for hundreds of samples
// (docs/python.md section 1). dvr's noise is mostly aliasing of thin TF layers crossed within a
// step, so while it is noisier than kFirstFrameNoise and another frame fits the time left, the
// frame is rendered again at a finer step dt (halved as often as the noise calls for, about 2x
// per halving), not with more samples: on AMReX PeleLM's flame sheet (`render --mode dvr`,
// linear temp, 384^2, 2 spp) halving dt twice takes the noise from 0.091 to 0.035, four times the
// samples only to 0.059.
#include <cstdint>

#include "core/image_io.h"
#include "render/renderer.h"
#include "scene/preview_hold.h"

namespace amrvk::picture {

inline constexpr uint32_t kFirstFrameSpp = 2;         // samples per pixel: two, so its noise is known
inline constexpr double kFirstFrameNoise = scene::kNoVisibleNoise;  // mean relative standard error: no visible grain
// Every frame's GPU time together (dt / 2^k is predicted at 2^k the last frame's time) may reach
// kFirstFrameBudgetFactor times the first frame's, within [kFirstFrameGpuSeconds,
// kFirstFrameMaxGpuSeconds]: the budget follows the data and the image size through that first
// frame's cost. A fixed second stopped Enzo and AMReX at 256^2 at noise 0.07-0.09 on lavapipe,
// where 8 times the first frame allows the three halvings that take the noise down about 8x.
inline constexpr double kFirstFrameGpuSeconds = 1.0;
inline constexpr double kFirstFrameBudgetFactor = 8.0;
inline constexpr double kFirstFrameMaxGpuSeconds = 8.0;
inline constexpr double kFirstFrameMinDt = 1.0 / 16;  // finest step tried, in finest-cell widths

struct FirstFrame {
    Image image;            // linear radiance, row 0 the top (as RenderOutput::mean)
    double dt = 0;          // the dvr step it was rendered with: the settings' dvrStep / 2^k
    double noise = 0;       // scene::meanRelativeError of it
    double gpuSeconds = 0;  // every frame made for it, together
    uint32_t frames = 0;    // frames rendered (1 + the refinements)
};

// The GPU seconds every frame may take together, given the first frame's.
double firstFrameBudgetSeconds(double firstFrameSeconds);

// What the renderer holds after the first frame.
enum class AfterFirstFrame {
    Restore,  // its own settings and no sample (a front end that path-traces next)
    Keep,     // the first frame itself: dvr at FirstFrame::dt, kFirstFrameSpp samples (`render --first-frame`)
};

// Renders the first frame of the picture `renderer` holds (its settings, TF and structures, from
// dt = its settings' dvrStep).
FirstFrame renderFirstFrame(render::Renderer& renderer, AfterFirstFrame after = AfterFirstFrame::Restore);

}  // namespace amrvk::picture
