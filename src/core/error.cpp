#include "core/error.h"

namespace amrvk {

std::string oneLineMessage(std::string_view message) {
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out;
    out.reserve(message.size());
    for (const char ch : message) {
        const auto c = static_cast<unsigned char>(ch);
        if (c >= 0x20 && c != 0x7f) out += ch;
        else if (c == '\n') out += "\\n";
        else if (c == '\r') out += "\\r";
        else if (c == '\t') out += "\\t";
        else out += {'\\', 'x', kHex[c >> 4], kHex[c & 15]};
    }
    return out;
}

}  // namespace amrvk
