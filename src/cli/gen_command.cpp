// PLACEHOLDER: replaced by the synthetic generator in this session.
#include "cli/commands.h"
#include "core/error.h"
namespace amrvk::cli {
int runGen(const std::vector<std::string>&) {
    AMRVK_CHECK(false, "amrvk gen: not built yet");
    return 1;
}
}  // namespace amrvk::cli
