#include "core/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace amrvk {

static bool gSilenced = false;

void silenceProgress() { gSilenced = true; }

static bool progressEnabled() {
    if (gSilenced) return false;
    const char* env = std::getenv("AMRVK_PROGRESS");
    if (env && *env) return std::strcmp(env, "0") != 0;
    return isatty(STDERR_FILENO) != 0;
}

std::string formatBytes(uint64_t bytes) {
    static const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    double v = double(bytes);
    int u = 0;
    while (v >= 1024.0 && u < 6) {
        v /= 1024.0;
        ++u;
    }
    char buf[48];
    if (u == 0)
        std::snprintf(buf, sizeof(buf), "%llu B", static_cast<unsigned long long>(bytes));
    else
        std::snprintf(buf, sizeof(buf), "%.1f %s", v, units[u]);
    return buf;
}

std::string memoryNote(uint64_t bytes, bool upperBound) {
    return (upperBound ? "at most " : "") + formatBytes(bytes) + " of memory";
}

ProgressStage::ProgressStage(std::string name) : mName(std::move(name)), mEnabled(progressEnabled()) {
    if (mEnabled) std::fprintf(stderr, "amrvk: %s ...\n", mName.c_str());
}

ProgressStage::ProgressStage(std::string name, const std::string& memory)
    : mName(std::move(name)), mEnabled(progressEnabled()) {
    if (mEnabled) std::fprintf(stderr, "amrvk: %s (%s) ...\n", mName.c_str(), memory.c_str());
}

ProgressStage::~ProgressStage() {
    if (!mEnabled) return;
    if (mResult.empty()) std::fprintf(stderr, "amrvk: %s done in %.2f s\n", mName.c_str(), mTimer.seconds());
    else std::fprintf(stderr, "amrvk: %s done in %.2f s (%s)\n", mName.c_str(), mTimer.seconds(), mResult.c_str());
}

ProgressBar::ProgressBar(std::string name, std::string unit)
    : mName(std::move(name)), mUnit(std::move(unit)), mEnabled(progressEnabled()) {}

void ProgressBar::update(uint64_t done, uint64_t total, const std::string& detail) {
    if (!mEnabled) return;
    const double now = mTimer.seconds();
    if (done != total && now - mLast < 0.1) return;
    mLast = now;
    constexpr int kWidth = 24;
    const int filled = total > 0 ? int(double(kWidth) * double(std::min(done, total)) / double(total)) : 0;
    const std::string text = detail.size() > 70 ? detail.substr(0, 70) : detail;
    // Remaining time at the rate so far (the work is taken as evenly spread over the units).
    char eta[32] = "";
    if (done > 0 && done < total)
        std::snprintf(eta, sizeof eta, "  eta %.0f s", now * double(total - done) / double(done));
    std::fprintf(stderr, "\r\033[Kamrvk: %s [%.*s%*s] %llu/%llu %s  %.1f s%s  %s", mName.c_str(), filled,
                 "########################", kWidth - filled, "", static_cast<unsigned long long>(done),
                 static_cast<unsigned long long>(total), mUnit.c_str(), now, eta, text.c_str());
    std::fflush(stderr);
    mDrawn = true;
}

void ProgressBar::finish() {
    if (mDrawn) std::fputc('\n', stderr);
    mDrawn = false;
}

}  // namespace amrvk
