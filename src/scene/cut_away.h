#pragma once
// Cut-aways (docs/cut-aways.md): a crop box and up to shared::kMaxClipPlanes clip planes, world
// space. The medium is kept inside the crop box and behind every plane (the side its normal points
// away from, ParaView's Clip default); elsewhere it is empty, so rays pass the cut part unattenuated.
// Inside, the field is reconstructed as before: cells beyond the cut still weigh in near it. The
// kept region is convex, so a ray meets it in one interval; the shaders narrow every traversal to
// it (shaders/lib/cut_away.glsl), which keeps tracking exact and unbiased and skips every
// majorant box beyond the cut.
#include <glm/glm.hpp>

#include <optional>
#include <vector>

#include "amr/model.h"
#include "shared/cut_away_gpu.h"

namespace amrvk::scene {

struct CropBox {
    glm::dvec3 lo{0.0}, hi{0.0};  // world; kept: lo <= p <= hi
    bool operator==(const CropBox&) const = default;
};

struct ClipPlane {
    glm::dvec3 point{0.0};   // world: a point on the plane
    glm::dvec3 normal{1.0, 0.0, 0.0};  // world: the removed side is where it points (need not be unit)
    bool operator==(const ClipPlane&) const = default;
};

struct CutAway {
    std::optional<CropBox> crop;
    std::vector<ClipPlane> clips;  // at most shared::kMaxClipPlanes
    bool empty() const { return !crop && clips.empty(); }
    bool operator==(const CutAway&) const = default;
};

// A plane normal scaled to unit length without overflow or underflow: divided by its largest
// absolute component first, so 1e308 or 1e-300 per component gives the direction as 1 does. Zero
// for an exactly zero normal (which validateCutAway refuses).
glm::dvec3 unitNormal(glm::dvec3 n);

// Throws a one-line error naming --crop or --clip for a box with lo >= hi on an axis, a non-finite
// number, an exactly zero normal or more than kMaxClipPlanes planes.
void validateCutAway(const CutAway& cut);

// True when world point p is kept (inside the crop box and behind every plane).
bool keeps(const CutAway& cut, glm::dvec3 p);

// True when the cut keeps no volume of the box [lo, hi] (world): the crop box misses it, or the
// planes and the crop leave nothing, or only a sheet, of it (issue 52, point 7: two opposite clip
// planes gave a black picture without a word). Exact up to 1e-9 of the box's diagonal: every
// vertex of a kept region lies on three of its at most 10 bounding planes, so one of the 120
// triples' intersections is kept by the region narrowed by that margin.
bool keepsNothingOf(const CutAway& cut, glm::dvec3 lo, glm::dvec3 hi);

// The kept part [tMin, tMax] of the ray o + t d (world), narrowed from the given interval; false
// when nothing of it is kept. CPU twin of clipToCutAway (lib/cut_away.glsl), in double.
bool keptInterval(const CutAway& cut, glm::dvec3 o, glm::dvec3 d, double& tMin, double& tMax);

// The cut in local voxel space for the shaders: voxel = (world - origin) / scale, local = voxel -
// localOrigin. Plane normals are renormalised in voxel space.
shared::CutAwayGpu cutAwayGpu(const CutAway& cut, const amr::Transform& voxelToWorld, glm::dvec3 localOrigin);

// The same cut in voxel space (for the brute-force and reference tests and the viewer's handles).
CutAway cutAwayInVoxelSpace(const CutAway& cut, const amr::Transform& voxelToWorld);

}  // namespace amrvk::scene
