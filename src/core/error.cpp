#include "core/error.h"

namespace amrvk {

std::string oneLineMessage(std::string_view message) {
    static constexpr char kHex[] = "0123456789abcdef";
    // Bounded too: a message that quotes a huge name or value keeps its start and its end.
    constexpr size_t kMaxBytes = 1024, kTail = 256;
    std::string cut;
    if (message.size() > kMaxBytes) {
        cut = strCat(message.substr(0, kMaxBytes - kTail), " [... ", message.size() - kMaxBytes, " bytes ...] ",
                     message.substr(message.size() - kTail));
        message = cut;
    }
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
