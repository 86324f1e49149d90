// amrvk gen: synthetic AMR data sets written as ExaBrick .cells/.scalars (see amr/synthetic.h).
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "amr/synthetic.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "core/error.h"

namespace amrvk::cli {

namespace {

const char* kGenUsage =
    "Writes deterministic synthetic AMR (leaf cells, level 0 = finest) as BASE.cells\n"
    "(16-byte int32 x,y,z,level records) and BASE.scalars (float32, same order), streamed\n"
    "depth-first with bounded memory; nothing is left behind if the run fails.\n"
    "\n"
    "The data are block-structured like FLASH or AMReX output: an octree is refined where the\n"
    "field varies and every leaf is one full aligned block of B^3 same-level cells (--block 1:\n"
    "every leaf is a single cell). Small targets use a smaller B so that N >= 64 B^3\n"
    "(teapot: 512 B^3); the summary line reports the B used.\n"
    "\n"
    "kinds:\n"
    "  cloud    turbulent cloud: log-normal density from hashed fractal value noise,\n"
    "           refined where the density varies (structure at many scales)\n"
    "  shells   nested spherical shells with sharp radial bands, refined at the boundaries\n"
    "  teapot   'teapot in a stadium': a tiny torus and ball refined to the finest level\n"
    "           inside a coarse domain at least 2^20 cells wide (large level jumps)\n"
    "\n"
    "--time T makes one output of a time series: the field evolves smoothly and periodically\n"
    "with T (period 1; T = 0 is the field without --time): the cloud drifts on a small circle\n"
    "and its contrast swings by 25%, the shells breathe by 15%, the teapot's torus turns about z.\n"
    "For example, for i in 0 1 2; do amrvk gen cloud --cells 2e4 --time 0.$i -o s_$i; done\n"
    "makes three outputs that `amrvk render 's_*.cells' -o movie.mp4` renders (docs/movies.md).";

// Progress on stderr: at most 10 lines/s on a terminal (rewritten in place), once a second
// otherwise, and only after the first second unless stderr is a terminal.
class ProgressPrinter {
public:
    explicit ProgressPrinter(std::string label)
        : mLabel(std::move(label)), mTty(::isatty(::fileno(stderr)) != 0), mStart(Clock::now()) {}
    ~ProgressPrinter() { finish(); }
    ProgressPrinter(const ProgressPrinter&) = delete;
    ProgressPrinter& operator=(const ProgressPrinter&) = delete;

    void update(std::string_view phase, double fraction) {
        const auto now = Clock::now();
        const double elapsed = std::chrono::duration<double>(now - mStart).count();
        const double since = std::chrono::duration<double>(now - mLast).count();
        if (!mTty && elapsed < 1.0) return;
        if (mPrinted && since < (mTty ? 0.1 : 1.0)) return;
        mLast = now;
        mPrinted = true;
        char line[256];
        std::snprintf(line, sizeof line, "%s: %.*s %3d%%", mLabel.c_str(), static_cast<int>(phase.size()), phase.data(),
                      static_cast<int>(fraction * 100.0));
        const size_t length = std::strlen(line);
        mWidth = std::max(mWidth, length);
        // On a terminal: rewrite in place, padded over a longer previous line.
        if (mTty)
            std::fprintf(stderr, "\r%-*s", static_cast<int>(mWidth), line);
        else
            std::fprintf(stderr, "%s\n", line);
        std::fflush(stderr);
    }

