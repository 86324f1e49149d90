#pragma once
// The limits every front end applies to a picture (the CLI's option checks, session files, the
// viewer, Python), stated once here.
#include <cstdint>

namespace amrvk::scene {

inline constexpr int kMaxImageSide = 16384;                      // pixels per side of an image
inline constexpr uint32_t kMaxSpp = uint32_t{1} << 24;            // samples per pixel of one picture
inline constexpr uint32_t kMaxKdLeaves = (uint32_t{1} << 24) - 1;  // leaves of a kd-tree
inline constexpr uint32_t kMaxDenseMiB = uint32_t{1} << 20;        // the dense sampler's grid, MiB
// The vertical field of view, in degrees, lies in the open interval (0, kMaxFovDegrees).
inline constexpr double kMaxFovDegrees = 180;
inline bool validFov(double degrees) { return degrees > 0 && degrees < kMaxFovDegrees; }

}  // namespace amrvk::scene
