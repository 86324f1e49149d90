#pragma once
// Reports of `amrvk bench` in its output directory: results.json (every figure, device, command
// line), results.csv (one row per run), results.md (the paper's layout: rows traversal x sampler
// x back-end, columns data set x TF; best three and the worst marked; then speed against error,
// dvr, grid sweep, --auto, the reference commands and the plots) and the plots that
// tools/plot_bench.py draws from results.json as PNG and PDF (RMSE against time log-log per group,
// dvr against ae tracking, frames/s against macrocell resolution, device memory per combination).
// Every report file is written to a temporary name and renamed.
#include <filesystem>
#include <string>
#include <vector>

#include "bench/bench_runner.h"
#include "bench/plot_script.h"

namespace amrvk::bench {

// results.json and .csv, then the plots (drawPlots), then results.md, into dir. Returns what
// drawPlots reported: the plot files, or the note saying why there are none and how to draw them.
PlotOutcome writeReports(const BenchResults& results, const std::filesystem::path& dir);

}  // namespace amrvk::bench
