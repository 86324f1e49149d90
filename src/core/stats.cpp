#include "core/stats.h"

#include <sys/resource.h>

namespace amrvk {

uint64_t peakResidentBytes() {
    rusage usage{};
    if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
    return static_cast<uint64_t>(usage.ru_maxrss) * 1024u;
}

}  // namespace amrvk
