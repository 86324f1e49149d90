#pragma once
// `mpirun -n N amrvk view` (docs/mpi.md, mpi/view_link.h): rank 0 runs the viewer with every rank
// tracing a share of each pass (sample-parallel), the others follow it headless.
#include <memory>

#include "scene/volume.h"
#include "viewer/viewer_app.h"

namespace amrvk::mpi {
class World;
}

namespace amrvk::cli {

// Every rank of the job calls it with the same options and its own read of the data. Returns the
// exit status; a rank's error is thrown (runOnRanks reports it once).
int viewOnRanks(mpi::World& world, viewer::ViewerOptions options, std::shared_ptr<const scene::Volume> volume);

}  // namespace amrvk::cli
