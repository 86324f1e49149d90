#pragma once
// The exhaustive host-side majorant check (`amrvk info --check-majorants`, CI on every real sample
// and a 10^6-cell cloud): for every box of every traversal (the macrocells of grid-dda and
// grid-bvh, ABRs, brick bounds, brick domains, and the kd leaves built for each TF), the exact
// range of the reconstruction over the box grown by the position margin (amr/exact_range.h: brute
// force over the cells, no bricks) must fit inside the stored range with room for the GPU's float
// error on both sides (accel/majorant_bounds.h), and, for each TF, its maximum alpha over that
// interval must not exceed the majorant the renderer derives from the stored range (by more than
// the GPU's violation tolerance, 1e-6 relative). The dense sampler's macrocell ranges bound its
// own trilinear resampling of the field, not the reconstruction, and are not checked here
// (accel/dense_grid.h; tests/cpu/dense_grid_test.cpp).
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "accel/bvh.h"
#include "accel/value_range.h"
#include "amr/exact_range.h"
#include "scene/transfer_function.h"
#include "scene/volume.h"

namespace amrvk::scene {

struct MajorantCheckOptions {
    std::vector<TransferFunction> tfs;  // already mapped over the field's range
    std::string grid = "auto";          // macrocells (--grid)
    uint32_t kdLeaves = 4096;           // kd leaves (--kd-leaves)
    uint32_t subMajorants = 8;          // the largest division of a loose macrocell (--sub-majorants; 0: none)
    // Sub-boxes checked per TF at most: of the refined macrocells, every k-th with all its
    // sub-boxes, k the smallest that keeps the count within this (1: every one).
    uint64_t maxSubBoxes = uint64_t(1) << 18;
    // Called between batches: (box set, boxes done, boxes in the set). Optional.
    std::function<void(const std::string&, uint64_t, uint64_t)> onProgress;
};

struct BoxSetCheck {
    std::string boxes;       // "macrocells", "abrs", "brick bounds", "brick domains", "kd leaves", "sub-boxes"
    std::string traversals;  // the --traversal values that step them
    std::string tf;          // kd leaves, sub-boxes: the TF they were built for (only that TF is checked)
    uint64_t sampledEvery = 1;  // sub-boxes: those of every k-th refined macrocell were checked
    uint64_t count = 0;      // boxes
    uint64_t withData = 0;   // boxes some cell support reaches
    uint64_t vertices = 0;   // reconstruction values evaluated
    uint64_t rangeFailures = 0;  // stored range without room for the exact range +- the GPU error
    double worstExcess = 0;      // of the worst range failure, relative to the largest |value| there
    std::string worst;           // one line on the worst range failure (empty without one)
    struct PerTf {
        std::string tf;
        uint64_t failures = 0;  // boxes whose exact alpha maximum exceeds their majorant
        double worstRatio = 0;  // largest (exact alpha maximum) / majorant seen
    };
    std::vector<PerTf> tfs;
    double seconds = 0;
    bool ok() const;
};

// Builds each traversal's structures over `volume` (scene::VolumeScene, as a renderer would) and
// checks their boxes.
std::vector<BoxSetCheck> checkMajorants(const std::shared_ptr<const Volume>& volume, const MajorantCheckOptions& options);

// One box set as the renderer stores it, voxel space.
struct StoredBoxes {
    std::vector<accel::BoxD> boxes;
    std::vector<accel::ValueRange> ranges;
    std::vector<float> majorants;  // kd leaves: their majorants under the one TF they were built for
};
// Checks `s` against the exact reconstruction with the position `margin` and every TF of `tfs`
// (majorants: maxAlpha of the stored range, or s.majorants where given); `out.boxes` names the
// set for progress. What checkMajorants does per set; tests hand it planted defects.
void checkBoxSet(const amr::ExactRange& exact, const StoredBoxes& s, double margin,
                 const std::vector<const TransferFunction*>& tfs, const MajorantCheckOptions& options, BoxSetCheck& out);

}  // namespace amrvk::scene
