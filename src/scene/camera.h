#pragma once
// A pinhole camera in world space, and its conversion to a ray basis in voxel space (the renderer
// moves the eye into local voxel space with VolumeScene::toLocal).
#include <glm/glm.hpp>

#include "amr/model.h"

namespace amrvk::scene {

struct Camera {
    glm::dvec3 eye{0.0}, target{0.0, 0.0, -1.0}, up{0.0, 1.0, 0.0};  // world space
    double fovYDegrees = 40.0;
    bool operator==(const Camera&) const = default;
};

// A three-quarter view from (+x, -y, +z) that frames the world box with z up.
Camera defaultCamera(glm::dvec3 worldLo, glm::dvec3 worldHi, double fovYDegrees = 40.0);

// Ray basis: direction(px, py) = dir00 + px * du + py * dv (pixel coordinates, y down), in voxel
// space; eye is the ray origin in voxel space.
struct RayBasis {
    glm::dvec3 eye, dir00, du, dv;
};
RayBasis makeRayBasis(const Camera& camera, int width, int height, const amr::Transform& voxelToWorld);

}  // namespace amrvk::scene
