#pragma once
// Active brick regions (exabrick-reference.md 2.2): disjoint boxes obtained by splitting the union
// of brick basis-function domains at domain faces, so that the set of bricks whose domain overlaps
// an ABR is the same everywhere inside it. Empty space gets no ABR.
#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

#include "accel/bricks.h"
#include "accel/value_range.h"

namespace amrvk::accel {

// A box in half-voxel units ("2x voxel space") so that domains (bounds +- half a cell) are exact.
struct HalfBox {
    glm::i64vec3 lo, hi;
    glm::dvec3 lower() const { return glm::dvec3(lo) * 0.5; }  // voxel space
    glm::dvec3 upper() const { return glm::dvec3(hi) * 0.5; }
    double volume() const {
        glm::dvec3 s = upper() - lower();
        return s.x * s.y * s.z;
    }
};

// Basis-function domain of a brick: its bounds grown by half a cell on each side.
HalfBox brickDomain(const Brick& brick);

struct Abr {
    HalfBox box;
    uint32_t brickBegin = 0;  // first entry in AbrSet::brickList
    uint32_t brickCount = 0;  // bricks whose domain overlaps the box, ids sorted ascending
    int32_t finestLevel = 0;  // finest level among the listed bricks
};

struct AbrSet {
    std::vector<Abr> abrs;
    std::vector<uint32_t> brickList;
    double buildSeconds = 0;
    uint64_t memoryBytes() const {
        return abrs.size() * sizeof(Abr) + brickList.size() * sizeof(uint32_t);
    }
    std::span<const uint32_t> bricksOf(const Abr& a) const {
        return {brickList.data() + a.brickBegin, a.brickCount};
    }
};

AbrSet buildAbrs(const BrickSet& bricks);

class SupportRangeQuery;

// Majorant range per ABR (SupportRangeQuery::majorantRange, margin voxel units): every cell whose
// tent support (centre +- one cell width) reaches the closed ABR box, also from bricks whose
// domain only touches it (their weight is 0 on the box but not a float rounding beyond it), with
// room for the GPU's float sums. NaN slots are skipped.
std::vector<ValueRange> computeAbrValueRanges(const AbrSet& abrs, const SupportRangeQuery& query, double margin);

}  // namespace amrvk::accel
