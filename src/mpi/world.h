#pragma once
// One MPI job (MPI_COMM_WORLD) as amrvk uses it: this rank, the job size, the rank on this node
// (device choice), the failure agreement that turns an error on any rank into one line and a clean
// exit of every rank, and the sums and gathers of sample-parallel rendering. Built only with MPI
// (CMake option AMRVK_MPI, Open MPI from Debian); docs/mpi.md.
#include <cstdint>
#include <exception>
#include <functional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace amrvk::mpi {

// The first failing rank of an agreement (rank < 0: none failed).
struct Failure {
    int rank = -1;
    int count = 0;        // ranks that failed at this agreement
    bool fatal = false;   // one of them cannot go on (it is leaving the job)
    std::string message;  // the first failing rank's error (known on rank 0 and on that rank)
};

// Thrown on a healthy rank when another rank failed: rank 0 prints the failure, every rank exits.
class PeerFailed : public std::runtime_error {
public:
    explicit PeerFailed(Failure f) : std::runtime_error(f.message), failure(std::move(f)) {}
    Failure failure;
};

class World {
public:
    // MPI_Init (errors returned, not fatal); one per process.
    World();
    ~World();  // MPI_Finalize
    World(const World&) = delete;
    World& operator=(const World&) = delete;

    int rank() const { return mRank; }
    int size() const { return mSize; }
    int localRank() const { return mLocalRank; }  // rank among the ranks on this node
    const std::string& host() const { return mHost; }

    // Every rank calls agree() at the same points of its work, with the error it hit (empty: none).
    // Returns which rank failed first and how many did. A fatal error (the rank leaves the job)
    // waits at most `failedWaitSeconds` for the others to get there (they may be rendering): past
    // it, the rank prints `lineIfAlone` itself and aborts the job (MPI_Abort), so no fault keeps
    // the job alive. A non-fatal one (the job goes on, e.g. a failed bench run) waits as long as
    // healthy ranks do.
    Failure agree(const std::string& error, const std::string& lineIfAlone = {}, double failedWaitSeconds = 20,
                  bool fatal = true);
    // agree("") that throws PeerFailed when another rank failed.
    void checkpoint();

    // Rank 0: every rank's text, in rank order (others: empty).
    std::vector<std::string> gatherToRoot(const std::string& text);
    // Largest value over ranks, on every rank.
    double maxOverRanks(double value);
    // Throws, on every rank, "ranks disagree on WHAT (HINT)" unless every rank passes the same
    // fingerprint (collective): ranks started with different data or options would otherwise
    // combine pictures that do not belong together.
    void requireSame(uint64_t fingerprint, const std::string& what,
                     const std::string& hint = "every rank must run the same command on the same data");
    // Element-wise over every rank, the result on every rank (same count on all). Each returns the
    // bytes this rank contributed.
    struct FloatRank {
        float value;
        int rank;
    };
    uint64_t minLocEverywhere(std::vector<FloatRank>& values);  // the least value and its rank (lowest on ties)
    uint64_t sumEverywhere(std::vector<float>& values);
    uint64_t productEverywhere(std::span<float> values);
    uint64_t sumEverywhere(std::vector<uint64_t>& values);
    uint64_t sumEverywhere(std::vector<double>& values);

    // Prints `line` on stderr and ends every rank of the job.
    [[noreturn]] void abort(const std::string& line);

private:
    int mRank = 0, mSize = 1, mLocalRank = 0;
    std::string mHost;
};

// Runs `body` on every rank of a job started by mpirun (MPI_Init before, MPI_Finalize after; ranks
// other than 0 print no progress). An error on any rank - thrown, or a PeerFailed from a
// checkpoint - ends every rank with exit status 1, and rank 0 prints one line,
// "amrvk COMMAND: error: rank R of N: MESSAGE" (or "... (every rank)" when all failed alike);
// describe(error) gives MESSAGE. No rank writes outputs after a failure it can know of.
int runOnEveryRank(const std::string& command, const std::function<int(World&)>& body,
                   const std::function<std::string(std::exception_ptr)>& describe);

}  // namespace amrvk::mpi
