#include "cli/ranks.h"

#include "cli/options.h"
#include "core/error.h"
#include "core/mpi_launch.h"

#if AMRVK_MPI
#include "mpi/world.h"
#endif

namespace amrvk::cli {

int runOnRanks([[maybe_unused]] const std::string& command, const std::function<int(mpi::World*)>& body) {
    if (launchedJobSize() == 0) return body(nullptr);
#if AMRVK_MPI
    return mpi::runOnEveryRank(
        command, [&](mpi::World& world) { return body(&world); },
        [&](std::exception_ptr e) { return errorText(e, command); });
#else
    AMRVK_CHECK(launchedJobSize() <= 1, "started by an MPI launcher with ", launchedJobSize(),
                " processes, but this amrvk was built without MPI (install libopenmpi-dev and rebuild; docs/mpi.md)");
    return body(nullptr);
#endif
}

}  // namespace amrvk::cli
