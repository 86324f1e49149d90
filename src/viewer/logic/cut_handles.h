#pragma once
// The crop box's handles in the viewer's picture, window-free: the box's edges and one handle at
// the centre of each face, projected with exactly the renderer's camera rays (scene::makeRayBasis),
// the handle under the pointer, and a drag that moves that face along its normal so the face's
// handle follows the pointer's motion projected on the normal's screen direction. Pixel
// coordinates are the picture's (origin top left, y down, width x height); everything else is world.
#include <glm/glm.hpp>

#include <array>
#include <optional>

#include "scene/camera.h"
#include "scene/cut_away.h"

namespace amrvk::viewer {

struct CutHandles {
    // Picture position of a world point; nullopt when it lies behind the eye (or on its plane).
    static std::optional<glm::dvec2> project(const scene::Camera& camera, int width, int height, glm::dvec3 world);

    // Face f = 2 * axis + side (side 0: the lower face, 1: the upper one) and its centre (world).
    static glm::dvec3 faceCentre(const scene::CropBox& box, int face);

    // The 12 edges of the box as world segments (for drawing; project each end).
    static std::array<std::array<glm::dvec3, 2>, 12> edges(const scene::CropBox& box);

    // The face whose projected handle is nearest `pixel` within `radius` pixels, else -1.
    static int pick(const scene::Camera& camera, int width, int height, const scene::CropBox& box, glm::dvec2 pixel,
                    double radius);

    // The box after dragging face `face` by `pixelDelta`: the face moves along its axis by the
    // distance whose projection onto the screen best matches the motion (least squares along the
    // axis' screen direction), kept inside [lo, hi] (the data's world bounds) and at least
    // `minWidth` from the opposite face. Unchanged when the axis points at the eye (no screen
    // direction).
    static scene::CropBox drag(const scene::Camera& camera, int width, int height, const scene::CropBox& box, int face,
                               glm::dvec2 pixelDelta, glm::dvec3 lo, glm::dvec3 hi, double minWidth);
};

}  // namespace amrvk::viewer
