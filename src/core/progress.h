#pragma once
// Progress for long work on stderr: "amrvk: <stage> ... 1.23 s". Printed when stderr is a
// terminal or AMRVK_PROGRESS=1, never into stdout (which may carry JSON).
#include <cstdint>
#include <string>

#include "core/stats.h"

namespace amrvk {

// "about 1.2 GiB of memory" / "at most ...": what a build states before it starts.
std::string memoryNote(uint64_t bytes, bool upperBound = false);

// Turns every progress line of this process off (MPI ranks other than 0: one bar per job).
void silenceProgress();

// "1.5 GiB": binary units, one decimal (bytes below 1 KiB exactly).
std::string formatBytes(uint64_t bytes);

class ProgressStage {
public:
    explicit ProgressStage(std::string name);
    // A build that states the memory it is about to take first: "amrvk: NAME (MEMORY) ...", e.g.
    // memory = "at most 1.2 GiB" (see memoryNote()).
    ProgressStage(std::string name, const std::string& memory);
    ~ProgressStage();
    // Said after the time when the stage ends: "amrvk: NAME done in 1.23 s (RESULT)", e.g. the
    // memory a build took where it could not be known before.
    void setResult(std::string result) { mResult = std::move(result); }
    ProgressStage(const ProgressStage&) = delete;
    ProgressStage& operator=(const ProgressStage&) = delete;

private:
    std::string mName, mResult;
    Timer mTimer;
    bool mEnabled;
};

// A one-line bar on stderr, redrawn at most every 0.1 s (and at the end):
// "amrvk: NAME [####    ] done/total UNIT  seconds  eta seconds  detail" (the estimated time left
// at the rate since the bar was made). Silent when progress is disabled.
class ProgressBar {
public:
    ProgressBar(std::string name, std::string unit);
    void update(uint64_t done, uint64_t total, const std::string& detail = {});
    // Ends the line (once) if anything was drawn.
    void finish();

private:
    std::string mName, mUnit;
    bool mEnabled, mDrawn = false;
    Timer mTimer;
    double mLast = -1;
};

}  // namespace amrvk
