#pragma once
// The CPU-side structures one render configuration needs, and nothing more ("model only what a
// scene needs"): bricks and brick-order values always; ABRs only for the abr sampler; the
// sampler's BVH (over brick domains or ABR boxes); the macrocell value-range grid for grid-dda.
// All coordinates the GPU sees are local voxel space: voxel - localOrigin.
#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <vector>

#include "accel/abrs.h"
#include "accel/bricks.h"
#include "accel/bvh.h"
#include "accel/range_grid.h"
#include "amr/model.h"

namespace amrvk::render {

enum class SamplerKind { ExtBrick, Abr };
SamplerKind parseSampler(const std::string& name);
const char* samplerName(SamplerKind kind);

struct VolumeScene {
    const amr::Model* model = nullptr;
    const amr::Field* field = nullptr;
    SamplerKind sampler = SamplerKind::ExtBrick;
    glm::i64vec3 localOrigin{0};  // voxel space; = lower corner of the data bounds
    amr::Box3l bounds;            // union of leaf cells, voxel space
    int32_t minLevel = 0;         // finest level present; sigma is per (1 << minLevel) voxel units
    float valueLo = 0, valueHi = 0;
    accel::BrickSet bricks;
    std::vector<float> brickValues;
    std::optional<accel::AbrSet> abrs;  // abr sampler only
    accel::Bvh samplerBvh;              // boxes in local voxel space
    accel::RangeGrid grid;              // origin in voxel space (converted on upload)
    struct Timing {
        double bricks = 0, abrs = 0, bvh = 0, grid = 0;
    } buildSeconds;
};

VolumeScene buildVolumeScene(const amr::Model& model, const amr::Field& field, SamplerKind sampler,
                             const std::string& gridSpec);

}  // namespace amrvk::render
