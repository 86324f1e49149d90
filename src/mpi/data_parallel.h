#pragma once
// Data-parallel rendering (mpirun -n N amrvk render --distribute data; docs/mpi.md): the data set
// is cut into N boxes of about equal cell counts (amr/space_partition.h); each rank reads only the
// cells of its box plus the halo the tent reconstruction needs at its faces, builds its own
// structures and majorants, and traces every path through its box only. The ranks hold the same
// path state and agree after each tracking stage by reductions (shaders/shared/data_parallel_gpu.h):
// the nearest of their first collisions, the product of their shadow transmittances. Unbiased for
// ae, ss and ms; the image equals the single-process one statistically.
#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>

#include "amr/space_partition.h"
#include "mpi/world.h"
#include "picture/picture.h"
#include "session/picture_description.h"

namespace amrvk::mpi {

struct DataPart {
    amr::CellCensus census;         // the whole data set (every rank computes the same)
    std::vector<amr::Box3l> owned;  // the box each rank owns (voxel space), in rank order
    uint64_t ownedCells = 0;        // cells whose lower corner lies in this rank's box (the rest: halo)
    double censusSeconds = 0, readSeconds = 0;
    std::shared_ptr<const scene::Volume> volume;  // the region's cells, in the whole data's frame
};

// This rank's part of the data `d` names: a census of the whole (two streamed passes), the
// partition, then the cells of its region, as a volume in the whole's frame (scene::VolumeFrame:
// bounds, which session::resolvePicture's camera frames, TF range, and the field's percentiles,
// which the fitted presets follow: every rank's counts of the cells it owns summed over the ranks,
// so they equal one process's exactly). Refuses mode dvr before reading anything.
DataPart loadPart(World& world, const session::PictureDescription& d);

struct DataParallelResult {
    scene::RenderOutput out;     // the image of every sample (the same on every rank)
    nlohmann::ordered_json mpi;  // rank 0: the "mpi" block of --json
};

// Renders p.session().spp samples per pixel with every rank's part of the data (collective: every
// rank calls it). progress(done, spp) on rank 0.
DataParallelResult renderDataParallel(World& world, picture::Picture& p, const DataPart& part,
                                      nlohmann::ordered_json rankInfo,
                                      const std::function<void(uint32_t, uint32_t)>& progress = {});

}  // namespace amrvk::mpi
