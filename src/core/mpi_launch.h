#pragma once
// Whether an MPI launcher (mpirun, mpiexec, srun) started this process, read from the environment
// it sets (Open MPI's OMPI_COMM_WORLD_SIZE, PMI's PMI_SIZE): known with or without MPI in the build, before MPI_Init.
#include <cstdlib>

namespace amrvk {

// The job size the launcher gave; 0 when no launcher started this process.
inline int launchedJobSize() {
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {
        const char* v = std::getenv(name);
        if (v && std::atoi(v) > 0) return std::atoi(v);
    }
    return 0;
}

// This process's rank in that job (0 when no launcher started it).
inline int launchedRank() {
    for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMI_RANK"}) {
        const char* v = std::getenv(name);
        if (v && *v) return std::atoi(v);
    }
    return 0;
}

}  // namespace amrvk
