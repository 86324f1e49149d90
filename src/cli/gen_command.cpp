// amrvk gen: synthetic AMR data sets written as ExaBrick .cells/.scalars (see amr/synthetic.h).
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>

#include "amr/synthetic.h"
#include "cli/args.h"
#include "cli/commands.h"
#include "core/error.h"

namespace amrvk::cli {

namespace {

const std::vector<OptionSpec> kGenSpecs = {
    {"cells", 1, "N", "target leaf-cell count, e.g. 1e6 (result within a factor 1.4; required)"},
    {"seed", 1, "S", "random seed, integer >= 0 (default 1); same seed = identical files"},
    {"output", 1, "BASE", "writes BASE.cells and BASE.scalars (-o BASE; required)"},
    {"block", 1, "B", "cells per block edge: 1, 2, 4, 8, 16 or 32 (default 8); 1 = one cell per leaf"},
    {"levels", 1, "L", "cell levels 0..L-1: domain 2^(L-1) blocks wide (default: by kind and N)"},
    {"field", 1, "NAME", "field name: writes BASE.NAME.scalars instead of BASE.scalars"},
};

const char* kGenUsage =
    "usage: amrvk gen <kind> --cells N [--seed S] -o BASE [--block B] [--levels L] [--field NAME]\n"
    "\n"
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
    "options:\n";

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
        std::snprintf(line, sizeof line, "%s: %.*s %3d%%", mLabel.c_str(), static_cast<int>(phase.size()),
                      phase.data(), static_cast<int>(fraction * 100.0));
        const size_t length = std::strlen(line);
        mWidth = std::max(mWidth, length);
        // On a terminal: rewrite in place, padded over a longer previous line.
        if (mTty) std::fprintf(stderr, "\r%-*s", static_cast<int>(mWidth), line);
        else std::fprintf(stderr, "%s\n", line);
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
    for (const std::string& a : argv) {
        if (a == "--help" || a == "-h") {
            std::fputs(kGenUsage, stdout);
            std::fputs(formatOptions(kGenSpecs).c_str(), stdout);
            return 0;
        }
    }
    Args args("gen", argv, kGenSpecs, 1, 1);
    amr::SyntheticParams params;
    params.kind = amr::parseSyntheticKind(args.positional()[0]);
    AMRVK_CHECK(args.has("cells"), "amrvk gen: --cells N is required (see amrvk gen --help)");
    AMRVK_CHECK(args.has("output"), "amrvk gen: -o BASE is required (see amrvk gen --help)");
    const int64_t cells = args.getInt("cells", 0);
    AMRVK_CHECK(cells >= 1, "--cells: ", cells, " must be at least 1");
    params.cells = static_cast<uint64_t>(cells);
    const int64_t seed = args.getInt("seed", 1);
    AMRVK_CHECK(seed >= 0, "--seed: ", seed, " must be >= 0");
    params.seed = static_cast<uint64_t>(seed);
    const int64_t block = args.getInt("block", 8);
    AMRVK_CHECK(block >= 1 && block <= 32 && (block & (block - 1)) == 0, "--block: ", block,
                " is not one of 1, 2, 4, 8, 16, 32");
    params.blockCells = static_cast<int>(block);
    const int64_t levels = args.getInt("levels", 0);
    AMRVK_CHECK(!args.has("levels") || (levels >= 1 && levels <= amr::kMaxLevel + 1), "--levels: ",
                levels, " is outside [1, ", amr::kMaxLevel + 1, "]");
    params.levels = static_cast<int>(levels);
    params.field = args.get("field");
    AMRVK_CHECK(params.field.find('/') == std::string::npos, "--field: '", params.field,
                "' must not contain '/'");
    const std::string base = args.get("output");
    AMRVK_CHECK(!base.empty(), "amrvk gen: -o BASE must not be empty");

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
    std::printf("amrvk gen %s: %llu cells, levels %d-%d (%d levels), %llu blocks of %d^3 cells%s, domain 2^%d, "
                "%.1f MB in %s.cells + %s%s, %.2f s\n",
                kindName.c_str(), static_cast<unsigned long long>(st.cells), st.minLevel, st.maxLevel,
                st.maxLevel - st.minLevel + 1, static_cast<unsigned long long>(st.cells / blockVolume),
                st.blockCells, reduced.c_str(), st.rootLevel, static_cast<double>(st.bytes) / 1e6, base.c_str(),
                base.c_str(), scalars.c_str(), st.seconds);
    if (!st.targetReached)
        std::fprintf(stderr,
                     "amrvk gen: warning: only %llu of %llu cells fit in a 2^%d domain (raise --levels)\n",
                     static_cast<unsigned long long>(st.cells),
                     static_cast<unsigned long long>(params.cells), st.rootLevel);
    return 0;
}

}  // namespace amrvk::cli
