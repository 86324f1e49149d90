#include "scene/camera.h"

#include <cmath>

#include "core/error.h"
#include "scene/limits.h"

namespace amrvk::scene {

Camera defaultCamera(glm::dvec3 worldLo, glm::dvec3 worldHi, double fovYDegrees) {
    Camera c;
    c.fovYDegrees = fovYDegrees;
    c.target = 0.5 * (worldLo + worldHi);
    double radius = 0.5 * glm::length(worldHi - worldLo);
    glm::dvec3 dir = glm::normalize(glm::dvec3(0.9, -1.3, 0.8));
    double dist = radius / std::sin(glm::radians(fovYDegrees) * 0.5) * 1.02;
    c.eye = c.target + dir * dist;
    c.up = {0.0, 0.0, 1.0};
    return c;
}

RayBasis makeRayBasis(const Camera& camera, int width, int height, const amr::Transform& voxelToWorld) {
    glm::dvec3 forward = camera.target - camera.eye;
    AMRVK_CHECK(glm::length(forward) > 0, "--camera: eye and target coincide");
    forward = glm::normalize(forward);
    glm::dvec3 right = glm::cross(forward, camera.up);
    AMRVK_CHECK(glm::length(right) > 1e-12, "--camera: up vector is parallel to the view direction");
    right = glm::normalize(right);
    glm::dvec3 up = glm::cross(right, forward);
    AMRVK_CHECK(validFov(camera.fovYDegrees), "--fov: ", camera.fovYDegrees, " is outside (0, ", kMaxFovDegrees, ")");
    double h = std::tan(glm::radians(camera.fovYDegrees) * 0.5);
    double w = h * double(width) / double(height);
    // World-space basis for pixel coordinates in [0, width] x [0, height], y down.
    glm::dvec3 du = right * (2.0 * w / width), dv = -up * (2.0 * h / height);
    glm::dvec3 dir00 = forward - right * w + up * h;
    // World -> voxel is linear per axis: directions divide by the scale.
    RayBasis b;
    b.eye = (camera.eye - voxelToWorld.origin) / voxelToWorld.scale;
    b.dir00 = dir00 / voxelToWorld.scale;
    b.du = du / voxelToWorld.scale;
    b.dv = dv / voxelToWorld.scale;
    return b;
}

}  // namespace amrvk::scene
