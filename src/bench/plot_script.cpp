#include "bench/plot_script.h"

#include <cstdio>
#include <sstream>

#include "core/process.h"

namespace fs = std::filesystem;

namespace amrvk::bench {

fs::path plotScriptPath() {
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    return ec ? fs::path("plot_bench.py") : self.parent_path() / "plot_bench.py";
}

std::optional<std::string> findMatplotlibPython() {
    for (const char* python : {"python3", "/usr/bin/python3"})
        if (runProcess({python, "-c", "import matplotlib"}, ProcessOutput::Discard).status == 0) return python;
    return std::nullopt;
}

PlotOutcome drawPlots(const fs::path& dir) {
    PlotOutcome outcome;
    const fs::path script = plotScriptPath();
    const std::string byHand = "python3 " + script.string() + " " + dir.string();
    std::error_code ec;
    if (!fs::is_regular_file(script, ec)) {
        outcome.note = "plots not drawn: " + script.string() +
                       " is missing (the build copies tools/plot_bench.py next to amrvk); to draw them: python3 "
                       "tools/plot_bench.py " + dir.string();
        return outcome;
    }
    const std::optional<std::string> python = findMatplotlibPython();
    if (!python) {
        outcome.note = "plots not drawn: no Python with matplotlib (tried python3 on PATH and /usr/bin/python3); "
                       "install python3-matplotlib, then run: " + byHand;
        return outcome;
    }
    // Its stdout names the files written; anything else (its error, matplotlib's warnings) is kept
    // apart: the last such line is the reason when it fails, and the others pass through.
    const ProcessResult run = runProcess({*python, script.string(), dir.string()}, ProcessOutput::CaptureAll);
    std::vector<std::string> messages;
    std::istringstream lines(run.out);
    for (std::string line; std::getline(lines, line);) {
        if (line.empty()) continue;
        const bool file = line.find('/') == std::string::npos && (line.ends_with(".png") || line.ends_with(".pdf")) &&
                          fs::is_regular_file(dir / line, ec);
        (file ? outcome.files : messages).push_back(line);
    }
    if (run.status != 0) {
        outcome.failed = true;
        outcome.note = "plots not drawn: " + script.filename().string() + " ended with status " +
                       std::to_string(run.status) + (messages.empty() ? "" : " (" + messages.back() + ")") +
                       "; to retry: " + byHand;
        return outcome;
    }
    for (const std::string& m : messages) std::fprintf(stderr, "%s\n", m.c_str());
    return outcome;
}

}  // namespace amrvk::bench
