#pragma once
// Deterministic procedural AMR data sets ("amrvk gen"), streamed depth-first to disk.
//
// Every kind is an octree over the cube [0, 2^rootLevel)^3 of finest-level units. A node is
// refined when its refinement score (a measure of how much the field varies inside it, made
// monotone: never larger than its parent's) is >= a threshold t; the leaves are the cells.
// The cell count is a monotone function of t, so t is chosen for the requested count:
//  1. best-first expansion (highest score first) up to min(N, 32768) leaves gives the exact
//     count-versus-threshold curve for small counts in bounded memory;
//  2. depth-first counting passes at 8x, 64x, ... that count, each stopped early once it passes
//     4x its own target, extend the curve; every new t comes from log-log interpolation between
//     the nearest measured points, clamped into the bracket of too-many / too-few thresholds;
//  3. the writing pass itself is the last check: it is abandoned (nothing committed) once it
//     exceeds 1.4 N cells and retried with a corrected t when it ends outside [N/1.4, 1.4 N].
//     A measured t whose count already lies in that range is reused as it is (passes are exact).
// Typical cost: about 1.15 N evaluated cells of counting plus the N written ones.
// Output: cells in depth-first order (children x fastest, then y, then z), level 0 = finest.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "amr/model.h"

namespace amrvk::amr {

enum class SyntheticKind {
    Cloud,   // log-normal turbulent density: hashed hierarchical value noise in a soft ball
    Shells,  // nested spherical shells with box-filtered edges; refined at the shell boundaries
    Teapot,  // tiny torus + ball refined to the finest level inside a 2^20+ wide coarse domain
};

// "cloud" | "shells" | "teapot"; throws amrvk::Error listing the kinds otherwise.
SyntheticKind parseSyntheticKind(std::string_view name);
std::string_view syntheticKindName(SyntheticKind kind);

struct SyntheticParams {
    SyntheticKind kind = SyntheticKind::Cloud;
    uint64_t cells = 1000000;  // target leaf-cell count; the result lies within a factor 1.4
    uint64_t seed = 1;         // same seed (and other parameters) = byte-identical output
    int levels = 0;            // octree depth + 1, i.e. domain 2^(levels-1) units; 0 = by kind/N
    std::string field;         // field name; empty = "scalars" (files BASE.scalars)
    // Called every 65536 cells with the phase ("counting pass K", "writing" or "generating")
    // and its estimated completed fraction in [0, 1); no throttling.
    std::function<void(std::string_view phase, double fraction)> progress;
};

struct SyntheticStats {
    uint64_t cells = 0;
    int rootLevel = 0;                    // domain is 2^rootLevel finest units wide
    int minLevel = 0, maxLevel = 0;       // levels present among the cells
    std::vector<uint64_t> cellsPerLevel;  // index = level, size maxLevel + 1
    uint64_t bytes = 0;                   // bytes written (.cells + .scalars); 0 in memory
    double threshold = 0;                 // refinement threshold t that was used
    int countingPasses = 0;               // depth-first passes spent choosing t (incl. retries)
    bool targetReached = true;            // false when the domain saturated below N / 1.4
    double seconds = 0;                   // wall time of the whole call
};

// Domain depth used for `params` (the rootLevel of the result).
int syntheticRootLevel(const SyntheticParams& params);

// Writes BASE.cells and BASE.scalars (or BASE.<field>.scalars) through AtomicFileWriter in
// chunks of 1M cells; memory stays bounded independent of the cell count. A failed or
// interrupted run leaves neither file behind.
SyntheticStats generateSynthetic(const SyntheticParams& params, const std::filesystem::path& base);

// The same cells and values in memory (format "synthetic", one field), for tests and benchmarks.
Model makeSyntheticModel(const SyntheticParams& params, SyntheticStats* stats = nullptr);

}  // namespace amrvk::amr
