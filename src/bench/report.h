#pragma once
// Reports of `amrvk bench` in its output directory: results.json (every figure, device, command
// line), results.csv (one row per run), results.md (the paper's layout: rows traversal x sampler
// x back-end, columns data set x TF; best three and the worst marked; then speed against error,
// dvr, grid sweep, --auto and the reference commands) and PNG plots (RMSE against time log-log per
// group, dvr against path tracing, frames/s against macrocell resolution, device memory per
// combination). Every file is written to a temporary name and renamed.
#include <filesystem>
#include <string>
#include <vector>

#include "bench/bench_runner.h"

namespace amrvk::bench {

std::string resultsJson(const BenchResults& results);
std::string resultsCsv(const BenchResults& results);
std::string resultsMarkdown(const BenchResults& results, const std::vector<std::string>& plotFiles);
// Writes the plots; returns their file names (relative to dir).
std::vector<std::string> writePlots(const BenchResults& results, const std::filesystem::path& dir);
// All of the above into dir.
void writeReports(const BenchResults& results, const std::filesystem::path& dir);

}  // namespace amrvk::bench
