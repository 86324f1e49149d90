#pragma once
// Shared by the libFuzzer targets (docs/fuzzing.md). Each target turns the fuzz input into one or
// more files in a scratch directory of that input's (Scratch), calls a reader, and accepts
// exactly two outcomes: success, or an amrvk::Error (a clean one-line message). Any other
// exception type aborts, so libFuzzer records it as a crash like a sanitizer report, a hang
// (-timeout) or an out-of-memory (-rss_limit_mb / -malloc_limit_mb).
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <typeinfo>
#include <vector>

#include "core/error.h"

namespace amrvk::fuzz {

// This process's scratch directory, under $TMPDIR (or /tmp), made on first use; its destructor
// (a static's, run by exit() as libFuzzer ends after -runs, -max_total_time or a replay) removes it.
class ProcessScratch {
public:
    ProcessScratch() {
        const char* t = std::getenv("TMPDIR");
        std::string tmpl = std::string(t && *t ? t : "/tmp") + "/amrvk-fuzz-XXXXXX";
        if (!mkdtemp(tmpl.data())) {
            std::perror("amrvk fuzz: mkdtemp");
            std::abort();
        }
        mDir = tmpl;
    }
    ~ProcessScratch() {
        std::error_code ec;
        std::filesystem::remove_all(mDir, ec);
    }
    const std::filesystem::path& path() const { return mDir; }
    // Removes everything inside.
    void empty() const {
        std::error_code ec;
        for (const auto& e : std::filesystem::directory_iterator(mDir, ec)) std::filesystem::remove_all(e.path(), ec);
    }

private:
    std::filesystem::path mDir;
};

// The scratch directory of one input: the process's, empty when the input comes and emptied when
// it is done (also when the reader threw). The directory was left by every run before: an atexit
// handler registered before the path's static was constructed ran after its destructor and removed
// nothing. A process that libFuzzer ends with _Exit (a crash, a sanitizer report, -timeout,
// -rss_limit_mb, -malloc_limit_mb) runs no destructor and leaves it, with that one input's files:
// tools/run.sh fuzzes under a TMPDIR of its own, removes what such findings left, and fails when a
// run without findings left any (docs/fuzzing.md). (A new directory per input was measured 10x
// slower, and libFuzzer then ran every seed twice on start.)
class Scratch {
public:
    Scratch() : mProcess(process()) { mProcess.empty(); }
    ~Scratch() { mProcess.empty(); }
    Scratch(const Scratch&) = delete;
    Scratch& operator=(const Scratch&) = delete;
    const std::filesystem::path& path() const { return mProcess.path(); }

private:
    static const ProcessScratch& process() {
        static const ProcessScratch dir;
        return dir;
    }
    const ProcessScratch& mProcess;
};

inline void writeFile(const std::filesystem::path& p, std::string_view bytes) {
    std::filesystem::create_directories(p.parent_path());
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) {
        std::fprintf(stderr, "amrvk fuzz: cannot write %s\n", p.c_str());
        std::abort();
    }
}

// The separator between the files of a multi-file input (also in the targets' dictionaries).
inline constexpr std::string_view kSeparator = "\n--next-file--\n";

// Splits the input at kSeparator into at most `maxParts` parts (the last part keeps any further
// separators); missing parts are empty.
inline std::vector<std::string_view> splitParts(const uint8_t* data, size_t size, size_t maxParts) {
    std::string_view rest(reinterpret_cast<const char*>(data), size);
    std::vector<std::string_view> parts;
    while (parts.size() + 1 < maxParts) {
        const size_t at = rest.find(kSeparator);
        if (at == std::string_view::npos) break;
        parts.push_back(rest.substr(0, at));
        rest.remove_prefix(at + kSeparator.size());
    }
    parts.push_back(rest);
    parts.resize(maxParts);
    return parts;
}

// Joins files into one input (for the seed generator).
inline std::string joinParts(const std::vector<std::string>& parts) {
    std::string out;
    for (size_t i = 0; i < parts.size(); ++i) {
        if (i) out += kSeparator;
        out += parts[i];
    }
    return out;
}

// Runs f; an amrvk::Error is the expected failure, anything else is a finding (abort).
// AMRVK_FUZZ_VERBOSE=1 prints each outcome (for running a target on single files).
template <typename F>
void expectOnlyAmrvkErrors(const char* target, F&& f) {
    static const bool verbose = [] {
        const char* v = std::getenv("AMRVK_FUZZ_VERBOSE");
        return v && *v && *v != '0';
    }();
    try {
        f();
        if (verbose) std::fprintf(stderr, "==amrvk-fuzz== %s: read\n", target);
    } catch (const amrvk::Error& e) {
        if (verbose) std::fprintf(stderr, "==amrvk-fuzz== %s: amrvk::Error: %s\n", target, e.what());
        // A clean, one-line error is the correct outcome for bad input; a message spanning lines
        // (the CLI's contract, tests/cli/bad_input.sh) is a finding too (findings.md F3).
        // AMRVK_FUZZ_ONE_LINE=0 turns that check off.
        static const bool oneLine = [] {
            const char* v = std::getenv("AMRVK_FUZZ_ONE_LINE");
            return !(v && *v == '0');
        }();
        const std::string_view msg = e.what();
        if (oneLine && (msg.find('\n') != std::string_view::npos || msg.empty())) {
            std::fprintf(stderr, "==amrvk-fuzz== %s: amrvk::Error message is not one line: %s\n",
                         target, e.what());
            std::abort();
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "==amrvk-fuzz== %s: uncaught %s: %s\n", target, typeid(e).name(), e.what());
        std::abort();
    } catch (...) {
        std::fprintf(stderr, "==amrvk-fuzz== %s: uncaught non-std exception\n", target);
        std::abort();
    }
}

}  // namespace amrvk::fuzz
