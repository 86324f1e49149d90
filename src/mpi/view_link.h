#pragma once
// The MPI viewer's link (mpirun -n N amrvk view, sample-parallel; docs/mpi.md): rank 0 runs the
// viewer (a window or --headless) and owns the picture; every other rank follows it. Before each
// pass of the estimate rank 0 sends every rank one order: the picture as a session when it changed
// since the last order (so every edit reaches every rank before the next pass, and no pass mixes
// two pictures), the first sample index of the pass and the samples per rank. Each rank traces its
// share (rank r: indices first + r * perRank on) and answers with its sums, which rank 0 adds to
// the share it traced into its own accumulation: N ranks give one process's image of the same
// samples. Messages are point to point and polled with a deadline: a rank that does not answer
// within kViewAnswerSeconds ends the job with one line naming it; rank 0 ending (window closed,
// a script's quit, an error) sends every rank a quit, so no rank is left running.
#include <cstdint>
#include <string>

#include "mpi/world.h"
#include "picture/picture.h"

namespace amrvk::mpi {

inline constexpr double kViewAnswerSeconds = 20;

// Thrown on rank 0 when a rank answered a pass with an error: that rank reports it (it leaves its
// follow loop with it), rank 0 ends without one of its own.
class FollowerFailed : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Rank 0's side.
class ViewLink {
public:
    explicit ViewLink(World& world);
    ~ViewLink();  // sends every rank a quit (once)
    ViewLink(const ViewLink&) = delete;
    ViewLink& operator=(const ViewLink&) = delete;

    int ranks() const { return mWorld.size(); }
    // Collective with followViewer's start: every rank's fitted picture and data are the same
    // (World::requireSame: "ranks disagree on ..." on every rank, one line).
    void start(const picture::Picture& p);
    // One pass of `perRank` samples per pixel on every rank over p as it is now (its session sent
    // first where it changed): rank 0's share accumulated into p.renderer, the others' added.
    // A rank's error: FollowerFailed; a rank that does not answer: the job ends (World::abort).
    void pass(const picture::Picture& p, uint32_t perRank);
    void quit();

private:
    World& mWorld;
    std::string mSentSession;  // the session text every rank holds
    bool mQuit = false;
};

// Ranks > 0: start (as ViewLink::start), then follow rank 0's orders until it quits: each new
// session made this rank's picture (other data read and built, as rank 0 did; else the TF,
// structure and settings committed), each pass's share traced and answered. Returns when rank 0
// quits; an error on this rank is answered to rank 0 and thrown.
void followViewer(World& world, gpu::Context& ctx, picture::Picture& p, const picture::Options& options);

}  // namespace amrvk::mpi
