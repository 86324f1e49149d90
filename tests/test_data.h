#pragma once
// Locating test data: real AMR sets (AMRVK_DATA_DIR, default ../shared/data/amr beside the
// checkout) and a per-test scratch directory under the build tree.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <sstream>
#include <string>

#include "core/error.h"

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

// The message of the amrvk::Error that f() throws; a test failure (and "") when it throws none.
inline std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    ADD_FAILURE() << "expected an amrvk::Error";
    return {};
}

inline void expectContains(const std::string& text, const std::string& part) {
    EXPECT_NE(text.find(part), std::string::npos) << "'" << part << "' not in: " << text;
}

// Expects f() to throw amrvk::Error with a one-line message holding every fragment.
inline void expectError(const std::function<void()>& f, std::initializer_list<std::string> fragments) {
    const std::string msg = errorOf(f);
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    for (const std::string& part : fragments) expectContains(msg, part);
}

inline std::string readAll(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream os;
    os << in.rdbuf();
    return os.str();
}

inline void writeAll(const std::filesystem::path& p, const std::string& bytes) {
    std::ofstream out(p, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace amrvk::test

// Skips the test with a clear message when a real data set is absent.
#define AMRVK_REQUIRE_DATA(relpath)                                                      \
    do {                                                                                 \
        if (!std::filesystem::exists(::amrvk::test::dataDir() / (relpath)))              \
            GTEST_SKIP() << "real AMR data not found: " << (::amrvk::test::dataDir() / (relpath)) \
                         << " (set AMRVK_DATA_DIR)";                                     \
    } while (0)
