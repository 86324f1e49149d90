#pragma once
// Automatic structure choice (`amrvk bench --auto`, `amrvk render --traversal auto`) by a cost model:
// every combination estimates the same image, so the most efficient one has the least
// (variance x GPU time) per sample. Measured, at a size that fills the device (2^20 paths per
// sample on a GPU, 96^2 on a CPU device: a small probe times the dispatch and the longest path,
// not the throughput; at 48^2 on lavapipe the spiky tail turned the order of two combinations)
// and with the GPU timer:
//  - each allowed traversal (and back-end) with one reference sampler: its GPU time, lookups,
//    steps and null collisions per path and its variance (the counts do not depend on the sampler:
//    every sampler gives the same values, so the paths are the same);
//  - each other sampler under the most efficient traversal: the unit cost of its lookups, ns per lookup
//    above the reference sampler's, (time(s) - time(ref)) / lookups.
// Every other combination is predicted from its traversal's time and counts and the sampler's
// unit cost (but abr/abr, which samples without a point query, is measured); a predicted best is
// measured before it can win. Macrocell resolutions (1/4, 1/2 and 2 times auto's, then finer
// while the finest wins, up to 256) are then measured for a grid winner and for the grid
// traversals within slowFactor of the best; each of those at its best grid and at the default
// grid is then measured with sub-majorants (scene/sub_majorants.h: the same paths, fewer lookups
// where the TF makes macrocells loose, a per-TF build). A probe far slower than the best so far is stopped after its
// first sample. The measured probes within contenderBand of the best are measured again and keep the mean of both.
// Measured probes within tieTolerance of the best tie (two runs of one combination on lavapipe differ by 10-40%): the
// one with the fewest structures wins, then the most efficient.
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
    std::optional<uint32_t> subMajorants;  // StructureConfig::subMajorants; empty: off or kSubMajorantsProbed
};
// The sub-majorant division auto measures for the grid combinations (step 4c).
inline constexpr uint32_t kSubMajorantsProbed = 8;

struct AutoOptions {
    int probeSize = 0;           // probe image is probeSize^2; 0 = fill the device (1024 on GPUs, 96 on CPUs)
    uint32_t probeSpp = 0;       // timed samples per pixel after one warm-up sample (>= 2: a variance); 0 = 2 on GPUs, 16 on CPUs
    double slowFactor = 4.0;     // stop a probe whose warm-up frame is this much slower than the best
    // Macrocell resolutions measured besides auto's, as multiples of auto's macrocells on the
    // longest axis (accel::parseGridDims: 128 from 1,048,576 cells on, fewer for smaller data, so
    // 32, 64 and 256 there); a resolution equal to auto's or below 4 is left out.
    std::vector<double> gridFactors = {0.25, 0.5, 2.0};
    // Where the finest of those is a combination's best measured grid, twice it is measured, and so
    // on while the finest wins, up to this many macrocells on the longest axis (the protocol's
    // finest grid; Enzo DD0018 at 256 took 389 MB of device memory, benchmarks section 25).
    int maxExtendedGrid = 256;
    double minProbeSeconds = -1;  // timed GPU seconds a probe aims at (more samples, up to 256); < 0 = 0.25 on CPUs, 0.05 on GPUs
    double tieTolerance = 0.1;   // measured probes this close to the best tie; the one that builds less wins
    double contenderBand = 0.75;  // measured probes this close to the best are measured again ...
    int contenders = 3;           // ... at most this many (0: none), and keep the mean of both
};

struct AutoProbe {
    scene::StructureConfig config;
    double secondsPerSpp = 0;  // GPU seconds per sample of the probe image (measured or predicted)
    double variance = 0;       // mean per-pixel sample variance (rgb mean)
    double efficiency = 0;     // 1 / (variance x secondsPerSpp); 0 when stopped early or failed
    double lookupsPerPath = 0, stepsPerPath = 0, nullsPerPath = 0;  // counts (measured runs)
    bool predicted = false;    // from the cost model, not rendered
    double wallSeconds = 0;    // probe cost incl. structure build and shader compilation
    std::string note;          // why it was stopped or failed
};

struct AutoChoice {
    scene::StructureConfig config;
    std::vector<AutoProbe> probes;  // measured and predicted, in the order they were made
    // The unit costs of the model: per sampler, GPU ns per lookup above the reference sampler's.
    std::vector<std::pair<scene::SamplerKind, double>> lookupNs;
    int probeSize = 0;
    double seconds = 0;           // wall time of all probes
    double configureSeconds = 0;  // configuring the scene for the pick at the end
};

// Step 5's rule: among the measured probes within tieTolerance of the most efficient, the one
// that builds the fewest structures (one rebuilt per TF edit counts once more), then the most
// efficient of those; any grid, the default one no more than another (benchmarks section 26: the
// default grid won a tie on Enzo at 0.93 of the best probe and rendered at 0.76 of grid 256).
// Null when no probe was measured.
const AutoProbe* pickAmongTies(const std::vector<AutoProbe>& probes, double tieTolerance);

// Step 4a's rule: the next --grid to measure for `combination` (its traversal, sampler and
// back-end) when its best measured probe so far is at grid `finest`: twice `finest`, at most
// maxGrid; 0 when another grid is its best, or the step would be less than 1.5x finer.
int nextFinerGrid(const std::vector<AutoProbe>& probes, const scene::StructureConfig& combination, int finest,
                  int maxGrid);

// Probes with the renderer's volume under `tf` and `settings` (mode, camera, lights; size and
// spp are the probe's): each probe switches the renderer's structures, and it is left with the
// pick's structures and `tf` (its settings and accumulation are the last probe's: set them next).
AutoChoice autoSelect(Renderer& renderer, const scene::TransferFunction& tf,
                      const scene::RenderSettings& settings, const AutoConstraints& constraints,
                      const AutoOptions& options = {},
                      const std::function<void(const std::string&)>& onProbe = {});

}  // namespace amrvk::render
