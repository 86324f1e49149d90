#pragma once
// What every JSON reader checks of the text before it parses it. nlohmann's parser itself is
// iterative, but copying, dumping and comparing a value recurse once per nesting level, so a file
// nesting arrays 10^5 deep (a hostile session or TF) would overflow the stack after parsing.
#include <string>
#include <string_view>

namespace amrvk {

// Deeper than any amrvk document (a session nests 4 levels, a ParaView preset file 3).
inline constexpr int kMaxJsonDepth = 64;

// Throws "<where>: JSON nested deeper than 64 levels (at byte N)" when arrays and objects nest
// deeper than maxDepth outside strings. Linear in the text, no allocation.
void checkJsonDepth(std::string_view text, const std::string& where, int maxDepth = kMaxJsonDepth);

}  // namespace amrvk
