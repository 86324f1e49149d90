#pragma once
// The CPU-side structures of one structure combination over a shared Volume, and nothing more
// ("model only what a scene needs"): exactly what scene::planOf(config) lists (ABRs, the
// sampler's BVH or its BLAS boxes, the brick grid, the dense resampling, macrocell value ranges,
// the static traversal boxes with their ranges, the support-range query the kd-tree is built from
// per TF). configure() switches combination, building what is missing and freeing what the new one
// does not use. A render::Renderer owns its VolumeScene (nobody else can reconfigure it under the
// device copy); the CPU tests configure their own.
#include <glm/glm.hpp>

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "accel/abrs.h"
#include "accel/brick_grid.h"
#include "accel/bvh.h"
#include "accel/dense_grid.h"
#include "accel/kdtree.h"
#include "accel/range_grid.h"
#include "accel/support_range.h"
#include "scene/structure_config.h"
#include "scene/transfer_function.h"
#include "scene/volume.h"
#include "shared/amr_gpu.h"

namespace amrvk::scene {

// Traversal boxes of abr | brick | ext-brick (local voxel space) with the value range of every
// cell whose support touches each box (so the range bounds every sample inside it).
struct DomainBoxes {
    std::vector<shared::AabbGpu> boxes;
    std::vector<accel::ValueRange> ranges;
    uint64_t memoryBytes() const {
        return boxes.size() * sizeof(shared::AabbGpu) + ranges.size() * sizeof(accel::ValueRange);
    }
};

class VolumeScene {
public:
    // Builds the structures of `config` (backend resolved: Sw or Rq) over `volume`.
    VolumeScene(std::shared_ptr<const Volume> volume, const StructureConfig& config);
    // Builds what `next` needs and frees the rest. Validates `next` before touching anything.
    void configure(const StructureConfig& next);

    const Volume& volume() const { return *mVolume; }
    const std::shared_ptr<const Volume>& sharedVolume() const { return mVolume; }
    const StructureConfig& config() const { return mConfig; }
    const StructurePlan& plan() const { return mPlan; }

    // The structures (present exactly when the plan lists them).
    std::optional<accel::AbrSet> abrs;                   // plan.abrs
    accel::Bvh samplerBvh;                               // plan.samplerBvh: over brick domains or ABR boxes
    std::vector<shared::AabbGpu> samplerBoxes;           // plan.samplerBoxes: the same boxes, BLAS input
    std::optional<accel::RangeGrid> grid;                // plan.macrocellRanges (origin in voxel space)
    std::optional<accel::DenseGrid> dense;               // plan.denseGrid
    std::optional<accel::BrickGrid> brickGrid;           // plan.brickGrid (same layout as `grid`)
    std::optional<accel::SupportRangeQuery> supportRanges;  // plan.supportRangeQuery (kdtree, per TF)
    DomainBoxes domains;                                 // plan.staticBoxes

    // The kd-tree of a kdtree combination (plan.supportRangeQuery) for `tf`, with
    // config().kdLeaves leaves: what render::MajorantPass uploads on every TF change.
    accel::KdTree kdTreeFor(const TransferFunction& tf) const;

    // Host seconds of the last build of each structure.
    struct Timing {
        double abrs = 0, samplerBvh = 0, grid = 0, domains = 0, dense = 0, brickGrid = 0;
    } buildSeconds;
    // Build seconds of every structure the current combination uses, whether built by the last
    // configure() or kept from an earlier one; bricks included, the per-TF kd-tree not.
    double combinationBuildSeconds() const;
    // Host bytes per structure currently held (name, bytes), the volume's model and bricks first.
    std::vector<std::pair<std::string, uint64_t>> hostBytes() const;

private:
    void buildMacrocellRanges();  // plan.macrocellRanges, for mConfig.grid
    void buildStaticBoxes();      // plan.staticBoxes
    std::shared_ptr<const Volume> mVolume;
    StructureConfig mConfig;
    StructurePlan mPlan;
    bool mConfigured = false;
};

}  // namespace amrvk::scene
