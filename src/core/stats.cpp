#include "core/stats.h"

#include <sys/resource.h>
#include <unistd.h>

#include <fstream>

namespace amrvk {

uint64_t peakResidentBytes() {
    rusage usage{};
    if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
    return static_cast<uint64_t>(usage.ru_maxrss) * 1024u;
}

uint64_t currentResidentBytes() {
    std::ifstream in("/proc/self/statm");
    uint64_t pages = 0, resident = 0;
    if (!(in >> pages >> resident)) return 0;
    return resident * static_cast<uint64_t>(sysconf(_SC_PAGESIZE));
}

}  // namespace amrvk
