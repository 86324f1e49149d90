#pragma once
// A camera path (docs/movies.md, "Camera paths"), window- and Vulkan-free: keyframes, each a
// camera (world space, as a session's "camera" holds it) at a whole frame number, kept sorted by
// frame, at most one a frame. Between two keyframes the camera is eased in time (smoothstep: it
// stops at every keyframe) and turned about the target rather than moved in a straight line: the
// target moves linearly, the eye's direction from the target by slerp, its distance log-linearly,
// the up vector by slerp and is then made perpendicular to the view again, the field of view
// linearly. A path round the data therefore keeps its distance and never cuts through it.
// Frames, not seconds: frame k of the path is frame k of the movie; `fps` only says how fast the
// movie plays (and the viewer's preview at most). The viewer's preview and `amrvk render --session`
// both take frame k's camera from cameraAt(k), so the movie is the preview, frame for frame.
#include <cstdint>
#include <vector>

#include "scene/camera.h"

namespace amrvk::session {

// A path has at most this many frames (the last keyframe's frame is below it), as a series has.
inline constexpr uint32_t kMaxPathFrames = 100000;
inline constexpr size_t kMaxKeyframes = 1000;  // keyframes in one path
inline constexpr double kMaxPathFps = 1000;    // frames per second lie in (0, kMaxPathFps]

struct Keyframe {
    uint32_t frame = 0;    // the path frame it is shown at (from 0)
    scene::Camera camera;  // world space; fovYDegrees in degrees
    bool operator==(const Keyframe&) const = default;
};

class CameraPath {
public:
    // An empty path (no keyframes): a session without "cameraPath".
    CameraPath() = default;

    // Adds `camera` at `frame`. One-line errors: a frame already holding a keyframe, a frame at or
    // above kMaxPathFrames, more than kMaxKeyframes, a camera checkKeyframeCamera refuses.
    void add(uint32_t frame, const scene::Camera& camera);
    // Deletes the keyframe at `frame`; a one-line error when there is none.
    void remove(uint32_t frame);
    // Moves the keyframe at `from` to frame `to` (its camera kept); refused when `to` holds another.
    void move(uint32_t from, uint32_t to);
    // Replaces the camera of the keyframe at `frame` (checked as add checks it).
    void setCamera(uint32_t frame, const scene::Camera& camera);

    bool empty() const { return mKeys.empty(); }
    const std::vector<Keyframe>& keyframes() const { return mKeys; }  // sorted by frame, frames distinct
    bool hasKeyframe(uint32_t frame) const;
    // The last keyframe's frame + 1 (0 when empty): the frames of the movie, 0 .. frameCount()-1.
    // A path of one keyframe at frame 0 is a still of one frame.
    uint32_t frameCount() const { return mKeys.empty() ? 0 : mKeys.back().frame + 1; }

    double fps() const { return mFps; }
    void setFps(double fps);  // (0, kMaxPathFps]; one-line error otherwise

    // The camera at path time `frame` (frames, may be fractional; 0 <= frame <= frameCount() - 1).
    // Exactly a keyframe's camera at its frame (its up as given); between keyframes the up is the
    // unit vector perpendicular to the view, the same picture. Before the first keyframe the first
    // one's camera, after the last the last one's.
    // Never NaN: the keyframes are checked, and the fallbacks of interpolate() cover what is left.
    scene::Camera cameraAt(double frame) const;

    bool operator==(const CameraPath&) const = default;

private:
    std::vector<Keyframe> mKeys;
    double mFps = 24;
};

// A keyframe's camera: finite eye, target and up, eye and target apart, up not parallel to the
// view (sin of the angle > 1e-9), fov in (0, 180) degrees. Throws "camera path keyframe at frame
// F: ..." (one line).
void checkKeyframeCamera(uint32_t frame, const scene::Camera& camera);

// The camera between keyframe cameras a (s = 0) and b (s = 1) at eased parameter s in [0, 1]:
// target lerped, eye direction slerped (opposite directions: turned about a's up, made
// perpendicular to a's direction), eye distance log-lerped, up slerped and made perpendicular to
// the view (when that leaves nothing, a's up carried by the turn of the view direction), fov
// lerped. s = 0 and s = 1 give a and b exactly.
scene::Camera interpolateCamera(const scene::Camera& a, const scene::Camera& b, double s);

// The easing in time between two keyframes: smoothstep, u^2 (3 - 2u) for u in [0, 1] (clamped);
// its derivative is 0 at both ends, so the camera stops at every keyframe.
double easeInOut(double u);

// The output of a time series shown at movie frame `frame` of `frames` when the series has `steps`
// outputs: floor(frame * steps / frames) (the steps spread evenly over the frames, step 0 first;
// with steps == frames frame k shows step k). The same rule for every front end, so the same
// frame shows the same step.
uint32_t stepOfFrame(uint32_t frame, uint32_t frames, uint32_t steps);

}  // namespace amrvk::session
