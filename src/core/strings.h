#pragma once
// Small string helpers for messages and metadata attributes.
#include <cctype>
#include <charconv>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "core/error.h"

namespace amrvk {

// Shortest text that reads back as exactly `v` (e.g. "0.1", "1e-05").
inline std::string formatDouble(double v) {
    char buf[32];
    auto [end, ec] = std::to_chars(buf, buf + sizeof(buf), v);
    return ec == std::errc() ? std::string(buf, end) : strCat(v);
}

// `s` for a message: at most `max` bytes of it, the rest counted ("1234567... (60000 bytes)").
inline std::string elide(std::string_view s, size_t max = 40) {
    if (s.size() <= max) return std::string(s);
    return strCat(s.substr(0, max), "... (", s.size(), " bytes)");
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

// One row of an enum's name table (parseNamed, nameOf): the spelling on the command line and in files.
template <typename E>
struct Named {
    const char* name;
    E value;
};

// The value named `name`; else an error naming the option, the value and the choices.
template <typename E, size_t N>
E parseNamed(const Named<E> (&table)[N], std::string_view name, const char* option) {
    std::string choices;
    for (const Named<E>& n : table) {
        if (name == n.name) return n.value;
        choices += choices.empty() ? n.name : std::string("|") + n.name;
    }
    throw Error(strCat(option, " '", name, "': expected ", choices));
}

template <typename E, size_t N>
const char* nameOf(const Named<E> (&table)[N], E value) {
    for (const Named<E>& n : table)
        if (n.value == value) return n.name;
    return "?";
}

// `s` in ASCII lower case.
inline std::string toLower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

// `s` without leading and trailing spaces, tabs and carriage returns.
inline std::string trim(std::string_view s) {
    const size_t first = s.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) return {};
    return std::string(s.substr(first, s.find_last_not_of(" \t\r") - first + 1));
}

// The non-empty items of a `sep`-separated list ("spiky,,foggy" -> spiky, foggy), untrimmed.
inline std::vector<std::string> splitList(std::string_view text, char sep = ',') {
    std::vector<std::string> out;
    size_t pos = 0;
    while (pos <= text.size()) {
        size_t end = text.find(sep, pos);
        if (end == std::string_view::npos) end = text.size();
        if (end > pos) out.emplace_back(text.substr(pos, end - pos));
        pos = end + 1;
    }
    return out;
}

// The "key = value" lines of a text (both sides trimmed; lines without '=' skipped), in order;
// hashComments: text after '#' on a line is ignored (Enzo parameter files; RAMSES info files keep it).
inline std::vector<std::pair<std::string, std::string>> keyValueLines(std::string_view text, bool hashComments) {
    std::vector<std::pair<std::string, std::string>> out;
    size_t pos = 0;
    while (pos < text.size()) {
        size_t end = text.find('\n', pos);
        if (end == std::string_view::npos) end = text.size();
        std::string_view line = text.substr(pos, end - pos);
        pos = end + 1;
        if (hashComments) line = line.substr(0, line.find('#'));
        const size_t eq = line.find('=');
        if (eq == std::string_view::npos) continue;
        out.emplace_back(trim(line.substr(0, eq)), trim(line.substr(eq + 1)));
    }
    return out;
}

}  // namespace amrvk
