#pragma once
// Other programs run by amrvk (python3 for the bench plots, ffmpeg for movies): started with an
// argument vector through posix_spawnp, never a shell, so no argument is ever interpreted.
#include <optional>
#include <string>
#include <vector>

namespace amrvk {

enum class ProcessOutput {
    Discard,     // the child's stdout and stderr go to /dev/null
    Capture,     // its stdout is returned, its stderr stays ours
    CaptureAll,  // its stdout and stderr are returned together
};

struct ProcessResult {
    int status = -1;  // exit status; -1: could not be started; 128 + N: ended by signal N
    std::string out;  // what ProcessOutput captured
};

// Runs args[0] (looked up on PATH when it has no '/') with `args` as its argument vector and our
// environment; its stdin is /dev/null. Waits for it to end.
ProcessResult runProcess(const std::vector<std::string>& args, ProcessOutput output);

// The path of the executable `name` as posix_spawnp would find it: `name` itself when it has a
// '/', else the first executable regular file `name` in a directory of PATH; nullopt if none.
std::optional<std::string> findExecutable(const std::string& name);

}  // namespace amrvk
