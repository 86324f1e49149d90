#include "core/json_text.h"

#include "core/error.h"

namespace amrvk {

void checkJsonDepth(std::string_view text, const std::string& where, int maxDepth) {
    int depth = 0;
    bool inString = false, escaped = false;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (inString) {
            if (escaped) escaped = false;
            else if (c == '\\') escaped = true;
            else if (c == '"') inString = false;
            continue;
        }
        if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            AMRVK_CHECK(++depth <= maxDepth, where, ": JSON nested deeper than ", maxDepth, " levels (at byte ", i, ")");
        } else if (c == ']' || c == '}') {
            --depth;  // unbalanced text is the parser's error to report
        }
    }
}

}  // namespace amrvk
