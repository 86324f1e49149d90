#pragma once
// What an edit invalidates: the one rule the renderer follows (and the viewer relies on), so an
// interactive change redoes only what depends on it. Window-free and Vulkan-free.
//   camera, image size, seed      -> accumulation (size: also the accumulation buffer)
//   mode                          -> accumulation, pipeline selection
//   lighting, medium (cut-away too), dvr options -> accumulation
//   transfer function             -> majorants, culled traversal hierarchy, kd-tree, accumulation
//   structure combination         -> device copy, majorants, culling, kd-tree, pipelines, accumulation
//   shader sources                -> pipelines, accumulation
//   control extinction            -> minorants made or dropped, majorants (which write them), culling,
//                                    kd-tree, pipeline selection (a specialization), accumulation
// Every change resets the accumulation: the image it held no longer estimates the new picture.
#include <cstdint>
#include <string>

#include "scene/render_settings.h"

namespace amrvk::scene {

enum class Change : uint32_t {
    Camera = 1u << 0,            // eye, target, up, field of view
    ImageSize = 1u << 1,         // width, height
    Seed = 1u << 2,
    Mode = 1u << 3,              // ae | ss | ms | dvr
    Lighting = 1u << 4,          // ambient, background, lights
    Medium = 1u << 5,            // density scale, phase g, tracking step cap, shadow estimator, cut-away
    DvrOptions = 1u << 6,        // dvr step and shading
    TransferFunction = 1u << 7,
    Structure = 1u << 8,         // traversal, sampler, back-end, grid, kd leaves
    Shaders = 1u << 9,
    Control = 1u << 10,          // the trackers' control extinction (minorants or none)
};

// A set of changes (bit mask of Change).
struct ChangeSet {
    uint32_t bits = 0;
    ChangeSet() = default;
    ChangeSet(Change c) : bits(uint32_t(c)) {}
    bool has(Change c) const { return (bits & uint32_t(c)) != 0; }
    bool empty() const { return bits == 0; }
    ChangeSet& operator|=(ChangeSet o) {
        bits |= o.bits;
        return *this;
    }
    friend ChangeSet operator|(ChangeSet a, ChangeSet b) { return a |= b; }
};

// What has to be redone or rebuilt after a set of changes.
struct Invalidation {
    bool accumulation = false;        // zero the image and the sample count
    bool accumulationBuffer = false;  // reallocate it (size)
    bool viewParams = false;          // ViewGpu
    bool shadingParams = false;       // ShadingGpu
    bool pipelines = false;           // drop compiled pipelines (structure, shaders)
    bool majorants = false;           // majorant pass over every structure
    bool minorants = false;           // the macrocells' control extinction made or dropped (before the majorants)
    bool culling = false;             // culled traversal hierarchy (sw BVH / rq BLAS)
    bool kdTree = false;              // the TF-specific kd-tree (kdtree traversal)
    bool deviceScene = false;         // the device copy of the TF-independent structures
};

Invalidation invalidatedBy(ChangeSet changes);

// The changes that turn settings `from` into `to` (empty when they render the same picture).
ChangeSet settingsChanges(const RenderSettings& from, const RenderSettings& to);

// "camera|lighting" etc. for logs and test messages.
std::string describe(ChangeSet changes);

}  // namespace amrvk::scene
