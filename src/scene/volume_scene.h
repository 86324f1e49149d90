#pragma once
// The TF-independent CPU-side structures one render configuration needs, and nothing more
// ("model only what a scene needs"): bricks and brick-order values always; ABRs for the abr
// sampler or traversal; the sampler's BVH (sw back-end) or its boxes (rq back-end: the GPU builds
// the BLAS); the macrocell value-range grid for grid-dda and grid-bvh; traversal boxes with value
// ranges for abr, brick and ext-brick; the support-range query the kdtree traversal builds its
// TF-specific tree from; the dense resampling for the dense sampler (whose macrocell ranges then
// come from the dense samples); the brick grid for the grid sampler. configure() switches combination, building what is missing and
// freeing what the new one does not use. Renderers only read a scene; whoever owns it configures
// it. All coordinates the GPU sees are local voxel space, converted in one place: toLocal().
#include <glm/glm.hpp>

#include <functional>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "accel/abrs.h"
#include "accel/brick_grid.h"
#include "accel/bricks.h"
#include "accel/bvh.h"
#include "accel/dense_grid.h"
#include "accel/range_grid.h"
#include "accel/support_range.h"
#include "amr/model.h"
#include "scene/structure_config.h"
#include "shared/amr_gpu.h"

namespace amrvk::scene {

// Traversal boxes of abr | brick | ext-brick | kdtree (local voxel space) with the value range of
// every cell whose support touches each box (so the range bounds every sample inside it).
struct DomainBoxes {
    std::vector<shared::AabbGpu> boxes;
    std::vector<accel::ValueRange> ranges;
    uint64_t memoryBytes() const {
        return boxes.size() * sizeof(shared::AabbGpu) + ranges.size() * sizeof(accel::ValueRange);
    }
};

// The support-range query refers to the scene's own bricks and values, so it must not follow the
// scene when it moves: a moved scene drops it and builds it again on first use
// (VolumeScene::supportRangeQuery).
struct SceneSupportRanges {
    mutable std::optional<accel::SupportRangeQuery> query;
    SceneSupportRanges() = default;
    SceneSupportRanges(SceneSupportRanges&&) noexcept {}
    SceneSupportRanges& operator=(SceneSupportRanges&&) noexcept {
        query.reset();
        return *this;
    }
};

struct VolumeScene {
    const amr::Model* model = nullptr;
    const amr::Field* field = nullptr;
    StructureConfig config;
    glm::i64vec3 localOrigin{0};  // voxel space; = lower corner of the data bounds
    amr::Box3l bounds;            // union of leaf cells, voxel space
    int32_t minLevel = 0;         // finest level present; sigma is per (1 << minLevel) voxel units
    float valueLo = 0, valueHi = 0;
    accel::BrickSet bricks;
    std::span<const float> brickValues;  // = field->values: the model is in brick order
    std::optional<accel::AbrSet> abrs;                   // abr sampler or abr traversal
    accel::Bvh samplerBvh;                               // sw back-end: over brick domains or ABR boxes
    std::vector<shared::AabbGpu> samplerBoxes;           // rq back-end: the same boxes, BLAS input
    std::optional<accel::RangeGrid> grid;                // grid-dda, grid-bvh (origin in voxel space)
    std::optional<accel::DenseGrid> dense;               // dense sampler
    std::optional<accel::BrickGrid> brickGrid;           // grid sampler (same layout as `grid`)
    SceneSupportRanges supportRanges;                    // kdtree (the renderer builds the tree per TF)
    DomainBoxes domains;                                 // abr, brick, ext-brick traversals
    struct Timing {
        double bricks = 0, abrs = 0, samplerBvh = 0, grid = 0, domains = 0, dense = 0, brickGrid = 0;
    } buildSeconds;

    // Builds what `config` needs and frees the rest. config.backend must be resolved (Sw or Rq).
    void configure(const StructureConfig& config);
    // kdtree traversal: the exact range query the TF-specific tree is built from (built by
    // configure(), again on first use after the scene moved).
    const accel::SupportRangeQuery& supportRangeQuery() const;
    // Host bytes per structure currently held (name, bytes).
    std::vector<std::pair<std::string, uint64_t>> hostBytes() const;
    // Voxel space -> local voxel space (what the GPU sees): the one place localOrigin is
    // subtracted. The integer form throws when a coordinate leaves the int32 range.
    glm::dvec3 toLocal(glm::dvec3 voxel) const { return voxel - glm::dvec3(localOrigin); }
    glm::ivec3 toLocal(glm::i64vec3 voxel) const;
    shared::AabbGpu toLocal(const accel::BoxD& voxelBox) const;
};

// Bricks and values only; call configure() next. Puts the model (cells and every field) in brick
// order (accel::buildBricks), so the scene's brick values are the field itself; the model must
// outlive the scene and `field` must be one of its fields.
VolumeScene makeVolumeScene(amr::Model& model, const amr::Field& field);
VolumeScene buildVolumeScene(amr::Model& model, const amr::Field& field, const StructureConfig& config);
// Convenience for the default traversal (grid-dda, sw).
VolumeScene buildVolumeScene(amr::Model& model, const amr::Field& field, SamplerKind sampler,
                             const std::string& gridSpec);

}  // namespace amrvk::scene