    // Erases the in-place line so that the next output starts on a clean line.
    void finish() {
        if (mTty && mPrinted) std::fprintf(stderr, "\r%*s\r", static_cast<int>(mWidth), "");
        mPrinted = false;
        mWidth = 0;
    }

private:
    using Clock = std::chrono::steady_clock;
    std::string mLabel;
    bool mTty;
    Clock::time_point mStart, mLast{};
    bool mPrinted = false;
    size_t mWidth = 0;
};

}  // namespace

int runGen(const std::vector<std::string>& argv) {
    CLI::App app(kGenUsage, "amrvk gen");
    setUpCommand(app);
    std::string kind, base;
    double cells = 0;
    int64_t seed = 1, block = 8, levels = 0;
    amr::SyntheticParams params;
    app.add_option("kind", kind, "cloud, shells or teapot")->required();
    app.add_option("--cells", cells, "target leaf-cell count, e.g. 1e6 (the result is within a factor 1.4)")
        ->required()
        ->check(interval(1, 1e11))  // amr::generateSynthetic's own limit
        ->type_name("N");
    app.add_option("--seed", seed, "random seed; the same seed gives identical files")
        ->check(interval(0, 4.6e18))
        ->capture_default_str()
        ->type_name("S");
    app.add_option("-o,--output", base, "writes BASE.cells and BASE.scalars")->required()->type_name("BASE");
    app.add_option("--block", block, "cells per block edge (1 = one cell per leaf)")
        ->check(CLI::IsMember({1, 2, 4, 8, 16, 32}))
        ->capture_default_str()
        ->type_name("B");
    app.add_option("--levels", levels, "cell levels 0..L-1: the domain is 2^(L-1) blocks wide (default: by kind and N)")
        ->check(interval(1, amr::kMaxLevel + 1))
        ->type_name("L");
    app.add_option("--field", params.field, "field name: writes BASE.NAME.scalars instead of BASE.scalars")
        ->type_name("NAME");
    app.add_option("--time", params.time,
                   "time of the evolving field (period 1): consecutive times make a time series")
        ->check(interval(-1e6, 1e6))
        ->capture_default_str()
        ->type_name("T");
    if (!parseCommandLine(app, argv)) return 0;
    params.kind = amr::parseSyntheticKind(kind);
    AMRVK_CHECK(cells == std::floor(cells), "--cells: ", cells, " is not a whole number");
    params.cells = static_cast<uint64_t>(cells);
    params.seed = static_cast<uint64_t>(seed);
    params.blockCells = static_cast<int>(block);
    params.levels = static_cast<int>(levels);
    AMRVK_CHECK(params.field.find('/') == std::string::npos, "--field: '", params.field, "' must not contain '/'");
    AMRVK_CHECK(!base.empty(), "amrvk gen: -o BASE must not be empty");
    checkOutputs({{"-o", base + ".cells"}, {"-o", base + (params.field.empty() ? "" : "." + params.field) + ".scalars"}}, {});

    const std::string kindName(amr::syntheticKindName(params.kind));
    ProgressPrinter printer("amrvk gen " + kindName);
    params.progress = [&](std::string_view phase, double fraction) { printer.update(phase, fraction); };
    amr::SyntheticStats st = amr::generateSynthetic(params, base);
    params.progress = nullptr;
    printer.finish();

    const std::string scalars = params.field.empty() ? ".scalars" : "." + params.field + ".scalars";
    const uint64_t blockVolume = static_cast<uint64_t>(st.blockCells) * static_cast<uint64_t>(st.blockCells) *
                                 static_cast<uint64_t>(st.blockCells);
    const std::string reduced = st.blockCells == params.blockCells
                                    ? std::string()
                                    : strCat(" (reduced from --block ", params.blockCells, ": too few blocks for N)");
    std::printf(
        "amrvk gen %s: %llu cells, levels %d-%d (%d levels), %llu blocks of %d^3 cells%s, domain "
        "2^%d, "
        "%.1f MB in %s.cells + %s%s, %.2f s\n",
        kindName.c_str(), static_cast<unsigned long long>(st.cells), st.minLevel, st.maxLevel,
        st.maxLevel - st.minLevel + 1, static_cast<unsigned long long>(st.cells / blockVolume), st.blockCells,
        reduced.c_str(), st.rootLevel, static_cast<double>(st.bytes) / 1e6, oneLineMessage(base).c_str(),
        oneLineMessage(base).c_str(), oneLineMessage(scalars).c_str(), st.seconds);
    if (!st.targetReached)
        std::fprintf(stderr, "amrvk gen: warning: only %llu of %llu cells fit in a 2^%d domain (raise --levels)\n",
                     static_cast<unsigned long long>(st.cells), static_cast<unsigned long long>(params.cells),
                     st.rootLevel);
    return 0;
}

}  // namespace amrvk::cli
