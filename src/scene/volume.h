#pragma once
// One field of an AMR data set, in brick order with its bricks: the part of every picture that
// depends neither on the structure combination nor on the transfer function. Immutable once made
// and shared (std::shared_ptr<const Volume>) by the renderers and front ends that show it. It owns
// its model: makeVolume takes the model by value (move it in), because building bricks reorders
// cells and every field in place; nobody else holds the data it reorders. All coordinates the GPU
// sees are local voxel space, converted in one place: toLocal().
#include <glm/glm.hpp>

#include <memory>
#include <span>
#include <string_view>

#include "accel/bricks.h"
#include "accel/bvh.h"
#include "amr/model.h"
#include "amr/value_percentiles.h"
#include "amr/volume_histogram.h"
#include "shared/amr_gpu.h"

namespace amrvk::scene {

struct Volume {
    amr::Model model;              // cells and every loaded field, in brick order
    size_t fieldIndex = 0;         // the field shown: model.fields[fieldIndex]
    amr::ModelSummary summary;     // bounds (union of leaf cells, voxel space), levels, leaf volume
    amr::FieldStats fieldStats;    // the field's range and volume-weighted mean
    // The field's percentiles by cell count (what the spiky and foggy presets are laid over);
    // [0] and [100] are valueLo() and valueHi().
    amr::Percentiles percentiles;
    // The space each value fills (what the layers preset sizes its opacities by), over
    // [valueLo(), valueHi()] in the frame's bounds.
    amr::VolumeHistogram volumeHistogram;
    glm::i64vec3 localOrigin{0};   // voxel space; = lower corner of frameBounds
    // The box a picture of it frames (voxel space): its bounds, or for a part of a larger data set
    // (VolumeFrame) the whole data's.
    amr::Box3l frameBounds;
    accel::BrickSet bricks;
    // One value of the field per brick slot (NaN for an empty slot) when the bricks were given
    // (bricks.cellIds not empty: a .bricks file, the model in its file order); else empty.
    std::vector<float> slotValues;
    // The cells were freed after the brick build (VolumeOptions::releaseCells); cellCount holds
    // their number.
    bool cellsReleased = false;
    uint64_t cellCount = 0;  // leaf cells of the model, released or not

    const amr::Field& field() const { return model.fields[fieldIndex]; }
    // The field in brick-slot order: the model's own values when it is in brick order.
    std::span<const float> brickValues() const {
        return bricks.cellIds.empty() ? std::span<const float>(field().values) : std::span<const float>(slotValues);
    }
    const amr::Box3l& bounds() const { return summary.bounds; }
    int32_t minLevel() const { return summary.minLevel; }  // sigma is per (1 << minLevel) voxel units
    float valueLo() const { return fieldStats.minValue; }
    float valueHi() const { return fieldStats.maxValue; }
    // World-space corners of the bounds.
    glm::dvec3 worldLo() const { return model.voxelToWorld.toWorld(glm::dvec3(summary.bounds.lower)); }
    glm::dvec3 worldHi() const { return model.voxelToWorld.toWorld(glm::dvec3(summary.bounds.upper)); }
    glm::dvec3 frameWorldLo() const { return model.voxelToWorld.toWorld(glm::dvec3(frameBounds.lower)); }
    glm::dvec3 frameWorldHi() const { return model.voxelToWorld.toWorld(glm::dvec3(frameBounds.upper)); }
    // The same box with its lower corner below the upper on every axis (a negative voxel spacing
    // swaps worldLo and worldHi on that axis): what cut-aways are checked and clamped against.
    glm::dvec3 worldMin() const { return glm::min(worldLo(), worldHi()); }
    glm::dvec3 worldMax() const { return glm::max(worldLo(), worldHi()); }
    // Host bytes of the model (cells and loaded fields, and the slot values of given bricks).
    uint64_t modelBytes() const;

    // Voxel space -> local voxel space (what the GPU sees): the one place localOrigin is
    // subtracted. The integer form throws when a coordinate leaves the int32 range.
    glm::dvec3 toLocal(glm::dvec3 voxel) const { return voxel - glm::dvec3(localOrigin); }
    glm::ivec3 toLocal(glm::i64vec3 voxel) const;
    shared::AabbGpu toLocal(const accel::BoxD& voxelBox) const;
};

// What makeVolume keeps of the model once the bricks exist.
struct VolumeOptions {
    // Frees the 16-byte cell array after the brick build (4 of the 20 bytes per cell of a
    // one-field model are left): the bricks hold every cell's position, and the field in brick
    // order is all the traversals and the ext-brick, abr and grid samplers read. For a one-shot
    // render: model.cells is then empty (Volume::cellsReleased), and what reads the cells (the
    // dense sampler, the majorant check, histograms, reference samplers) refuses with an error.
    bool releaseCells = false;
};

// Takes `model` (validated cells, as amr::readModel returns them), selects `field` (a loaded
// field's name; empty: the default field) and builds the bricks, which puts the model in brick
// order. Throws a one-line error for an unknown field, overlapping cells or a domain wider than
// 2^31 finest cells (what local int32 coordinates can hold).
std::shared_ptr<const Volume> makeVolume(amr::Model model, std::string_view field = {},
                                         const VolumeOptions& options = {});
// makeVolume with bricks made elsewhere (accel::readBricksFile: checked against `model`, may have
// empty slots): the model keeps its order and the field is copied into slot order. What `amrvk
// info --bricks` describes; the renderers build their own bricks.
std::shared_ptr<const Volume> makeVolume(amr::Model model, std::string_view field, accel::BrickSet given);

// What a part of a larger data set (an MPI rank's cells, data-parallel rendering) takes from the
// whole instead of from its own cells, so every part renders in one frame.
struct VolumeFrame {
    amr::Box3l bounds;            // the whole data's (voxel space): its lower corner is the one local
                                  // origin of every part, and the default camera frames it
    int32_t minLevel = 0;         // the whole data's finest level: extinction per the same width
    float valueLo = 0, valueHi = 0;  // the whole field's range (TF fitting)
    amr::Percentiles percentiles;    // the whole field's percentiles (TF fitting; each cell counted once)
    amr::VolumeHistogram volumeHistogram;  // the whole field's (TF fitting; each cell counted once)
};
// makeVolume for a part: its own bounds and bricks, `frame`'s origin, finest level and range.
std::shared_ptr<const Volume> makeVolume(amr::Model model, std::string_view field, const VolumeFrame& frame);

}  // namespace amrvk::scene
