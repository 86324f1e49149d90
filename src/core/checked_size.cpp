#include "core/checked_size.h"

#include <unistd.h>

#include <cstdlib>
#include <string>

#include "core/error.h"

namespace amrvk {

uint64_t checkedProduct(std::initializer_list<uint64_t> factors, std::string_view what) {
    uint64_t p = 1;
    bool overflow = false;
    for (uint64_t f : factors) {
        if (f == 0) return 0;
        overflow = __builtin_mul_overflow(p, f, &p) || overflow;
    }
    if (overflow) {
        std::string text;
        for (uint64_t f : factors) text += (text.empty() ? "" : " x ") + std::to_string(f);
        AMRVK_CHECK(false, what, ": ", text, " overflows 64 bits");
    }
    return p;
}

uint64_t checkedSum(uint64_t a, uint64_t b, std::string_view what) {
    uint64_t s = 0;
    AMRVK_CHECK(!__builtin_add_overflow(a, b, &s), what, ": ", a, " + ", b, " overflows 64 bits");
    return s;
}

int64_t checkedInRange(int64_t v, int64_t lo, int64_t hi, std::string_view what) {
    AMRVK_CHECK(v >= lo && v <= hi, what, ": ", v, " is outside [", lo, ", ", hi, "]");
    return v;
}

uint64_t checkedBoxCells(glm::i64vec3 lo, glm::i64vec3 hi, std::string_view what) {
    for (int a = 0; a < 3; ++a) {
        AMRVK_CHECK(lo[a] >= -kMaxIndex && lo[a] <= kMaxIndex && hi[a] >= -kMaxIndex && hi[a] <= kMaxIndex, what,
                    ": box (", lo.x, ",", lo.y, ",", lo.z, ")..(", hi.x, ",", hi.y, ",", hi.z,
                    ") has a corner outside [-", kMaxIndex, ", ", kMaxIndex, "]");
        AMRVK_CHECK(lo[a] <= hi[a], what, ": box (", lo.x, ",", lo.y, ",", lo.z, ")..(", hi.x, ",", hi.y, ",", hi.z,
                    ") is empty");
    }
    const glm::u64vec3 d(hi - lo + int64_t{1});
    return checkedProduct({d.x, d.y, d.z}, std::string(what) + ": box cells");
}

uint64_t memoryBudgetBytes() {
    static const uint64_t budget = [] {
        const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
        uint64_t b = pages > 0 && pageSize > 0 ? uint64_t(pages) * uint64_t(pageSize) : UINT64_MAX;
        if (const char* env = std::getenv("AMRVK_MEMORY_BUDGET")) {
            char* end = nullptr;
            const unsigned long long v = std::strtoull(env, &end, 10);
            if (end != env && *end == '\0' && v > 0) b = std::min<uint64_t>(b, v);
        }
        return b;
    }();
    return budget;
}

void checkAllocation(uint64_t bytes, std::string_view what) {
    const uint64_t budget = memoryBudgetBytes();
    AMRVK_CHECK(bytes <= budget, what, ": needs ", bytes, " bytes, more than the memory budget of ", budget,
                " bytes (physical memory, or AMRVK_MEMORY_BUDGET)");
}

}  // namespace amrvk
