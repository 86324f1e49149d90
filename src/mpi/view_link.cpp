#include "mpi/view_link.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <nlohmann/json.hpp>
#include <thread>
#include <vector>

#include "core/error.h"
#include "core/stats.h"
#include "mpi/sample_parallel.h"
#include "render/renderer.h"
#include "session/session.h"

namespace amrvk::mpi {

namespace {

using Json = nlohmann::json;
using Clock = std::chrono::steady_clock;

constexpr int kOrderTag = 5301, kAnswerTag = 5302, kSumsTag = 5303;

// A message from `source` with `tag` once one arrived (polled: a waiting rank sleeps rather than
// spins, so idle followers leave the cores to the others); false at the deadline.
template <typename T>
bool receive(int source, int tag, MPI_Datatype type, std::vector<T>& out, std::optional<Clock::time_point> deadline) {
    for (int idle = 0;; ++idle) {
        int arrived = 0;
        MPI_Status status;
        MPI_Iprobe(source, tag, MPI_COMM_WORLD, &arrived, &status);
        if (arrived) {
            int count = 0;
            MPI_Get_count(&status, type, &count);
            out.resize(size_t(count));
            MPI_Recv(out.data(), count, type, source, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
            return true;
        }
        if (deadline && Clock::now() > *deadline) return false;
        std::this_thread::sleep_for(std::chrono::microseconds(idle < 1000 ? 200 : 2000));
    }
}

std::string text(const std::vector<char>& bytes) { return std::string(bytes.begin(), bytes.end()); }

void sendText(const std::string& s, int dest, int tag) {
    MPI_Send(s.data(), int(s.size()), MPI_CHAR, dest, tag, MPI_COMM_WORLD);
}

// The follower's picture made the session's: other data (a series step, another scale or field)
// read and built as rank 0 did, else the TF, structure and settings committed at once.
void applySession(gpu::Context& ctx, picture::Picture& p, const session::Session& next,
                  const picture::Options& options) {
    const session::Session cur = p.session();
    if (next.input != cur.input || next.field != cur.field || !(next.read.scale == cur.read.scale) ||
        next.read.logFloor != cur.read.logFloor) {
        session::PictureDescription d;
        d.session = next;
        p = picture::makePicture(ctx, session::loadVolume(next), d, options);
        return;
    }
    picture::PictureEdit e;
    if (!(next.structure == cur.structure)) e.structure = next.structure;
    if (!(next.tf == cur.tf) || next.tfColors != cur.tfColors) {
        e.tf = next.tf;
        e.tfColors = next.tfColors;
    }
    e.settings = next.settings;
    p.commit(e);
    p.described.spp = next.spp;
    p.described.legend = next.legend;
}

void requireSamePicture(World& world, const picture::Picture& p) {
    world.checkpoint();  // every rank has its picture (or one failed: all stop here)
    world.requireSame(pictureFingerprint(p.session()), "the picture (data, options or fitted choices)",
                      "every rank must run the same amrvk view command on the same data");
    world.requireSame(p.volume->model.cellCount(), "the data set (cell count)",
                      "every rank must run the same amrvk view command on the same data");
}

}  // namespace

ViewLink::ViewLink(World& world) : mWorld(world) {
    AMRVK_CHECK(world.rank() == 0, "internal: the viewer's link is rank 0's");
}

ViewLink::~ViewLink() { quit(); }

void ViewLink::start(const picture::Picture& p) {
    requireSamePicture(mWorld, p);
    mSentSession = session::sessionJson(p.session());  // every rank fitted the same session
}

void ViewLink::quit() {
    if (mQuit) return;
    mQuit = true;
    const std::string order = Json{{"kind", "quit"}}.dump();
    for (int r = 1; r < mWorld.size(); ++r) {
        MPI_Request request;  // a hung rank must not hold rank 0: sent without waiting for it
        MPI_Isend(order.data(), int(order.size()), MPI_CHAR, r, kOrderTag, MPI_COMM_WORLD, &request);
        MPI_Request_free(&request);
    }
}

void ViewLink::pass(const picture::Picture& p, uint32_t perRank) {
    render::Renderer& renderer = *p.renderer;
    AMRVK_CHECK(perRank >= 1 && renderer.rowsDone() == 0, "internal: a pass of whole samples");
    const Timer mine;
    const uint32_t first = renderer.accumulatedSpp();
    Json order = {{"kind", "pass"}, {"first", first}, {"perRank", perRank}};
    const std::string sessionText = session::sessionJson(p.session());
    const bool changed = sessionText != mSentSession;
    if (changed) order["session"] = sessionText;
    const std::string orderText = order.dump();
    std::vector<MPI_Request> sent(size_t(mWorld.size() - 1));
    for (int r = 1; r < mWorld.size(); ++r)
        MPI_Isend(orderText.data(), int(orderText.size()), MPI_CHAR, r, kOrderTag, MPI_COMM_WORLD,
                  &sent[size_t(r - 1)]);
    mSentSession = sessionText;
    renderer.accumulate(perRank);  // rank 0's share: indices first .. first + perRank
    // The others do what rank 0 did (a rebuild after a change, the share), at about its pace.
    const double grace = kViewAnswerSeconds + 4.0 * mine.seconds() + (changed ? 4.0 * p.report.buildSeconds : 0.0);
    const Clock::time_point deadline =
        Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(grace));
    const auto silent = [&](int r) {
        mWorld.abort(strCat("amrvk view: error: rank ", r, " of ", mWorld.size(), " did not answer within ",
                            int(grace + 0.5), " s (hung, or its device stopped); every rank ends"));
    };
    std::string failure;
    for (int r = 1; r < mWorld.size(); ++r) {
        std::vector<char> header;
        if (!receive(r, kAnswerTag, MPI_CHAR, header, deadline)) silent(r);
        const Json h = Json::parse(text(header));
        if (h.contains("error")) {
            if (failure.empty()) failure = h["error"].get<std::string>();
            continue;
        }
        std::vector<double> values;
        if (!receive(r, kSumsTag, MPI_DOUBLE, values, deadline)) silent(r);
        if (!failure.empty()) continue;
        scene::RenderStats stats;
        stats.paths = h["paths"].get<uint64_t>();
        stats.gpuSeconds = h["gpuSeconds"].get<double>();
        const std::vector<uint64_t> counters = h["counters"].get<std::vector<uint64_t>>();
        for (size_t k = 0; k < std::min(counters.size(), stats.counters.size()); ++k) stats.counters[k] = counters[k];
        const scene::RenderSettings& s = renderer.settings();
        renderer.addSums({.width = s.width, .height = s.height, .values = std::move(values)}, perRank, stats);
    }
    MPI_Waitall(int(sent.size()), sent.data(), MPI_STATUSES_IGNORE);  // every order was received
    if (!failure.empty()) throw FollowerFailed(failure);
}

void followViewer(World& world, gpu::Context& ctx, picture::Picture& p, const picture::Options& options) {
    requireSamePicture(world, p);
    for (;;) {
        std::vector<char> bytes;
        receive(0, kOrderTag, MPI_CHAR, bytes, std::nullopt);
        const Json order = Json::parse(text(bytes));
        if (order["kind"] == "quit") return;
        std::string error;
        Json answer;
        std::vector<double> values;
        try {
            if (order.contains("session"))
                applySession(ctx, p, session::parseSession(order["session"].get<std::string>(), "rank 0's picture"),
                             options);
            const uint32_t first = order["first"].get<uint32_t>(), perRank = order["perRank"].get<uint32_t>();
            render::Renderer& r = *p.renderer;
            r.setFirstSample(first + uint32_t(world.rank()) * perRank);  // resets: this pass's share alone
            r.accumulate(perRank);
            values = r.sums().values;
            const scene::RenderStats& st = r.stats();
            answer = {{"paths", st.paths},
                      {"gpuSeconds", st.gpuSeconds},
                      {"counters", std::vector<uint64_t>(st.counters.begin(), st.counters.end())}};
        } catch (const std::exception& e) {
            error = e.what();
            answer = {{"error", error}};
        }
        sendText(answer.dump(), 0, kAnswerTag);
        if (!error.empty()) throw Error(error);
        MPI_Send(values.data(), int(values.size()), MPI_DOUBLE, 0, kSumsTag, MPI_COMM_WORLD);
    }
}

}  // namespace amrvk::mpi
