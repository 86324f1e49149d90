#pragma once
// Errors from Python name Python's keywords, not the command line's options: amrvk's checks are
// shared by every front end and word their one-line messages for the CLI ("--density-scale -1
// must be finite and >= 0", "use --nan drop"); the module rewrites the option names it binds into
// its keywords ("density_scale -1 must be ...", "use nan='drop'") before raising.
#include <string>
#include <string_view>

namespace amrvk::python {

// `message` with every CLI option the module has a keyword for replaced by that keyword. Only
// whole option tokens are replaced ("--g" but not "--gpu-timeout" or "a--g"); the rest is kept.
std::string keywordMessage(std::string_view message);

}  // namespace amrvk::python
