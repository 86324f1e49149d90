#pragma once
// Small string helpers for messages and metadata attributes.
#include <charconv>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "core/error.h"

namespace amrvk {

// Shortest text that reads back as exactly `v` (e.g. "0.1", "1e-05").
inline std::string formatDouble(double v) {
    char buf[32];
    auto [end, ec] = std::to_chars(buf, buf + sizeof(buf), v);
    return ec == std::errc() ? std::string(buf, end) : strCat(v);
}

// The streamed values joined by `separator`: join({1, 2, 3}) == "1 2 3".
template <typename T>
std::string join(const std::vector<T>& values, std::string_view separator = " ") {
    std::string out;
    for (const T& v : values) {
        if (!out.empty()) out += separator;
        out += strCat(v);
    }
    return out;
}

// `s` without leading and trailing spaces, tabs and carriage returns.
inline std::string trim(std::string_view s) {
    const size_t first = s.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) return {};
    return std::string(s.substr(first, s.find_last_not_of(" \t\r") - first + 1));
}

}  // namespace amrvk
