#pragma once
// Sample-parallel rendering (mpirun -n N amrvk render): every rank holds the whole data set and
// traces a disjoint range of the sample indices one process would trace (each sample is seeded by
// its index); the double sums of the ranks are added up, so N ranks give the image of one process
// with the same seed and spp up to float rounding (docs/mpi.md).
#include <cstdint>
#include <functional>
#include <vector>
#include <nlohmann/json.hpp>

#include "mpi/world.h"
#include "picture/picture.h"

namespace amrvk::mpi {

// Rank `rank` of `size` takes samples [first, first + count): contiguous ranges covering
// [0, spp) once, counts differing by at most one (a rank may get none when spp < size).
struct SampleRange {
    uint32_t first = 0, count = 0;
};
SampleRange sampleRange(uint32_t spp, int rank, int size);

// A hash of the fitted session (data source, field, TF, camera, settings, spp; not the structure
// choice, which may differ between ranks): equal on ranks that render the same picture.
uint64_t pictureFingerprint(const session::Session& s);

// The job's statistics from each rank's: paths and counters summed, GPU seconds the slowest rank's
// (the ranks run at once). Collective; adds the bytes this rank contributed to `sent`.
scene::RenderStats statsOverRanks(World& world, const scene::RenderStats& mine, uint64_t& sent);

// The "perRank" array of --json's mpi block (rank 0; others: null): every rank's `rankInfo` with
// what every mode reports (rank, host, local rank, device, peak host and device memory), in rank
// order. Adds to `moved` (rank 0) every rank's "bytesSent" and the reports themselves.
nlohmann::ordered_json gatherRankReports(World& world, nlohmann::ordered_json rankInfo, gpu::Context& ctx,
                                         uint64_t& moved);

// Renderer::render of the picture the renderer holds (its settings committed by the caller through
// picture::Picture; from scratch, snapshots at snapshotSpp) with the samples split over
// the ranks at each step between snapshots: every rank gets the image of all samples so far at each
// snapshot and at the end (the sums added on every rank), so every rank takes the same decisions
// after it. Collective: every rank calls it for the same picture. A rank's error fails the call on
// every rank (amrvk::Error naming the rank); a rank that left the job throws PeerFailed. The one
// sample-parallel driver: `amrvk render` and `amrvk bench` under mpirun.
struct SampleShare {
    scene::RenderOutput out;  // every rank's samples (the statistics summed over the ranks)
    scene::RenderStats mine;  // this rank's paths and counters
    uint32_t firstSample = 0, samples = 0;  // this rank's first sample index and how many it traced
    double renderSeconds = 0, reduceSeconds = 0;
    uint64_t bytesSent = 0;  // what this rank contributed to the reductions
};
SampleShare renderSamples(World& world, render::Renderer& renderer, uint32_t spp,
                          const std::function<void(uint32_t, uint32_t)>& progress,
                          const std::vector<uint32_t>& snapshotSpp = {},
                          const std::function<void(const scene::RenderOutput&)>& snapshot = {});

struct SampleParallelResult {
    scene::RenderOutput out;     // every rank's samples
    nlohmann::ordered_json mpi;  // rank 0: the "mpi" block of --json (per-rank work and bytes)
};

// `amrvk render` under mpirun: checks that every rank fitted the same picture, renders
// p.session().spp samples per pixel with renderSamples (progress(done, spp) on rank 0) and gathers
// the per-rank report. Calls world.checkpoint() before the first collective, so a rank that failed
// earlier ends the job cleanly. `rankInfo` is this rank's part of the report (read and build
// seconds, ...), gathered with the render's own numbers.
SampleParallelResult renderSampleParallel(World& world, picture::Picture& p, nlohmann::ordered_json rankInfo,
                                          const std::function<void(uint32_t, uint32_t)>& progress = {});

}  // namespace amrvk::mpi
