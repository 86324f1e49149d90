#pragma once
// The AMR data model: leaf cells in the ExaBrick convention plus named scalar fields.
//  - Cell.lower is the integer lower corner in finest-level units ("voxel space").
//  - Cell.level is 0 for the finest possible cells; a cell is (1 << level) units wide and its
//    lower corner is a multiple of its width (checked by validate()).
//  - Leaf cells never overlap; together they are the medium. Field values are cell averages.
#include <glm/glm.hpp>

#include "amr/cell_array.h"
#include "core/file_io.h"

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace amrvk::amr {

// "(lower X,Y,Z level L)", for messages.
std::string describeCell(const Cell& c);

constexpr int kMaxLevel = 30;  // widths up to 2^30 keep int32 corners exact

inline int64_t cellWidth(int32_t level) { return int64_t{1} << level; }

// floor(a / b) and ceil(a / b) for b > 0 (C++ division truncates towards zero).
inline int64_t floorDiv(int64_t a, int64_t b) { return a / b - (a % b != 0 && a < 0 ? 1 : 0); }
inline int64_t ceilDiv(int64_t a, int64_t b) { return -floorDiv(-a, b); }
// Cell volume in voxel units^3: 8^level, exact in double; level in [0, kMaxLevel].
inline constexpr std::array<double, kMaxLevel + 1> kCellVolume = [] {
    std::array<double, kMaxLevel + 1> v{};
    double x = 1;
    for (double& e : v) {
        e = x;
        x *= 8;
    }
    return v;
}();
inline double cellVolume(int32_t level) { return kCellVolume[size_t(level)]; }

// Half-open integer box [lower, upper) in voxel space; 64-bit so lower + width cannot overflow.
struct Box3l {
    glm::i64vec3 lower{0};
    glm::i64vec3 upper{0};
    bool empty() const { return upper.x <= lower.x || upper.y <= lower.y || upper.z <= lower.z; }
    glm::i64vec3 size() const { return upper - lower; }
    double volume() const {
        glm::dvec3 s(size());
        return empty() ? 0.0 : s.x * s.y * s.z;
    }
};

struct Field {
    std::string name;
    std::vector<float> values;  // one per cell, in cell order
    // The values' units as the reader knows them (amr/field_units.h): "code units (1 = X g/cm^3)",
    // a unit ("K", yt's "g/cm**3"), or "" when not known. A log scale keeps it: the values are
    // then log10 of numbers in these units.
    std::string units;
};

// world = origin + scale * voxel, per axis.
struct Transform {
    glm::dvec3 origin{0.0};
    glm::dvec3 scale{1.0};
    glm::dvec3 toWorld(glm::dvec3 voxel) const { return origin + scale * voxel; }
};

struct Model {
    std::string format;                       // "exabrick", "amrex", "enzo", "chombo", "carpet", "raw", ...
    std::string source;                       // path the model was read from
    CellArray cells;                          // leaf cells
    std::vector<Field> fields;                // loaded fields, each with cells.size() values
    std::vector<std::string> availableFields; // every field the source offers (loaded or not)
    Transform voxelToWorld;
    std::vector<std::pair<std::string, std::string>> attributes;  // source metadata, for info
    // Bumped whenever the cells are reordered in place (accel::buildBricks puts them in brick
    // order), so whatever indexes cells by position (amr::ReferenceSampler) can tell it has gone
    // stale. Only code that calls buildBricks directly can do that: scene::makeVolume takes the
    // model it reorders.
    uint64_t cellOrder = 0;

    uint64_t cellCount() const { return cells.size(); }
    // Returns the loaded field `name`; throws "unknown field 'X' in SOURCE (available: ...)".
    const Field& field(std::string_view name) const;
    // The field an operation uses when the user named none: defaultFieldIndex of the loaded ones.
    const Field& defaultField() const;
};

// The field a picture shows when none is named, as yt shows a density: the first of `names` that
// is density-like (density, dens, rho or gas_density, in any case), else the first. An AMReX
// plotfile lists x_velocity first; its density is the field a user expects. 0 for no names.
size_t defaultFieldIndex(const std::vector<std::string>& names);

struct ModelSummary {
    Box3l bounds;                          // union of leaf-cell boxes, voxel space
    int minLevel = 0, maxLevel = 0;
    std::vector<uint64_t> cellsPerLevel;   // index = level (0 = finest), size maxLevel + 1
    double leafVolume = 0;                 // sum of cell volumes, voxel units^3
};
// In parallel over fixed chunks (same result on every machine); the model passes validateCells.
ModelSummary summarize(const Model& model);
// From cell counts per level (index = level): the finest and coarsest level present (both 0 when
// none) and the counts up to the coarsest (ModelSummary, SyntheticStats).
void levelRange(const std::array<uint64_t, kMaxLevel + 1>& perLevel, int& minLevel, int& maxLevel,
                std::vector<uint64_t>& cellsPerLevel);

struct FieldStats {
    float minValue = 0, maxValue = 0;
    double volumeWeightedMean = 0;  // sum(v * width^3) / sum(width^3)
};
FieldStats computeFieldStats(const Model& model, const Field& field);

// What to do with NaN/Inf field values (see docs/formats.md):
//  Reject: throw "SOURCE: field 'F' has a non-finite value (nan) at cell N".
//  Drop:   remove those cells (the medium is empty there), consistently for every field.
enum class NanPolicy { Reject, Drop };
NanPolicy parseNanPolicy(std::string_view text);
const char* nanPolicyName(NanPolicy policy);  // "reject" | "drop"
void applyNanPolicy(Model& model, NanPolicy policy);

// How field values are taken. Log: log10 of each cell's value, before reconstruction (as yt does),
// so reconstruction, ranges and exact majorants all work on the logs (a monotone map of each cell
// range). Values <= 0 have no logarithm: they are floored at `floor` (> 0), by default the field's
// smallest positive value; a field with no positive value is an error. Auto: the field decides
// (autoScaleOf) once its values are read, as yt takes the log of fields that span decades; it is
// resolved to Linear or Log before the values are used (readModel, resolvedScale).
enum class FieldScale { Linear, Log, Auto };
FieldScale parseFieldScale(std::string_view text);
const char* fieldScaleName(FieldScale scale);
struct ScaleReport {
    uint64_t floored = 0;  // cells whose value was <= 0 (or below the floor) and became log10(floor)
    double floor = 0;      // the floor used (0 for linear)
};
// The smallest positive finite value of `values` (0 when there is none).
float smallestPositive(std::span<const float> values);
// Auto's choice for a field: Log where every finite value is positive and the largest is at least
// kAutoLogSpan times the smallest (two decades or more), else Linear (NaN values are ignored).
constexpr double kAutoLogSpan = 100;
// The finite extremes of values seen so far (a field read whole, or streamed in chunks).
struct FiniteExtremes {
    float lo = std::numeric_limits<float>::infinity(), hi = -std::numeric_limits<float>::infinity();
    void add(std::span<const float> values);
    // Auto's choice for them (Linear when no finite value was seen).
    FieldScale autoScale() const;
};
FieldScale autoScaleOf(float smallest, float largest);
FieldScale autoScaleOf(std::span<const float> values);
// The scale a model's values are in: Log where applyFieldScale took their log10.
FieldScale scaleOf(const Model& model);
// Applies `scale` (Linear or Log) to every field of `model` (NaN policy first: NaN stays NaN); floor 0 = each
// field's smallest positive value. Records "scale" (and "logFloored" when cells were floored) in
// model.attributes and returns what the first field needed. Throws "SOURCE: field 'F' has no
// positive value: log scale needs one (or --log-floor)".
ScaleReport applyFieldScale(Model& model, FieldScale scale, double floor = 0);

// World coordinates amrvk holds: a finest cell's size in [kMinCellSize, kMaxWorldCoordinate] and
// an origin within +-kMaxWorldCoordinate on every axis (the camera and the legend's world
// lengths work in them; a size of 1e-300 or 1e300 made the default camera's eye and target one).
inline constexpr double kMinCellSize = 1e-30;
inline constexpr double kMaxWorldCoordinate = 1e30;

// Throws amrvk::Error on: a field whose length differs from the cell count, a level outside
// [0, kMaxLevel], a cell not aligned to its width or reaching past 2^31-1, an empty model, a
// world transform outside the limits above.
// Checks every cell on its own (in parallel, no extra memory); readModel runs it.
void validateCells(const Model& model);
// validateCells, and two overlapping cells (a hash of every cell: about 12 bytes per cell).
// The brick build (accel::buildBricks) finds overlaps too, at no cost, so the render path
// needs only validateCells; this is for models that are not bricked (convert, tests).
void validate(const Model& model);

}  // namespace amrvk::amr
