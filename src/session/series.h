#pragma once
// A time series or turntable rendered by `amrvk render` (docs/movies.md), window- and Vulkan-free:
// which inputs in which order, one frame per input (or N frames of one input), the camera's
// azimuth per frame, where the numbered frames go, and the manifest beside them that lets a re-run
// of the same command skip the frames it already wrote.
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "amr/readers.h"
#include "amr/value_percentiles.h"
#include "amr/volume_histogram.h"
#include "scene/camera.h"

namespace amrvk::session {

// Natural order of names: runs of digits compare as numbers (output_2 before output_10, leading
// zeros ignored), everything else byte by byte; names equal that way fall back to plain order.
bool naturalLess(std::string_view a, std::string_view b);

// The outputs of a series from the command line's arguments: an argument naming an existing path
// is taken as it is; any other with a wildcard (* ? [) is a glob(3) pattern that amrvk expands
// (quote it so the shell does not). All of them sorted in natural order, whatever order they
// came in. One-line errors: a pattern that matches nothing, an output named twice.
std::vector<std::string> expandInputs(const std::vector<std::string>& args);
// Whether expandInputs takes `arg` as a glob pattern: it has * ? or [ and names no existing path.
bool isInputPattern(const std::string& arg);

// The TF range of a series when --tf-range does not give it: the first output's field range, or
// the union of every output's (a pass over the outputs first, one in memory at a time). spiky and
// foggy are fitted to the first output's percentiles, or to every output's pooled
// (amr::pooledPercentiles, from the same pass), and layers to its volume histogram or their mean
// (amr::pooledVolumeHistograms).
enum class SeriesRange : uint8_t { First, Union };
SeriesRange parseSeriesRange(std::string_view name);  // "first" | "union"

// The one scale of a series: `read`'s, or where it is auto the scale the first output decides
// (read with `field`, empty: its default), so one TF range means the same on every output.
amr::FieldScale seriesScale(const std::vector<std::string>& inputs, const amr::ReadOptions& read,
                            const std::string& field);

// Every output's field statistics pooled, for one TF over a series (--series-range union): the
// union of their ranges, their pooled percentiles (spiky, foggy) and volume histograms (layers).
// Each output is read alone (one in memory at a time) with `read`; `field` (empty: each output's
// default, then the first's for the rest) is set to the field read. Progress on stderr.
struct SeriesStatistics {
    std::pair<float, float> range;
    amr::Percentiles percentiles;
    amr::VolumeHistogram volumes;  // empty where no output has a positive-volume value
};
SeriesStatistics seriesStatistics(const std::vector<std::string>& inputs, const amr::ReadOptions& read,
                                  std::string& field);

// The input of each frame: one frame per input, or `frames` frames of a single input (a
// turntable). One-line errors: --frames with several inputs, --orbit over one input without
// --frames, a frame count above 100000.
std::vector<std::string> planFrames(const std::vector<std::string>& inputs, std::optional<uint32_t> frames,
                                    bool orbitGiven);

// Azimuth of frame k of n over an orbit of `degrees`: k * degrees / n, so a 360-degree orbit
// loops without repeating its first frame.
double frameAzimuth(uint32_t k, uint32_t n, double degrees);

// Where the frames of a series go: a printf pattern with one integer conversion.
struct FrameOutput {
    std::string pattern;                            // e.g. "frames/f_%04d.png" ('%' of the path written as %%)
    std::filesystem::path directory;                // the frames' directory ("." for a bare name)
    std::filesystem::path manifest;                 // beside the frames: the pattern's name with the number replaced by
                                                    // "manifest" and the extension by .json (f_manifest.json)
    std::string extension;                          // ".png", ".exr" or ".pfm"
    std::filesystem::path frame(uint32_t k) const;  // the file of frame k (numbered from 0)
};
// Whether `text` holds a frame number conversion (%d, %Nd or %0Nd; %% is a literal %): an -o
// that names numbered frames. A '%' in any other form leaves a single picture's name as it is.
bool hasFrameNumber(std::string_view text);
// `text` (given as `option`): a pattern with exactly one %d, %Nd or %0Nd (N <= 9; %% a literal %)
// and an image extension, or a directory (existing, or written with a trailing '/'), whose frames
// are DIR/frame_%04d.png. A plain file name is an error when frameCount > 1.
FrameOutput frameOutput(const std::string& option, const std::string& text, uint32_t frameCount);

// A file's size and modification time, to tell whether it changed since it was read.
struct FileStamp {
    uint64_t bytes = 0;
    int64_t modified = 0;  // std::filesystem::file_time_type ticks
    bool operator==(const FileStamp&) const = default;
};
// `path`'s stamp now; nullopt when it cannot be read (removed, or not a file).
std::optional<FileStamp> fileStamp(const std::filesystem::path& path);

// What the manifest beside the frames records: the command that made them and which are done.
struct FrameManifest {
    std::string recipe;       // what makes the frames (the caller's canonical text of the command)
    std::set<uint32_t> done;  // frames written by this recipe
    // Resolved on the first run and reused when a run resumes, so every frame shares them:
    std::optional<std::pair<float, float>> tfRange;  // the range the TF was fitted to (none: fixed TF)
    // The percentiles spiky and foggy were fitted to (none: a manifest of an older amrvk, whose
    // frames had the presets' range-fixed shapes over tfRange, or a TF not fitted).
    std::optional<amr::Percentiles> tfPercentiles;
    std::optional<amr::VolumeHistogram> tfHistogram;  // what layers was fitted to (with tfPercentiles)
    scene::Camera camera;                            // frame 0's camera (azimuth 0)
    glm::dvec3 centre{0.0};                          // the orbit's centre (the first output's world box centre)
    std::string field;                               // the field every output shows
    // Every file the done frames were read from (absolute paths), with its size in bytes and its
    // modification time (the file clock's ticks) then: a re-run that renders nothing still refuses
    // an output that would replace one, and renders anew when any of them changed. None in an
    // older amrvk's manifest.
    std::optional<std::map<std::string, FileStamp>> inputsRead;
};
// nullopt when the file does not exist; a one-line error naming it when it is not a manifest.
std::optional<FrameManifest> loadFrameManifest(const std::filesystem::path& path);
void saveFrameManifest(const std::filesystem::path& path, const FrameManifest& m);  // atomic

}  // namespace amrvk::session
