#pragma once
// Runtime errors of amrvk: one exception type whose message is one line that names the file,
// value or limit at fault. main() prints it and exits non-zero.
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

namespace amrvk {

// Concatenates any streamable values into one string.
template <typename... Args>
std::string strCat(Args&&... args) {
    std::ostringstream os;
    (os << ... << std::forward<Args>(args));
    return os.str();
}

// The message is kept on one line: control bytes from the input (line breaks, NUL, escapes) are
// shown as \n, \r, \t or \xHH, so a hostile file can neither split nor cut an error; one over
// 1 KiB keeps its first 768 and last 256 bytes around the count of those left out.
std::string oneLineMessage(std::string_view message);

class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(oneLineMessage(message)) {}
};

// Throws amrvk::Error built from the streamed message when cond is false.
#define AMRVK_CHECK(cond, ...)                                            \
    do {                                                                  \
        if (!(cond)) throw ::amrvk::Error(::amrvk::strCat(__VA_ARGS__)); \
    } while (0)

}  // namespace amrvk
