#pragma once
// How render and bench run: alone, or on every rank of an MPI job when an MPI launcher started the
// process (docs/mpi.md). Without MPI in the build, a launch with several processes is one error.
#include <functional>
#include <string>

namespace amrvk::mpi {
class World;
}

namespace amrvk::cli {

// body(world): the job under a launcher (errors agreed on and reported once, by rank 0), nullptr
// alone.
int runOnRanks(const std::string& command, const std::function<int(mpi::World*)>& body);

}  // namespace amrvk::cli
