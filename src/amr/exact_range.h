#pragma once
// The exact range of the tent reconstruction (amr/sampler.h) over a closed box, by brute force
// over the cells and without bricks: the independent answer scene/majorant_check.* holds every
// traversal's value ranges to.
// Why lattice vertices suffice: along each axis every tent weight changes form only at the planes
// c - w, c and c + w of its cell (centre c, width w). Between consecutive such planes of all the
// cells whose support reaches the box, N = sum(phi v) and D = sum(phi) are multilinear, so N - M D
// is too and its sign over a piece is decided at the piece's corners: f = N / D takes its extremes
// over the box (where D > 0) among its values at the lattice of the box faces and those planes.
// How: the box is halved until it spans at most kMaxCellsPerAxis cells of the finest level near
// it on every axis (which levels are near a box comes from an occupancy pyramid per level, so a
// coarse region is never evaluated at a fine lattice); each part gathers the cells whose support
// reaches it through the exact (lower, level) hash and evaluates f at every lattice vertex, in
// double. Thread-safe: over() keeps no shared scratch.
#include <glm/glm.hpp>

#include <cstdint>
#include <limits>
#include <vector>

#include "amr/cell_hash.h"
#include "amr/model.h"

namespace amrvk::amr {

class ExactRange {
public:
    static constexpr int kMaxCellsPerAxis = 4;

    // Indexes the model's cells (build bricks first: a model reordered afterwards is refused).
    ExactRange(const Model& model, const Field& field);

    struct Result {
        double lo = std::numeric_limits<double>::infinity();  // empty (lo > hi): no support
        double hi = -std::numeric_limits<double>::infinity();  // reaches the box
        double maxAbs = 0;       // largest |value| among the cells whose support reaches the box
        glm::dvec3 argLo{0}, argHi{0};  // where lo and hi are taken
        // The extremes of f -/+ relativeRoom x g, g the same reconstruction of |value| (what a
        // float sum of the weighted values can be off by, in units of the rounding: sum(phi |v|)
        // / sum(phi)). f +- k g = (N +- k N') / D is again a ratio of multilinear sums, so its
        // extremes are taken at the same vertices.
        double roomLo = std::numeric_limits<double>::infinity();
        double roomHi = -std::numeric_limits<double>::infinity();
        uint64_t vertices = 0;   // lattice vertices evaluated
        bool empty() const { return lo > hi; }
    };
    // Closed box [lo, hi], voxel space. NaN values are skipped, as by every sampler.
    Result over(glm::dvec3 lo, glm::dvec3 hi, double relativeRoom = 0) const;

private:
    // One level's occupancy at block size 2^g (g >= level + 3): packed block coordinates.
    struct Blocks {
        int32_t g = 0;
        std::vector<uint64_t> slots;  // open addressing; kEmpty marks a free slot
        uint64_t mask = 0;
        bool contains(uint64_t key) const;
    };
    // Levels (bit i: mLevels[i]) with a block near the box, conservatively: a superset of the
    // levels whose cells' supports reach it.
    uint32_t levelsNear(glm::dvec3 lo, glm::dvec3 hi) const;
    // Halves the box down to kMaxCellsPerAxis cells of its finest level near it, then evaluates.
    void part(glm::dvec3 lo, glm::dvec3 hi, double relativeRoom, Result& r) const;

    const Model& mModel;
    const Field& mField;
    CellHash mHash;
    uint64_t mCellOrder;
    glm::i64vec3 mOrigin{0};               // bounds' lower corner: block coordinates count from it
    std::vector<int32_t> mLevels;           // levels present, ascending
    std::vector<std::vector<Blocks>> mBlocks;  // [level index][g - first g of that level]
};

}  // namespace amrvk::amr
