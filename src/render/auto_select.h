#pragma once
// Automatic structure choice (`amrvk bench --auto`, `amrvk render --traversal auto`): short probe
// renders of every allowed traversal x sampler x back-end on a small image, scored by Monte Carlo
// efficiency 1 / (mean per-pixel sample variance x GPU seconds per sample), since every
// combination estimates the same image; then, when the winner uses a macrocell grid, the grid
// resolution is probed the same way. A probe whose first frame is far slower than the best so far
// is stopped early. Probes take seconds on lavapipe, less on a GPU.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "gpu/context.h"
#include "render/renderer.h"

namespace amrvk::render {

// What the user fixed; everything left empty is chosen.
struct AutoConstraints {
    std::optional<scene::TraversalKind> traversal;
    std::optional<scene::SamplerKind> sampler;
    std::optional<scene::Backend> backend;  // resolved (Sw or Rq) when set
    std::optional<std::string> grid;
    uint32_t kdLeaves = 4096;  // the kd-tree size of kdtree probes and picks (not chosen)
};

struct AutoOptions {
    int probeSize = 48;          // probe image is probeSize^2
    uint32_t probeSpp = 4;       // timed samples per pixel after one warm-up sample
    double slowFactor = 4.0;     // stop a probe whose warm-up frame is this much slower than the best
    std::vector<std::string> gridChoices = {"32", "64", "256"};  // besides auto (128)
};

struct AutoProbe {
    scene::StructureConfig config;
    double secondsPerSpp = 0;  // GPU seconds per frame at the probe size
    double variance = 0;       // mean per-pixel sample variance (rgb mean)
    double efficiency = 0;     // 1 / (variance x secondsPerSpp); 0 when stopped early or failed
    double wallSeconds = 0;    // probe cost incl. structure build and shader compilation
    std::string note;          // why it was stopped or failed
};

struct AutoChoice {
    scene::StructureConfig config;
    std::vector<AutoProbe> probes;
    double seconds = 0;           // wall time of all probes
    double configureSeconds = 0;  // configuring the scene for the pick at the end
};

// Probes with the renderer's volume under `tf` and `settings` (mode, camera, lights; size and
// spp are the probe's): each probe switches the renderer's structures, and it is left with the
// pick's structures and `tf` (its settings and accumulation are the last probe's: set them next).
AutoChoice autoSelect(Renderer& renderer, const scene::TransferFunction& tf,
                      const scene::RenderSettings& settings, const AutoConstraints& constraints,
                      const AutoOptions& options = {},
                      const std::function<void(const std::string&)>& onProbe = {});

}  // namespace amrvk::render
