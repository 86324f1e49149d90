// PLACEHOLDER: replaced by the real reader in this session.
#include "amr/readers.h"
#include "core/error.h"
namespace amrvk::amr {
Model readEnzo(const std::filesystem::path& path, const ReadOptions&) {
    AMRVK_CHECK(false, path.string(), ": enzo reader not built yet");
    return {};
}
}  // namespace amrvk::amr
