#pragma once
// What a structure combination needs, decided in one place: the traversal and sampler tables
// below and planOf(), which VolumeScene::configure (host structures), render::DeviceScene (device
// copy), render::MajorantPass (majorants, culling) and the bench's build-time accounting all read.
// Adding a traversal is one row in kTraversalTraits (its box set and what it builds) plus its
// code: the boxes in VolumeScene::configure, its segments in shaders/lib/traversal.glsl.
#include <cstdint>
#include <span>

#include "shared/kinds.h"

namespace amrvk::scene {

using shared::Backend;
using shared::SamplerKind;
using shared::TraversalKind;

// The boxes a box traversal steps through, each with a value range and a majorant per TF.
enum class BoxSet : uint8_t {
    None,          // grid-dda: the macrocell DDA, no boxes
    Macrocells,    // grid-bvh: the non-empty macrocells (computed from the grid, not stored)
    Abrs,          // abr: ABR boxes with their ABR ranges
    BrickBounds,   // brick: strict brick bounds with support ranges
    BrickDomains,  // ext-brick: brick basis domains with support ranges
    KdLeaves,      // kdtree: leaves of the TF-specific kd-tree (built per TF)
};

struct TraversalTraits {
    TraversalKind kind;
    const char* name;        // --traversal spelling
    BoxSet boxes;
    bool macrocellRanges;    // reads the macrocell value-range grid (--grid)
};
inline constexpr TraversalTraits kTraversalTraits[] = {
    {TraversalKind::GridDda, "grid-dda", BoxSet::None, true},
    {TraversalKind::GridBvh, "grid-bvh", BoxSet::Macrocells, true},
    {TraversalKind::Abr, "abr", BoxSet::Abrs, false},
    {TraversalKind::Brick, "brick", BoxSet::BrickBounds, false},
    {TraversalKind::ExtBrick, "ext-brick", BoxSet::BrickDomains, false},
    {TraversalKind::KdTree, "kdtree", BoxSet::KdLeaves, false},
};

// How the bricks at a point are found.
enum class Lookup : uint8_t {
    BrickDomainBvh,  // ext-brick: a BVH over brick domains (sw) or their BLAS (rq)
    AbrBvh,          // abr: a BVH over ABR boxes (sw) or their BLAS (rq)
    BrickGrid,       // grid: per-macrocell brick lists, no tree
    Dense,           // dense: the field resampled to the finest uniform grid (no bricks on the device)
};

struct SamplerTraits {
    SamplerKind kind;
    const char* name;  // --sampler spelling
    Lookup lookup;
    bool amr;          // reconstructs from the bricks (all but dense)
};
inline constexpr SamplerTraits kSamplerTraits[] = {
    {SamplerKind::ExtBrick, "ext-brick", Lookup::BrickDomainBvh, true},
    {SamplerKind::Abr, "abr", Lookup::AbrBvh, true},
    {SamplerKind::Grid, "grid", Lookup::BrickGrid, true},
    {SamplerKind::Dense, "dense", Lookup::Dense, false},
};

const TraversalTraits& traitsOf(TraversalKind kind);
const SamplerTraits& traitsOf(SamplerKind kind);

// Everything one combination builds, on the host and on the device. Derived only from the tables.
struct StructurePlan {
    TraversalKind traversal = TraversalKind::GridDda;
    SamplerKind sampler = SamplerKind::Grid;
    Backend backend = Backend::Sw;
    BoxSet traversalBoxes = BoxSet::None;
    Lookup lookup = Lookup::BrickGrid;
    // Host structures (VolumeScene).
    bool abrs = false;              // abr sampler or abr traversal
    bool samplerBvh = false;        // BVH over the lookup's boxes (sw back-end)
    bool samplerBoxes = false;      // the same boxes as BLAS input (rq back-end)
    bool brickGrid = false;         // grid sampler; kept on the host only for sub-majorants
    bool denseGrid = false;         // dense sampler
    bool macrocellRanges = false;   // grid traversals
    bool rangesFromDense = false;   // dense sampler: macrocell ranges from the dense samples
    bool staticBoxes = false;       // abr | brick | ext-brick: boxes and ranges built once
    bool supportRangeQuery = false; // kdtree: kept, the tree is rebuilt per TF from it
    // Device and per-TF work (DeviceScene, MajorantPass).
    bool bricksOnDevice = false;    // brick table and values (AMR samplers)
    bool boxMajorants = false;      // a majorant per traversal box and a culled hierarchy over them
    bool boxesPerTf = false;        // the boxes themselves change with the TF (kdtree)
    bool rayQueryCulling = false;   // rq: the culled boxes as a BLAS rebuilt per TF
    bool subMajorants = false;      // grid traversals over AMR samplers, where asked for: sub-boxes of the
                                    // loose macrocells per TF (scene/sub_majorants.h), from the brick grid
};
// `subMajorants`: asked for (StructureConfig::subMajorants > 0); only grid traversals over the
// AMR samplers have them (the dense sampler's ranges come from its samples, not the cells).
StructurePlan planOf(TraversalKind traversal, SamplerKind sampler, Backend backend, bool subMajorants);

}  // namespace amrvk::scene
