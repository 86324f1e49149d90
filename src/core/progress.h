#pragma once
// Progress for long work on stderr: "amrvk: <stage> ... 1.23 s". Printed when stderr is a
// terminal or AMRVK_PROGRESS=1, never into stdout (which may carry JSON).
#include <cstdint>
#include <string>

#include "core/stats.h"

namespace amrvk {

// Turns every progress line of this process off (MPI ranks other than 0: one bar per job).
void silenceProgress();

class ProgressStage {
public:
    explicit ProgressStage(std::string name);
    ~ProgressStage();
    ProgressStage(const ProgressStage&) = delete;
    ProgressStage& operator=(const ProgressStage&) = delete;

private:
    std::string mName;
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
