#pragma once
// Locating test data: real AMR sets (AMRVK_DATA_DIR, default ../shared/data/amr beside the
// checkout) and a per-test scratch directory under the build tree.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace amrvk::test {

inline std::filesystem::path dataDir() {
    if (const char* env = std::getenv("AMRVK_DATA_DIR"); env && *env) return env;
    return AMRVK_DEFAULT_DATA_DIR;
}

// A fresh, empty directory build/test-artifacts/<suite>.<name>/ for the running test.
inline std::filesystem::path scratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::filesystem::path p = std::filesystem::path(AMRVK_BINARY_DIR) / "test-artifacts" /
                              (std::string(info->test_suite_name()) + "." + info->name());
    std::filesystem::remove_all(p);
    std::filesystem::create_directories(p);
    return p;
}

}  // namespace amrvk::test

// Skips the test with a clear message when a real data set is absent.
#define AMRVK_REQUIRE_DATA(relpath)                                                      \
    do {                                                                                 \
        if (!std::filesystem::exists(::amrvk::test::dataDir() / (relpath)))              \
            GTEST_SKIP() << "real AMR data not found: " << (::amrvk::test::dataDir() / (relpath)) \
                         << " (set AMRVK_DATA_DIR)";                                     \
    } while (0)
