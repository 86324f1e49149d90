#pragma once
// Deterministic procedural AMR data sets ("amrvk gen"), streamed depth-first to disk.
//
// Block-structured like FLASH/PARAMESH or AMReX: every kind is an octree of nodes over the cube
// [0, 2^rootLevel)^3 of finest-cell units, and every leaf node becomes one full block of B^3
// same-level cells (B = blockCells, a power of two; cell width = node width / B, so cell level =
// node level - log2 B and nodes are never narrower than B). Level 0 is the finest cell level.
// Each cell's value is the field evaluated for that cell exactly as a leaf node of its size
// would be (the octree is refined log2 B further levels inside the block); B = 1 gives one cell
// per leaf. Domain depth unless `levels` is given: the B = 1 rule for N / B^3 cells, in node
// units, plus log2 B (the cell octree for N / B^3 cells with every node widened to a block);
// the teapot's stadium stays at least 2^20 cells wide.
// A node is refined when its refinement score (a measure of how much the field varies inside it,
// made monotone: never larger than its parent's) is >= a threshold t. The cell count is B^3
// times the leaf count, a monotone function of t, so t is chosen for the requested count:
//  1. best-first expansion (highest score first) up to min(N / B^3, 32768) leaves gives the
//     exact count-versus-threshold curve for small counts in bounded memory;
//  2. depth-first counting passes at 8x, 64x, ... that count, each stopped early once it passes
//     4x its own target, extend the curve; every new t comes from log-log interpolation between
//     the nearest measured points, clamped into the bracket of too-many / too-few thresholds;
//  3. the writing pass itself is the last check: it is abandoned (nothing committed) once it
//     exceeds 1.4 N cells and retried with a corrected t when it ends outside [N/1.4, 1.4 N].
//     A measured t whose count already lies in that range is reused as it is (passes are exact).
// Typical cost: counting passes evaluate about 1.15 N / B^3 nodes (block interiors are
// skipped); the writing pass evaluates about 1.15 N nodes (the blocks' subtrees included).
// Small targets: B is halved until N >= 64 B^3 (teapot: 512 B^3), enough blocks to land within
// the factor 1.4 and to span several levels; SyntheticStats::blockCells reports the B used.
// Output: cells in depth-first order (children x fastest, then y, then z; a block is the
// depth-first subtree of its leaf node), level 0 = finest.
// Parts: the fields in amr/synthetic_fields.*, the octree passes in amr/octree_refine.h, the
// choice of t in amr/threshold_search.*, the leaves' destinations in amr/cell_sinks.* (files
// through amr/cells_writer.*); this file pair only picks B, the depth and the field and runs them.
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
    // Number of cell levels the domain allows (cell levels 0..levels-1: the domain is
    // 2^(levels-1) blocks = 2^(levels-1) * B finest cells wide); 0 = by kind and N.
    int levels = 0;
    int blockCells = 8;        // B: cells per block edge, power of two in [1, 32]; 1 = cell octree
    std::string field;         // field name; empty = "scalars" (files BASE.scalars)
    // Time T of the evolving field (amr/synthetic_fields.h; period 1, 0 = the field without time):
    // consecutive times make a time series whose values change smoothly.
    double time = 0;
    // Called every 65536 cells with the phase ("counting pass K", "writing" or "generating")
    // and its estimated completed fraction in [0, 1); no throttling.
    std::function<void(std::string_view phase, double fraction)> progress;
};

struct SyntheticStats {
    uint64_t cells = 0;                   // = blocks * blockCells^3
    int blockCells = 1;                   // B used: the requested one, or smaller for small N
    int rootLevel = 0;                    // domain is 2^rootLevel finest cells wide
    int minLevel = 0, maxLevel = 0;       // levels present among the cells
    std::vector<uint64_t> cellsPerLevel;  // index = level, size maxLevel + 1
    uint64_t bytes = 0;                   // bytes written (.cells + .scalars); 0 in memory
    double threshold = 0;                 // refinement threshold t that was used
    int countingPasses = 0;               // depth-first passes spent choosing t (incl. retries)
    bool targetReached = true;            // false when the domain saturated below N / 1.4
    double seconds = 0;                   // wall time of the whole call
};

// Block edge B used for `params` (the blockCells of the result); throws amrvk::Error when
// params.blockCells is not a power of two in [1, 32].
int syntheticBlockCells(const SyntheticParams& params);

// Domain depth used for `params` (the rootLevel of the result, in finest cells).
int syntheticRootLevel(const SyntheticParams& params);

// Writes BASE.cells and BASE.scalars (or BASE.<field>.scalars) through AtomicFileWriter in
// chunks of 1M cells; memory stays bounded independent of the cell count. A failed or
// interrupted run leaves neither file behind.
SyntheticStats generateSynthetic(const SyntheticParams& params, const std::filesystem::path& base);

// The same cells and values in memory (format "synthetic", one field), for tests and benchmarks.
Model makeSyntheticModel(const SyntheticParams& params, SyntheticStats* stats = nullptr);

}  // namespace amrvk::amr
