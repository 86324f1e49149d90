// The viewer's camera path (session/camera_path.h, docs/viewer.md "Camera path"): keyframes of the
// current camera added, moved and deleted in the state (saved with the session), and the preview:
// a path frame's camera set as the camera, as an orbit sets it, so the picture of path frame k is
// what `amrvk render --session` renders as movie frame k.

#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include "core/error.h"
#include "session/camera_path.h"
#include "viewer/logic/script.h"
#include "viewer/viewer_app_impl.h"

namespace amrvk::viewer {

void ViewerApp::runPathAction(const ScriptAction& a) {
    const std::string& n = a.name;
    session::CameraPath& path = mState.cameraPath;
    if (n == "keyframe-add") {
        path.add(pathFrameArgument(a, 0), mState.settings.camera);
    } else if (n == "keyframe-delete") {
        path.remove(pathFrameArgument(a, 0));
    } else if (n == "keyframe-move") {
        path.move(pathFrameArgument(a, 0), pathFrameArgument(a, 1));
    } else if (n == "path-frame") {
        const uint32_t k = pathFrameArgument(a, 0);
        AMRVK_CHECK(!path.empty(), "the camera path has no keyframes");
        AMRVK_CHECK(k < path.frameCount(), "frame ", k, " is past the camera path's last frame ",
                    path.frameCount() - 1);
        stopPath();
        showPathFrame(k);
    } else if (n == "path-play") {
        playPath();
    } else if (n == "path-stop") {
        stopPath();
    } else if (n == "path-fps") {
        path.setFps(a.number(0));
    } else {
        AMRVK_CHECK(false, "the viewer has no action '", n, "'");
    }
}

void ViewerApp::applyPathRequests(const PathRequests& r) {
    session::CameraPath& path = mState.cameraPath;
    if (r.add) {
        path.add(*r.add, mState.settings.camera);
        mPanel.message = "keyframe added at frame " + std::to_string(*r.add);
    }
    if (r.remove) {
        path.remove(*r.remove);
        mPanel.message = "keyframe at frame " + std::to_string(*r.remove) + " deleted";
    }
    if (r.move) {
        path.move(r.move->first, r.move->second);
        mPanel.message = "keyframe moved to frame " + std::to_string(r.move->second);
    }
    if (r.fps) path.setFps(*r.fps);
    if (r.stop) stopPath();
    if (r.play) playPath();
    if (r.show && !path.empty()) {
        stopPath();
        showPathFrame(std::min(*r.show, path.frameCount() - 1));
    }
}

void ViewerApp::handlePathKey(int code) {
    try {
        if (code == GLFW_KEY_K) {
            // After the last keyframe by a second of the movie (the first at frame 0).
            const session::CameraPath& path = mState.cameraPath;
            const uint32_t at =
                path.empty() ? 0 : path.frameCount() - 1 + uint32_t(std::max(1.0, std::round(path.fps())));
            applyPathRequests({.add = at});
        } else if (code == GLFW_KEY_P) {
            mPathPreview.playing ? stopPath() : playPath();
        }
    } catch (const Error& e) {
        mPanel.message = std::string("error: ") + e.what();
    }
}

void ViewerApp::showPathFrame(uint32_t k) {
    mState.settings.camera = mState.cameraPath.cameraAt(double(k));
    // Over a time series, frame k shows the step render --session shows in it (session::stepOfFrame),
    // the camera above included in the step's picture.
    if (mPlayer) showStep(session::stepOfFrame(k, mState.cameraPath.frameCount(), uint32_t(mPlayer->steps())));
    mPathPreview.frame = k;
    mPathPreview.shownOnFrame = mFrame;
    mPathPreview.shownAt = Clock::now();
    mPathPreview.shown.emplace_back(k, mState.settings.camera);
    mPanel.pathFrame = int(k);
}

void ViewerApp::playPath() {
    AMRVK_CHECK(!mState.cameraPath.empty(), "the camera path has no keyframes (add one: K, or keyframe-add)");
    mPathPreview.playing = true;
    mPanel.pathPlaying = true;
    showPathFrame(0);
}

void ViewerApp::stopPath() {
    mPathPreview.playing = false;
    mPanel.pathPlaying = false;
}

void ViewerApp::advancePathPreview() {
    if (!mPathPreview.playing || mPathPreview.shownOnFrame == mFrame) return;  // one path frame a viewer frame
    const session::CameraPath& path = mState.cameraPath;
    const uint32_t next = mPathPreview.frame.value_or(0) + 1;
    if (path.empty() || next >= path.frameCount()) {
        stopPath();
        mPanel.message = "camera path played";
        return;
    }
    // Not faster than the movie: the frame waits until 1/fps after the last one was shown.
    std::this_thread::sleep_until(mPathPreview.shownAt + std::chrono::duration_cast<Clock::duration>(
                                                             std::chrono::duration<double>(1.0 / path.fps())));
    showPathFrame(next);
}

std::optional<uint32_t> ViewerApp::shownPathFrame() const {
    const session::CameraPath& path = mState.cameraPath;
    if (!mPathPreview.frame || path.empty() || *mPathPreview.frame >= path.frameCount()) return std::nullopt;
    if (!(path.cameraAt(double(*mPathPreview.frame)) == mState.settings.camera)) return std::nullopt;
    return mPathPreview.frame;
}

}  // namespace amrvk::viewer
