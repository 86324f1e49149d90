#include "mpi/world.h"

#include <mpi.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <thread>

#include "core/error.h"
#include "core/progress.h"
#include "core/stats.h"
#include "gpu/context.h"

namespace amrvk::mpi {

namespace {

constexpr int kMessageTag = 7301;

void check(int rc, const char* what) {
    if (rc == MPI_SUCCESS) return;
    char text[MPI_MAX_ERROR_STRING];
    int length = 0;
    MPI_Error_string(rc, text, &length);
    AMRVK_CHECK(false, "MPI: ", what, ": ", std::string(text, size_t(length)));
}

// Test hook (tests/mpi/collective_faults.sh): AMRVK_TEST_MPI_FAIL=CALL:RANK[:NTH] makes World's
// collective CALL (agree, gatherToRoot, maxOverRanks, requireSame, minLocEverywhere, sumEverywhere,
// productEverywhere) fail on rank RANK at its NTH call (default 1), as if MPI had returned an
// error there: that rank throws instead of joining the collective.
void injectedFault(const char* call, int rank) {
    static const std::string spec = [] {
        const char* env = std::getenv("AMRVK_TEST_MPI_FAIL");
        return std::string(env ? env : "");
    }();
    if (spec.empty()) return;
    static std::map<std::string, long> calls;
    const long nth = ++calls[call];
    const size_t a = spec.find(':'), b = spec.find(':', a == std::string::npos ? a : a + 1);
    if (a == std::string::npos || spec.substr(0, a) != call) return;
    if (std::strtol(spec.c_str() + a + 1, nullptr, 10) != rank) return;
    if (nth != (b == std::string::npos ? 1L : std::strtol(spec.c_str() + b + 1, nullptr, 10))) return;
    AMRVK_CHECK(false, "MPI: ", call, ": injected fault (AMRVK_TEST_MPI_FAIL=", spec, ")");
}

// Test hook: AMRVK_TEST_MPI_FAILED_WAIT_S=S replaces how long a failed rank waits for the others
// at an agreement (World::agree's failedWaitSeconds), so that the fault tests end in seconds.
double failedWait(double seconds) {
    static const double test = [] {
        const char* env = std::getenv("AMRVK_TEST_MPI_FAILED_WAIT_S");
        return env ? std::strtod(env, nullptr) : -1.0;
    }();
    return test > 0 ? test : seconds;
}

// Waits for a non-blocking collective; past `deadline` seconds (< 0: none) returns false.
bool waitFor(MPI_Request& request, double deadline) {
    const Timer timer;
    for (;;) {
        int done = 0;
        check(MPI_Test(&request, &done, MPI_STATUS_IGNORE), "MPI_Test");
        if (done) return true;
        if (deadline >= 0 && timer.seconds() > deadline) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
}

// call(first, n) over [0, count) in pieces of at most 2^26 elements (MPI counts are int).
template <typename Call>
void inPieces(size_t count, Call call) {
    constexpr size_t kPiece = size_t(1) << 26;
    for (size_t at = 0; at < count; at += kPiece) call(at, int(std::min(kPiece, count - at)));
}

// `op` over the ranks, the result on every rank; returns the bytes this rank contributed.
template <typename T>
uint64_t allPieces(T* data, size_t count, MPI_Datatype type, MPI_Op op) {
    inPieces(count, [&](size_t at, int n) {
        check(MPI_Allreduce(MPI_IN_PLACE, data + at, n, type, op, MPI_COMM_WORLD), "MPI_Allreduce");
    });
    return uint64_t(count * sizeof(T));
}

}  // namespace

World::World() {
    int provided = 0;
    check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    MPI_Comm_rank(MPI_COMM_WORLD, &mRank);
    MPI_Comm_size(MPI_COMM_WORLD, &mSize);
    MPI_Comm node;
    check(MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, mRank, MPI_INFO_NULL, &node),
          "MPI_Comm_split_type");
    MPI_Comm_rank(node, &mLocalRank);
    MPI_Comm_free(&node);
    char name[MPI_MAX_PROCESSOR_NAME];
    int length = 0;
    MPI_Get_processor_name(name, &length);
    mHost.assign(name, size_t(length));
}

World::~World() { MPI_Finalize(); }

Failure World::agree(const std::string& error, const std::string& lineIfAlone, double failedWaitSeconds, bool fatal) {
    injectedFault("agree", mRank);
    const int mine = error.empty() ? 0 : fatal ? 2 : 1;
    std::vector<int> all(size_t(mSize), 0);
    MPI_Request request;
    check(MPI_Iallgather(&mine, 1, MPI_INT, all.data(), 1, MPI_INT, MPI_COMM_WORLD, &request), "MPI_Iallgather");
    // A healthy rank waits as long as the others work; a rank that is leaving only so long.
    if (!waitFor(request, mine == 2 ? failedWait(failedWaitSeconds) : -1.0))
        abort(lineIfAlone.empty() ? error : lineIfAlone);
    Failure f;
    for (int r = 0; r < mSize; ++r)
        if (all[size_t(r)]) {
            if (f.rank < 0) f.rank = r;
            ++f.count;
            f.fatal = f.fatal || all[size_t(r)] == 2;
        }
    if (f.rank < 0) return f;
    if (f.rank == mRank) f.message = error;
    if (f.rank != 0 && mRank == f.rank) {
        const int length = int(std::min<size_t>(error.size(), 1 << 20));
        check(MPI_Send(error.data(), length, MPI_CHAR, 0, kMessageTag, MPI_COMM_WORLD), "MPI_Send");
    } else if (f.rank != 0 && mRank == 0) {
        MPI_Status status;
        check(MPI_Probe(f.rank, kMessageTag, MPI_COMM_WORLD, &status), "MPI_Probe");
        int length = 0;
        MPI_Get_count(&status, MPI_CHAR, &length);
        f.message.resize(size_t(length));
        check(MPI_Recv(f.message.data(), length, MPI_CHAR, f.rank, kMessageTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
              "MPI_Recv");
    }
    return f;
}

void World::checkpoint() {
    Failure f = agree("");
    if (f.rank >= 0) throw PeerFailed(std::move(f));
}


std::vector<std::string> World::gatherToRoot(const std::string& text) {
    injectedFault("gatherToRoot", mRank);
    AMRVK_CHECK(text.size() < size_t(INT_MAX / 2), "internal: gathered text too long");
    const int length = int(text.size());
    std::vector<int> lengths(size_t(mSize), 0), offsets(size_t(mSize), 0);
    check(MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Gather");
    std::string all;
    if (mRank == 0) {
        size_t total = 0;
        for (int r = 0; r < mSize; ++r) {
            offsets[size_t(r)] = int(total);
            total += size_t(lengths[size_t(r)]);
        }
        AMRVK_CHECK(total < size_t(INT_MAX), "internal: gathered text too long");
        all.resize(total);
    }
    check(MPI_Gatherv(text.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR, 0,
                      MPI_COMM_WORLD),
          "MPI_Gatherv");
    std::vector<std::string> out;
    if (mRank == 0)
        for (int r = 0; r < mSize; ++r)
            out.push_back(all.substr(size_t(offsets[size_t(r)]), size_t(lengths[size_t(r)])));
    return out;
}

double World::maxOverRanks(double value) {
    injectedFault("maxOverRanks", mRank);
    double most = value;
    check(MPI_Allreduce(&value, &most, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD), "MPI_Allreduce");
    return most;
}

void World::requireSame(uint64_t fingerprint, const std::string& what, const std::string& hint) {
    injectedFault("requireSame", mRank);
    uint64_t range[2] = {fingerprint, ~fingerprint};  // min of the value, min of its complement (max)
    check(MPI_Allreduce(MPI_IN_PLACE, range, 2, MPI_UINT64_T, MPI_MIN, MPI_COMM_WORLD), "MPI_Allreduce");
    AMRVK_CHECK(range[0] == fingerprint && ~range[1] == fingerprint, "ranks disagree on ", what, " (", hint, ")");
}

uint64_t World::minLocEverywhere(std::vector<FloatRank>& values) {
    injectedFault("minLocEverywhere", mRank);
    static_assert(sizeof(FloatRank) == 8);
    return allPieces(values.data(), values.size(), MPI_FLOAT_INT, MPI_MINLOC);
}
uint64_t World::sumEverywhere(std::vector<float>& values) {
    injectedFault("sumEverywhere", mRank);
    return allPieces(values.data(), values.size(), MPI_FLOAT, MPI_SUM);
}
uint64_t World::productEverywhere(std::span<float> values) {
    injectedFault("productEverywhere", mRank);
    return allPieces(values.data(), values.size(), MPI_FLOAT, MPI_PROD);
}
uint64_t World::sumEverywhere(std::vector<double>& values) {
    injectedFault("sumEverywhere", mRank);
    return allPieces(values.data(), values.size(), MPI_DOUBLE, MPI_SUM);
}
uint64_t World::sumEverywhere(std::vector<uint64_t>& values) {
    injectedFault("sumEverywhere", mRank);
    return allPieces(values.data(), values.size(), MPI_UINT64_T, MPI_SUM);
}

void World::abort(const std::string& line) {
    std::fprintf(stderr, "%s\n", line.c_str());
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, 1);
    _exit(1);
}

int runOnEveryRank(const std::string& command, const std::function<int(World&)>& body,
                   const std::function<std::string(std::exception_ptr)>& describe) {
    World world;
    if (world.rank() != 0) silenceProgress();
    gpu::reportGpuCrashes();  // again: MPI_Init put Open MPI's own SIGSEGV/SIGBUS handlers in place
    gpu::setErrorPrefix("rank " + std::to_string(world.rank()) + " of " + std::to_string(world.size()));
    const std::string prefix = "amrvk " + command + ": error: ";
    const std::string ofN = " of " + std::to_string(world.size());
    int rc = 1;
    std::string error;
    Failure failure;
    try {
        rc = body(world);
    } catch (const PeerFailed& e) {
        failure = e.failure;
    } catch (...) {
        error = describe(std::current_exception());
        if (error.empty()) error = "unknown error";
    }
    const std::string mine = prefix + "rank " + std::to_string(world.rank()) + ofN + ": ";
    if (failure.rank < 0) {
        // The agreement itself can fail (MPI returns an error): this rank cannot tell the others, who
        // wait for it without a deadline, so it ends the job with its own line (it used to leave
        // the collective and hang every rank in MPI_Finalize).
        try {
            failure = world.agree(error, mine + error);
        } catch (const std::exception& e) {
            world.abort(mine + (error.empty() ? std::string() : error + "; then ") + oneLineMessage(e.what()));
        }
    }
    if (failure.rank < 0) return rc;
    if (world.rank() == 0) {
        if (failure.count == world.size())
            std::fprintf(stderr, "%s%s (every rank%s)\n", prefix.c_str(), failure.message.c_str(), ofN.c_str());
        else
            std::fprintf(stderr, "%srank %d%s: %s%s\n", prefix.c_str(), failure.rank, ofN.c_str(),
                         failure.message.c_str(),
                         failure.count > 1 ? (" (and " + std::to_string(failure.count - 1) + " more)").c_str() : "");
    }
    return 1;
}

}  // namespace amrvk::mpi
