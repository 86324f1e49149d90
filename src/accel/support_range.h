#pragma once
// Exact value ranges over boxes: the range of every cell whose tent support (the cell box grown
// by half its width on each side, i.e. centre +- one width; CLOSED) intersects a CLOSED query
// box in voxel space. This bounds the reconstruction f (a convex combination of exactly those
// cells, exabrick-reference.md 3.1) anywhere in the box, so alpha majorants built on it are valid.
//
// Supports and brick domains lie on the half-voxel lattice and are handled as int64 half-voxel
// boxes; the double query box enters only through ceil(2 lo) and floor(2 hi), so every
// "intersects"/"contains" decision is exact (touching counts as intersecting).
// How: every brick is cut into chunks of at most kSupportChunkCells^3 cells; a BVH (accel/bvh.h)
// over the chunk domains carries, per node, the exact union of its chunk domains and the range
// of their cells. A query takes a node's range whole when its domain lies inside the box, skips
// it when disjoint or when its range cannot widen the result so far, and only scans the cells of
// a chunk that straddles the box (those of its sub-box whose support reaches the box).
#include <cstdint>
#include <span>
#include <vector>

#include "accel/bricks.h"
#include "accel/bvh.h"
#include "accel/majorant_bounds.h"
#include "accel/value_range.h"

namespace amrvk::accel {

constexpr int32_t kSupportChunkCells = 8;  // chunk edge, cells per axis

class SupportRangeQuery {
public:
    // brickValues: one value per brick slot (brickOrderValues); NaN slots are empty and skipped.
    // Keeps references to `bricks` and `brickValues`: both must outlive the query object.
    SupportRangeQuery(const BrickSet& bricks, std::span<const float> brickValues);

    // Range over every non-empty cell whose closed support intersects the closed box (voxel
    // space). Empty (lo > hi) when no support reaches the box, or when box.lo > box.hi on an
    // axis; zero-thickness boxes are valid. Throws amrvk::Error for a NaN coordinate.
    // Thread-safe (const, no shared scratch).
    ValueRange query(const BoxD& box) const;
    // The range a majorant over `box` (faces on the half-voxel lattice) needs: the query over the
    // box grown by marginHalfUnits(margin) half voxels, padded for the GPU's float sums
    // (accel/majorant_bounds.h), so it bounds every sample within `margin` of the box.
    ValueRange majorantRange(const BoxD& box, double margin) const;

    // The structures owned by the query (chunks, BVH, node boxes and ranges), not the inputs.
    uint64_t memoryBytes() const;

private:
    struct Chunk {
        glm::i64vec3 lo, hi;  // domain, half-voxel units, closed: union of its cells' supports
        glm::ivec3 k0;        // first brick-local cell; the chunk ends at min(k0 + edge, size)
        uint32_t brick;
        ValueRange range;  // over its non-empty cells
    };
    struct NodeBounds {
        glm::i64vec3 lo, hi;  // union of the node's chunk domains, half-voxel units
        ValueRange range;     // union of its chunk ranges
    };
    void scanChunk(const Chunk& c, glm::i64vec3 qlo, glm::i64vec3 qhi, ValueRange& r) const;

    const BrickSet* mBricks;
    std::span<const float> mValues;
    std::vector<Chunk> mChunks;
    Bvh mBvh;                        // over chunk domains; exact data in mNodes
    std::vector<NodeBounds> mNodes;  // parallel to mBvh.nodes
};

// Per brick: the majorant range (majorantRange, margin voxel units) over the brick's strict bounds:
// every cell whose support reaches them, its neighbours' cells included, so it bounds f on the
// brick (a leaf-cell region). This is the correct version of upstream's brick-range neighbour
// splatting (exabrick-reference.md 4.2).
std::vector<ValueRange> brickBoundsRanges(const SupportRangeQuery& query, const BrickSet& bricks, double margin);

// Per brick: the same over the brick's basis-function domain (bounds +- half a cell).
std::vector<ValueRange> brickDomainRanges(const SupportRangeQuery& query, const BrickSet& bricks, double margin);

}  // namespace amrvk::accel
