#include "viewer/logic/cut_handles.h"

#include <algorithm>
#include <cmath>

namespace amrvk::viewer {

std::optional<glm::dvec2> CutHandles::project(const scene::Camera& camera, int width, int height, glm::dvec3 world) {
    // The renderer's ray through pixel (x, y) is eye + s (dir00 + x du + y dv); solve for (s, s x, s y).
    const scene::RayBasis rb = scene::makeRayBasis(camera, width, height, amr::Transform{});
    const glm::dmat3 m(rb.dir00, rb.du, rb.dv);
    const glm::dvec3 c = glm::inverse(m) * (world - rb.eye);
    if (!(c.x > 1e-12)) return std::nullopt;
    return glm::dvec2(c.y / c.x, c.z / c.x);
}

glm::dvec3 CutHandles::faceCentre(const scene::CropBox& box, int face) {
    glm::dvec3 p = 0.5 * (box.lo + box.hi);
    const int axis = face / 2;
    p[axis] = face % 2 == 0 ? box.lo[axis] : box.hi[axis];
    return p;
}

std::array<std::array<glm::dvec3, 2>, 12> CutHandles::edges(const scene::CropBox& box) {
    auto corner = [&](int i) {
        return glm::dvec3(i & 1 ? box.hi.x : box.lo.x, i & 2 ? box.hi.y : box.lo.y, i & 4 ? box.hi.z : box.lo.z);
    };
    std::array<std::array<glm::dvec3, 2>, 12> out{};
    int n = 0;
    for (int i = 0; i < 8; ++i)
        for (int bit : {1, 2, 4})
            if (!(i & bit)) out[size_t(n++)] = {corner(i), corner(i | bit)};
    return out;
}

int CutHandles::pick(const scene::Camera& camera, int width, int height, const scene::CropBox& box, glm::dvec2 pixel,
                     double radius) {
    int best = -1;
    double bestDistance = radius;
    for (int f = 0; f < 6; ++f) {
        const auto p = project(camera, width, height, faceCentre(box, f));
        if (!p) continue;
        const double d = glm::length(*p - pixel);
        if (d <= bestDistance) {
            bestDistance = d;
            best = f;
        }
    }
    return best;
}

scene::CropBox CutHandles::drag(const scene::Camera& camera, int width, int height, const scene::CropBox& box, int face,
                                glm::dvec2 pixelDelta, glm::dvec3 lo, glm::dvec3 hi, double minWidth) {
    if (face < 0 || face > 5) return box;
    const int axis = face / 2;
    const glm::dvec3 centre = faceCentre(box, face);
    // Screen motion of the handle per world unit along the axis, by a small step either way.
    glm::dvec3 step(0.0);
    step[axis] = 1e-3 * std::max(glm::length(box.hi - box.lo), 1e-9);
    const auto a = project(camera, width, height, centre - step), b = project(camera, width, height, centre + step);
    if (!a || !b) return box;
    const glm::dvec2 perUnit = (*b - *a) / (2.0 * step[axis]);
    const double len2 = glm::dot(perUnit, perUnit);
    if (!(len2 > 1e-12)) return box;
    const double move = glm::dot(pixelDelta, perUnit) / len2;  // world units along the axis
    scene::CropBox out = box;
    if (face % 2 == 0) out.lo[axis] = std::clamp(box.lo[axis] + move, lo[axis], box.hi[axis] - minWidth);
    else out.hi[axis] = std::clamp(box.hi[axis] + move, box.lo[axis] + minWidth, hi[axis]);
    return out;
}

}  // namespace amrvk::viewer
