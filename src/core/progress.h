#pragma once
// Progress for long work on stderr: "amrvk: <stage> ... 1.23 s". Printed when stderr is a
// terminal or AMRVK_PROGRESS=1, never into stdout (which may carry JSON).
#include <string>

#include "core/stats.h"

namespace amrvk {

bool progressEnabled();

class ProgressStage {
public:
    explicit ProgressStage(std::string name);
    ~ProgressStage();
    ProgressStage(const ProgressStage&) = delete;
    ProgressStage& operator=(const ProgressStage&) = delete;
    double seconds() const { return mTimer.seconds(); }

private:
    std::string mName;
    Timer mTimer;
    bool mEnabled;
};

}  // namespace amrvk
