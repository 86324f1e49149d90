#pragma once
// Checked arithmetic for every size, count and coordinate read from a file or an option: a
// product, sum or narrowing that would wrap throws a one-line amrvk::Error naming `what` and the
// limit instead. Overflow is detected exactly (compiler builtins), never after the fact.
#include <cstdint>
#include <initializer_list>
#include <string_view>

#include <glm/glm.hpp>

namespace amrvk {

// Integer coordinates read from files (box corners, ghost widths, offsets) lie in
// [-kMaxIndex, kMaxIndex]: then a box's extent hi - lo + 1 and any difference of two corners fit
// in int32, and a corner times a level's cell width (<= 2^30) fits in int64.
constexpr int64_t kMaxIndex = (int64_t{1} << 30) - 1;

// The exact product of `factors` (0 if any is 0); throws "WHAT: a x b x ... overflows 64 bits" if
// it does not fit.
uint64_t checkedProduct(std::initializer_list<uint64_t> factors, std::string_view what);

// a + b; throws "WHAT: a + b overflows 64 bits" if it does not fit.
uint64_t checkedSum(uint64_t a, uint64_t b, std::string_view what);

// `v` if it lies in [lo, hi], else throws "WHAT: V is outside [LO, HI]".
int64_t checkedInRange(int64_t v, int64_t lo, int64_t hi, std::string_view what);

// An inclusive integer box lo..hi read from a file: every corner in [-kMaxIndex, kMaxIndex] and
// lo <= hi on every axis, else throws naming `what`. Returns its cell count, or throws if that
// overflows 64 bits.
uint64_t checkedBoxCells(glm::i64vec3 lo, glm::i64vec3 hi, std::string_view what);

// Bytes this machine can give one allocation: its physical memory, or AMRVK_MEMORY_BUDGET (bytes)
// where set lower. Read once.
uint64_t memoryBudgetBytes();

// Throws "WHAT: needs N bytes, more than the memory budget of M bytes (...)" when `bytes` exceeds
// memoryBudgetBytes(). Call before allocating anything whose size comes from input.
void checkAllocation(uint64_t bytes, std::string_view what);

}  // namespace amrvk
