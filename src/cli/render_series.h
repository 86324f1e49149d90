#pragma once
// `amrvk render` over a time series or as a turntable (docs/movies.md): several inputs or a glob
// pattern in natural order, --frames N --orbit DEG, numbered frames or an MP4 through ffmpeg,
// one TF range and camera for every frame, one output in memory at a time, frames a re-run of the
// same command already wrote skipped (the manifest of session/series.h).
#include <string>
#include <vector>

#include "cli/options.h"

namespace amrvk::mpi {
class World;
}

namespace amrvk::cli {

struct SeriesRequest {
    std::vector<std::string> inputs;  // as given: paths and glob patterns (none: the session's input)
    std::string output, jsonFile, varianceFile;
};

// Whether the render command line describes a series: several inputs, a glob pattern, a series
// option (--frames, --orbit, --series-range, --fps, --frames-dir), or an output that names frames
// (a %d pattern, a directory with a trailing '/') or a movie (.mp4).
bool isSeries(const CLI::App& app, const std::vector<std::string>& inputs, const std::string& output);

// Renders the series (one process: refused under an MPI launcher). Returns the exit code.
int renderSeries(const CLI::App& app, const SeriesRequest& request, const ReadArgs& read, const PictureArgs& pic,
                 const SeriesArgs& series, const DeviceArgs& dev, mpi::World* world);

}  // namespace amrvk::cli
