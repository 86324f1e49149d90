#include "core/progress.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace amrvk {

bool progressEnabled() {
    const char* env = std::getenv("AMRVK_PROGRESS");
    if (env && *env) return std::strcmp(env, "0") != 0;
    return isatty(STDERR_FILENO) != 0;
}

ProgressStage::ProgressStage(std::string name) : mName(std::move(name)), mEnabled(progressEnabled()) {
    if (mEnabled) std::fprintf(stderr, "amrvk: %s ...\n", mName.c_str());
}

ProgressStage::~ProgressStage() {
    if (mEnabled) std::fprintf(stderr, "amrvk: %s done in %.2f s\n", mName.c_str(), mTimer.seconds());
}

}  // namespace amrvk
