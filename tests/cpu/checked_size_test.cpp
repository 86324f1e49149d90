// core/checked_size: exact overflow detection, box limits and the allocation budget, against
// values worked out by hand at the edges.
#include <gtest/gtest.h>

#include "core/checked_size.h"
#include "test_data.h"

using namespace amrvk;
using namespace amrvk::test;

TEST(CheckedSize, ProductIsExactUpToTheLastRepresentableValue) {
    EXPECT_EQ(checkedProduct({}, "empty"), 1u);
    EXPECT_EQ(checkedProduct({uint64_t{1} << 32, (uint64_t{1} << 32) - 1}, "x"), UINT64_MAX - (uint64_t{1} << 32) + 1);
    EXPECT_EQ(checkedProduct({3, 5, 7, 0, UINT64_MAX}, "x"), 0u) << "a zero factor";
    expectError([] { checkedProduct({uint64_t{1} << 32, uint64_t{1} << 32}, "grid"); },
                {"grid: 4294967296 x 4294967296 overflows 64 bits"});
    // 2^21 * 2^21 * 2^22 = 2^64 wraps to exactly 0 without the check.
    expectError([] { checkedProduct({1u << 21, 1u << 21, 1u << 22}, "brick"); }, {"overflows 64 bits"});
    EXPECT_EQ(checkedProduct({UINT64_MAX, 2, 0}, "x"), 0u) << "the exact product, not a partial one";
}

TEST(CheckedSize, SumAndRange) {
    EXPECT_EQ(checkedSum(UINT64_MAX - 1, 1, "s"), UINT64_MAX);
    expectError([] { checkedSum(UINT64_MAX, 1, "cells"); }, {"cells: 18446744073709551615 + 1 overflows 64 bits"});
    EXPECT_EQ(checkedInRange(-5, -5, 5, "v"), -5);
    expectError([] { checkedInRange(6, -5, 5, "ngrow"); }, {"ngrow: 6 is outside [-5, 5]"});
}

TEST(CheckedSize, BoxCornersStayWithinTheIndexLimit) {
    EXPECT_EQ(checkedBoxCells({0, 0, 0}, {3, 3, 0}, "b"), 16u);
    EXPECT_EQ(checkedBoxCells({-kMaxIndex, 0, 0}, {kMaxIndex, 0, 0}, "b"), uint64_t(2 * kMaxIndex + 1));
    expectError([] { checkedBoxCells({-kMaxIndex - 1, 0, 0}, {0, 0, 0}, "Cell_H"); },
                {"Cell_H: box (-1073741824,0,0)..(0,0,0) has a corner outside [-1073741823, 1073741823]"});
    expectError([] { checkedBoxCells({0, 0, 0}, {0, int64_t{INT32_MAX}, 0}, "b"); }, {"corner outside"});
    expectError([] { checkedBoxCells({0, 5, 0}, {0, 4, 0}, "b"); }, {"b: box (0,5,0)..(0,4,0) is empty"});
    // Every corner legal, the extents 2^31 - 1 each: (2^31 - 1)^3 > 2^64.
    expectError([] { checkedBoxCells(glm::i64vec3(-kMaxIndex), glm::i64vec3(kMaxIndex), "b"); },
                {"b: box cells: 2147483647 x 2147483647 x 2147483647 overflows 64 bits"});
}

TEST(CheckedSize, AllocationBeyondTheBudgetIsRefusedBeforeItHappens) {
    const uint64_t budget = memoryBudgetBytes();
    EXPECT_GT(budget, uint64_t{1} << 26) << "at least 64 MiB on any machine that runs the tests";
    checkAllocation(budget, "exactly the budget");
    expectError([&] { checkAllocation(budget + 1, "--size 16384x16384"); },
                {"--size 16384x16384: needs", "more than the memory budget of"});
}
