#pragma once
// Command-line options of the amrvk subcommands (CLI11). Each option is declared once, with its
// name, value names, default, check and help, in a function that adds a group of options to a
// command and writes the parsed values into the structs the command uses; render, bench and the
// viewer share them. Defaults shown by --help come from the structs as they are when the options
// are added, so a command sets its own defaults first.
#include <CLI/CLI.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "amr/readers.h"
#include "gpu/context.h"
#include "scene/camera.h"
#include "scene/render_settings.h"
#include "scene/structure_config.h"

namespace amrvk::cli {

// An app named "amrvk <command>" gets amrvk's help layout (usage, its description, then each group
// of options with value names, checks and default) and leaves unknown arguments to
// parseCommandLine.
void setUpCommand(CLI::App& app);

// Parses the arguments after the command name. Returns false when --help was given (the help is
// printed on stdout). Throws amrvk::Error with a one-line message naming the option and the value
// for anything else: unknown options, missing or extra values, failed checks.
bool parseCommandLine(CLI::App& app, std::vector<std::string> args);

// Checks for numeric options; their messages name the value ("0 is outside [1, 64]") and CLI11
// puts the option's name in front. integerIn also accepts exact exponent forms such as 1e6; its
// hi = INT64_MAX means no upper limit. Value names must not contain ':' (the help puts a check's
// description after the first ':' of the type name into the description column).
enum class Open { None, Low, High, Both };  // which ends of an interval are excluded
CLI::Validator integerIn(int64_t lo, int64_t hi);
CLI::Validator numberIn(double lo, double hi, Open open = Open::None);
CLI::Validator finiteNumber();

// Input: --format, --field (repeatable when `multiField`: every field given is loaded; else one),
// --nan, --dims, --type, --threshold.
void addReadOptions(CLI::App& app, amr::ReadOptions& ro, bool multiField);
// --field alone, one value (bench: the field of every input that does not name its own).
void addFieldOption(CLI::App& app, std::string& field);

// Picture: --mode, --dt, --dvr-shading (render and viewer; bench has lists of modes and steps).
void addModeOptions(CLI::App& app, scene::RenderSettings& rs);
// Picture: --size and --seed. Returns --size for a command whose default is not rs's size.
CLI::Option* addImageOptions(CLI::App& app, scene::RenderSettings& rs);
// Medium and lights: --density-scale, --g, --ambient, --background, --light-dir, --light-point
// (repeatable; directional lights first, each kind in the order given).
void addLightingOptions(CLI::App& app, scene::RenderSettings& rs);

// --camera and --fov: an explicit view, else the three-quarter view of each data set.
struct CameraChoice {
    std::optional<std::array<glm::dvec3, 3>> eyeTargetUp;  // world space
    double fovDegrees = 40.0;                              // vertical
    std::optional<scene::Camera> explicitCamera() const;
    // The explicit camera, else scene::defaultCamera over the world box.
    scene::Camera cameraFor(glm::dvec3 worldLo, glm::dvec3 worldHi) const;
};
void addCameraOptions(CLI::App& app, CameraChoice& camera);

// Structures: --traversal (also `auto` when autoTraversal is given: then set instead of
// config.traversal), --sampler, --backend.
void addStructureOptions(CLI::App& app, scene::StructureConfig& config, bool* autoTraversal);
// Structure sizes: --grid (checked when parsed: auto, N or NxMxK with N in [1, 4096]).
void addGridOption(CLI::App& app, std::string& grid);
// Structure sizes: --grid, --kd-leaves, --dense-max-mib.
void addStructureSizeOptions(CLI::App& app, scene::StructureConfig& config);

// Transfer function: --tf-range LO HI (LO <= HI, both finite).
void addTfRangeOption(CLI::App& app, std::optional<std::pair<float, float>>& range);
// Transfer function: --tf, --tf-preset and --tf-range (render and viewer; bench has a list).
struct TfChoice {
    std::string spec = "ramp";  // file or preset (scene::loadTransferFunction)
    std::string preset;         // preset name inside a ParaView JSON file; empty: the first
    std::optional<std::pair<float, float>> range;
};
void addTransferFunctionOptions(CLI::App& app, TfChoice& tf);

// Device: --device, --shader-dir (applied when parsed: gpu::setShaderDirectory), --validation.
void addDeviceOptions(CLI::App& app, gpu::ContextOptions& co);

}  // namespace amrvk::cli
