#include "bench/plot_script.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <sstream>

extern char** environ;

namespace fs = std::filesystem;

namespace amrvk::bench {

namespace {

enum class Output { Discard, Capture };  // child's stdout and stderr to /dev/null, or stdout to us

struct ProcessResult {
    int status = -1;  // exit status; -1: could not be started; 128 + N: killed by signal N
    std::string out;  // stdout with Output::Capture
};

// Runs args[0] (looked up on PATH when it has no '/') with args as its argument vector and our
// environment; stdin is /dev/null. Waits for it to end.
ProcessResult runProcess(const std::vector<std::string>& args, Output output) {
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    int pipeFds[2] = {-1, -1};
    if (output == Output::Capture && ::pipe2(pipeFds, O_CLOEXEC) != 0) return {};
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    if (output == Output::Discard) {
        posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
        posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    } else {
        posix_spawn_file_actions_adddup2(&actions, pipeFds[1], STDOUT_FILENO);
    }
    pid_t pid = 0;
    const int spawned = ::posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (pipeFds[1] >= 0) ::close(pipeFds[1]);
    ProcessResult result;
    if (spawned == 0) {
        char buffer[4096];
        while (pipeFds[0] >= 0) {
            const ssize_t n = ::read(pipeFds[0], buffer, sizeof buffer);
            if (n > 0) result.out.append(buffer, size_t(n));
            else if (n == 0 || errno != EINTR) break;
        }
        int status = 0;
        while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
        }
        result.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
    if (pipeFds[0] >= 0) ::close(pipeFds[0]);
    return result;
}

}  // namespace

fs::path plotScriptPath() {
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    return ec ? fs::path("plot_bench.py") : self.parent_path() / "plot_bench.py";
}

std::optional<std::string> findMatplotlibPython() {
    for (const char* python : {"python3", "/usr/bin/python3"})
        if (runProcess({python, "-c", "import matplotlib"}, Output::Discard).status == 0) return python;
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
    const ProcessResult run = runProcess({*python, script.string(), dir.string()}, Output::Capture);
    if (run.status != 0) {
        outcome.note = "plots not drawn: " + *python + " " + script.string() + " ended with status " +
                       std::to_string(run.status) + " (see its messages above); to retry: " + byHand;
        return outcome;
    }
    std::istringstream lines(run.out);
    for (std::string line; std::getline(lines, line);)
        if (!line.empty()) outcome.files.push_back(line);
    return outcome;
}

}  // namespace amrvk::bench
