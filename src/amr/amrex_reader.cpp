// PLACEHOLDER: replaced by the real reader in this session.
#include "amr/readers.h"
#include "core/error.h"
namespace amrvk::amr {
Model readAmrex(const std::filesystem::path& path, const ReadOptions&) {
    AMRVK_CHECK(false, path.string(), ": amrex reader not built yet");
    return {};
}
}  // namespace amrvk::amr
