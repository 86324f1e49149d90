#pragma once
// Reading AMR data of every supported format into an amr::Model.
#include <glm/glm.hpp>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "amr/model.h"

namespace amrvk::amr {

// Voxels per axis of a raw volume (--dims, a session's read.dims, Python's dims=).
inline constexpr int kMaxRawDim = 1 << 20;

struct ReadOptions {
    std::string format = "auto";      // auto | exabrick | amrex | enzo | chombo | carpet | ramses | raw
    std::vector<std::string> fields;  // fields to load; empty = every field of the source
    NanPolicy nanPolicy = NanPolicy::Reject;
    // How field values are taken (amr::applyFieldScale): linear, or log10 of each cell's value
    // before reconstruction (as yt does); values <= 0 are floored at logFloor, by default (0) the
    // field's smallest positive value; auto: as the field decides (amr::autoScaleOf).
    FieldScale scale = FieldScale::Linear;
    double logFloor = 0;
    // Raw uniform volumes only (dims/type may instead come from a name like vol_64x64x32_uint8.raw):
    glm::ivec3 rawDims{0};            // voxels per axis
    std::string rawType;              // uint8 | uint16 | float32 | float64
    double rawThreshold = 0.0;        // a block becomes one coarse cell when max - min <= threshold
};

// Detects the format of `path` (file or directory) from names and magic bytes, or throws
// "PATH: unrecognised AMR format (use --format ...)".
std::string detectFormat(const std::filesystem::path& path);

// Reads, applies the NaN policy and validates. Throws amrvk::Error with a one-line message.
Model readModel(const std::filesystem::path& path, const ReadOptions& options);

// What readModel does after a reader, for cells made anywhere (a reader, the Python module's arrays,
// a caller's memory): the NaN policy, then every cell checked (validateCells). Overlaps are found
// by the brick build (scene::makeVolume).
Model checkedModel(Model model, NanPolicy nanPolicy);

// The cells of `path` in chunks, for work that must not hold them all (MPI data-parallel reading):
// visit(chunk) gets a model of at most about 2^20 cells with the one field options.fields names
// (empty: the default field), NaN policy applied and cells validated; `head` (optional) first
// gets the source's metadata (format, source, availableFields, voxelToWorld) with no cells.
// ExaBrick files are streamed (memory: one chunk); other formats are read whole, then visited.
void visitCells(const std::filesystem::path& path, const ReadOptions& options,
                const std::function<void(const Model& chunk)>& visit, Model* head = nullptr);

// The scale the values of `path` are read in: options.scale, or for Auto what the field decides
// (autoScaleOf; ExaBrick: one streamed pass over the values; other formats: read whole).
FieldScale resolvedScale(const std::filesystem::path& path, const ReadOptions& options);

// The log floor visitCells uses for `path` (options.scale resolved): options.logFloor, or for a log scale without one the
// field's smallest positive value (ExaBrick: one streamed pass over the values; other formats: 0,
// found when read whole). Callers that visit a file several times resolve it once.
double logFloorOf(const std::filesystem::path& path, const ReadOptions& options);

// Per-format readers: return the model before NaN policy and validation.
Model readExaBrick(const std::filesystem::path& path, const ReadOptions& options);
// ExaBrick in chunks of `chunkCells` (before NaN policy and validation): visitCells' streaming part.
void visitExaBrick(const std::filesystem::path& path, const ReadOptions& options, uint64_t chunkCells,
                   const std::function<void(Model& chunk)>& visit, Model* head);
Model readAmrex(const std::filesystem::path& path, const ReadOptions& options);
Model readEnzo(const std::filesystem::path& path, const ReadOptions& options);
Model readChombo(const std::filesystem::path& path, const ReadOptions& options);
// A Carpet (Cactus) HDF5 file: vertex-centred box-in-box levels onto cells (carpet_reader.cpp).
Model readCarpet(const std::filesystem::path& path, const ReadOptions& options);
// Whether the HDF5 file `path` is a Carpet file (its global-attributes group, or a dataset named
// "THORN::var it=N tl=T ..."); false for any other file, HDF5 or not.
bool isCarpetFile(const std::filesystem::path& path);
// A RAMSES output: its output_NNNNN directory (or a directory holding one info_NNNNN.txt), or
// its info_NNNNN.txt; reads every domain's amr_/hydro_ files (ramses_reader.cpp).
Model readRamses(const std::filesystem::path& path, const ReadOptions& options);
// The info_NNNNN.txt of the RAMSES output `path` names (as readRamses finds it), or an empty path.
std::filesystem::path ramsesInfoFile(const std::filesystem::path& path);
Model readRaw(const std::filesystem::path& path, const ReadOptions& options);

// The files writeExaBrick writes for `model`: "<base>.cells", then per field F
// "<base>.F'.scalars" with F' = scalarsName(F) (or "<base>.scalars" for a single field with
// writeSingleAsPlain).
std::vector<std::filesystem::path> exaBrickFiles(const Model& model, const std::filesystem::path& base,
                                                 bool writeSingleAsPlain = false);
// A field name as it may appear in a file name: names come from input files (Chombo components,
// AMReX variables, Enzo datasets) and sit inside "<base>.NAME.scalars", so '/' and control bytes
// become '_' ("/../../x" becomes "_.._.._x": one file name, never a path); "Y(H2)" stays.
std::string scalarsName(const std::string& field);
// Writes model.cells and every field to exaBrickFiles(...), atomically and all or none. Throws
// when two fields get the same file name.
void writeExaBrick(const Model& model, const std::filesystem::path& base,
                   bool writeSingleAsPlain = false);

}  // namespace amrvk::amr
