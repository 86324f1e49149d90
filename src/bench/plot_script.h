#pragma once
// The plots of `amrvk bench` are drawn by tools/plot_bench.py (matplotlib) from DIR/results.json.
// The build copies the script next to the binaries (build/bin/plot_bench.py); amrvk runs that copy
// with the first interpreter that can `import matplotlib`: `python3` on PATH, then
// /usr/bin/python3. Processes are started with an argument vector (core/process.h), never a shell.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace amrvk::bench {

struct PlotOutcome {
    std::vector<std::string> files;  // written by the script, relative to the directory (PNG and PDF)
    std::string note;                // empty when the script ran; else one line: why not, and how to
                                     // draw the plots by hand
    bool failed = false;             // the script ran and failed (a plot not written): bench's error
};

// plot_bench.py in the directory of the running executable (it may not exist).
std::filesystem::path plotScriptPath();

// The first of `python3` on PATH and /usr/bin/python3 that runs `import matplotlib`; nullopt if none.
std::optional<std::string> findMatplotlibPython();

// Runs the script on dir/results.json and returns the files it reports. Never throws: a missing
// script or interpreter is a note; a script that ran and failed (a full disk) sets `failed`, with
// its last message in the note, for the caller to end with an error once the reports are written.
PlotOutcome drawPlots(const std::filesystem::path& dir);

}  // namespace amrvk::bench
