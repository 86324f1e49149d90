// The viewer's keys and mouse: orbit, pan, zoom, cut-away handles, quit (ViewerApp, viewer_app_impl.h).
#include <GLFW/glfw3.h>

#include <algorithm>

#include "core/error.h"
#include "viewer/cut_overlay.h"
#include "viewer/logic/cut_handles.h"
#include "viewer/logic/viewer_layout.h"
#include "viewer/viewer_app_impl.h"
#include "viewer/window.h"

namespace amrvk::viewer {

// A key the panels did not take: arrows orbit by `step` of a picture `h` pixels high, +/- and
// page up/down zoom, r resets the view, q and Esc quit; in a time series space plays or pauses and
// comma and period step back and on; k and p edit and play the camera path.
void ViewerApp::handleKey(int code, double h, double step) {
    switch (code) {
        case GLFW_KEY_LEFT:
        case GLFW_KEY_RIGHT:
            mOrbit.orbit(mState.settings.camera, code == GLFW_KEY_LEFT ? -step : step, 0, h);
            break;
        case GLFW_KEY_UP:
        case GLFW_KEY_DOWN:
            mOrbit.orbit(mState.settings.camera, 0, code == GLFW_KEY_UP ? step : -step, h);
            break;
        case GLFW_KEY_EQUAL:
        case GLFW_KEY_KP_ADD:
        case GLFW_KEY_PAGE_UP:
            mOrbit.zoom(mState.settings.camera, 1);
            break;
        case GLFW_KEY_MINUS:
        case GLFW_KEY_KP_SUBTRACT:
        case GLFW_KEY_PAGE_DOWN:
            mOrbit.zoom(mState.settings.camera, -1);
            break;
        case GLFW_KEY_R:
            mOrbit.reset(mState.settings.camera);
            break;
        case GLFW_KEY_SPACE:  // a time series: play or pause, step back or on
            if (mPlayer) mPlayer->setPlaying(!mPlayer->playing());
            break;
        case GLFW_KEY_COMMA:
        case GLFW_KEY_PERIOD:
            if (!mPlayer) break;
            try {
                showStep(mPlayer->stepOn(code == GLFW_KEY_COMMA ? -1 : 1));
            } catch (const Error& e) {  // a step that cannot be read: said, the shown one kept
                mPanel.message = std::string("error: ") + e.what();
            }
            break;
        case GLFW_KEY_Q:
        case GLFW_KEY_ESCAPE:
            mQuit = true;
            break;
        default:
            handlePathKey(code);  // K, P
            break;
    }
}

void ViewerApp::handleInput() {
    // Drags are measured against the picture as shown (its height in pixels): a drag across the
    // whole picture turns as far whatever the window size.
    const session::PixelRect& picture = mLayout.picture;
    const double h = double(std::max(picture.height, 1)), step = h / 18.0;  // arrow keys: 10 degrees
    // Cursor positions are in window coordinates, the layout in framebuffer pixels (HiDPI).
    int windowW = 0, windowH = 0;
    glfwGetWindowSize(mWindow->handle(), &windowW, &windowH);
    const double toPixelsX = windowW > 0 ? double(mLayout.window.width) / windowW : 1.0;
    const double toPixelsY = windowH > 0 ? double(mLayout.window.height) / windowH : 1.0;
    auto overPicture = [&](double x, double y) { return picture.contains(x * toPixelsX, y * toPixelsY); };
    // ImGui decides per frame whether the pointer or keyboard is its own; the camera takes the mouse
    // only over the picture, and a drag that starts there stays a camera drag when it crosses a panel.
    const bool uiMouse = mImGui->wantsMouse(), uiKeys = mImGui->wantsKeyboard();
    // A cursor position (window coordinates) in the pixels of the image the picture shows.
    const scene::RenderSettings& rs = mState.settings;
    const double toImageX = double(rs.width) / std::max(picture.width, 1),
                 toImageY = double(rs.height) / std::max(picture.height, 1);
    auto inImage = [&](double x, double y) {
        return glm::dvec2((x * toPixelsX - picture.x) * toImageX, (y * toPixelsY - picture.y) * toImageY);
    };
    for (const InputEvent& e : mWindow->takeEvents()) {
        switch (e.kind) {
            case InputEvent::Kind::Button:
                ++mInputSeen.buttons;
                if (e.code >= 0 && e.code < 32) {
                    if (e.action == GLFW_PRESS) mInputSeen.held |= 1u << e.code;
                    if (e.action == GLFW_RELEASE) mInputSeen.held &= ~(1u << e.code);
                }
                // A left press on a crop-box handle drags that face (docs/cut-aways.md), not the camera.
                if (e.action == GLFW_PRESS && e.code == GLFW_MOUSE_BUTTON_LEFT && mDragButton < 0 && !uiMouse &&
                    overPicture(e.x, e.y) && rs.cut.crop) {
                    const double radius = kCutHandleRadius * toImageX;
                    mCutFace =
                        CutHandles::pick(rs.camera, rs.width, rs.height, *rs.cut.crop, inImage(e.x, e.y), radius);
                    if (mCutFace >= 0) {
                        mDragButton = e.code;
                        mLastX = e.x;
                        mLastY = e.y;
                        break;
                    }
                }
                if (e.action == GLFW_PRESS && mDragButton < 0 && !uiMouse && overPicture(e.x, e.y)) {
                    mDragButton = e.code;
                    mDragPans = e.code == GLFW_MOUSE_BUTTON_MIDDLE || (e.mods & GLFW_MOD_SHIFT);
                } else if (e.action == GLFW_RELEASE && e.code == mDragButton) {
                    mDragButton = -1;
                    mCutFace = -1;
                }
                break;
            case InputEvent::Kind::Cursor:
                ++mInputSeen.cursor;
                if (mDragButton >= 0 && mCutFace >= 0 && mState.settings.cut.crop) {
                    // The face follows the pointer along its normal, inside the data, never past the
                    // opposite face (a thousandth of the box's diagonal apart at least).
                    const glm::dvec2 delta = inImage(e.x, e.y) - inImage(mLastX, mLastY);
                    const glm::dvec3 lo = mVolume->worldMin(), hi = mVolume->worldMax();
                    scene::CropBox& box = *mState.settings.cut.crop;
                    box = CutHandles::drag(rs.camera, rs.width, rs.height, box, mCutFace, delta, glm::min(lo, box.lo),
                                           glm::max(hi, box.hi), 1e-3 * glm::length(hi - lo));
                    mInteracting = true;
                } else if (mDragButton >= 0) {
                    const double dx = e.x - mLastX, dy = e.y - mLastY;
                    scene::Camera& cam = mState.settings.camera;
                    if (mDragPans)
                        mOrbit.pan(cam, dx, dy, h);
                    else if (mDragButton == GLFW_MOUSE_BUTTON_RIGHT)
                        mOrbit.zoom(cam, -dy / 20.0);
                    else
                        mOrbit.orbit(cam, dx, dy, h);
                    mInteracting = true;
                }
                mLastX = e.x;
                mLastY = e.y;
                break;
            case InputEvent::Kind::Scroll:
                ++mInputSeen.scroll;
                if (!uiMouse && e.y != 0 && overPicture(mLastX, mLastY)) mOrbit.zoom(mState.settings.camera, e.y);
                break;
            case InputEvent::Kind::Key:
                ++mInputSeen.keys;
                if (uiKeys || e.action == GLFW_RELEASE) break;
                handleKey(e.code, h, step);
                break;
        }
    }
}

}  // namespace amrvk::viewer
