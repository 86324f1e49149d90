// A time series in the viewer (`amrvk view 'DD00*/DD00??'`): stepping and playing, the steps next
// to the shown one read ahead beside the event loop within a memory budget (ViewerApp,
// viewer_app_impl.h; the player's rules: viewer/logic/series_player.h).
#include <condition_variable>
#include <cstdio>
#include <map>
#include <mutex>
#include <thread>

#include "amr/step_time.h"
#include "core/error.h"
#include "core/stats.h"
#include "picture/picture.h"
#include "render/renderer.h"
#include "viewer/viewer_app_impl.h"

namespace amrvk::viewer {

// The worker that reads steps ahead: it reads the first wanted step not read yet (read options and
// field of `base`, input the step's), one at a time, and keeps it while it is wanted.
struct ViewerApp::ReadAhead {
    std::vector<std::string> inputs;
    std::mutex mutex;
    std::condition_variable changed;
    session::Session base;       // what a step is read with (its input replaced)
    std::vector<size_t> wanted;  // nearest first
    std::map<size_t, std::shared_ptr<const scene::Volume>> ready;
    std::map<size_t, std::string> failed;  // a step that could not be read: why
    std::optional<size_t> reading;
    bool stop = false;
    std::thread thread;

    std::optional<size_t> next() const {
        for (size_t k : wanted)
            if (!ready.count(k) && !failed.count(k)) return k;
        return std::nullopt;
    }
    void run() {
        std::unique_lock lock(mutex);
        for (;;) {
            changed.wait(lock, [&] { return stop || next().has_value(); });
            if (stop) return;
            const size_t k = *next();
            session::Session s = base;
            s.input = inputs[k];
            reading = k;
            lock.unlock();
            std::shared_ptr<const scene::Volume> volume;
            std::string error;
            try {
                volume = session::loadVolume(s);
            } catch (const std::exception& e) {
                error = e.what();
            }
            lock.lock();
            reading.reset();
            if (!error.empty())
                failed[k] = error;
            else if (std::find(wanted.begin(), wanted.end(), k) != wanted.end())
                ready[k] = std::move(volume);
            changed.notify_all();
        }
    }
};

void ViewerApp::ReadAheadDelete::operator()(ReadAhead* a) const { delete a; }

ViewerApp::~ViewerApp() { stopSeries(); }

void ViewerApp::startSeries() {
    if (mOpt.series.size() < 2) return;
    mPlayer.emplace(mOpt.series.size(), mOpt.seriesFps);
    mAhead.reset(new ReadAhead());
    mAhead->inputs = mOpt.series;
    mAhead->thread = std::thread([a = mAhead.get()] { a->run(); });
    scheduleAhead();
}

void ViewerApp::stopSeries() {
    if (!mAhead) return;
    {
        std::lock_guard lock(mAhead->mutex);
        mAhead->stop = true;
    }
    mAhead->changed.notify_all();
    mAhead->thread.join();  // a read under way finishes first
    mAhead.reset();
}

void ViewerApp::scheduleAhead() {
    if (!mAhead) return;
    const uint64_t perStep = mVolume->modelBytes() + mVolume->bricks.memoryBytes();
    std::lock_guard lock(mAhead->mutex);
    // Read with other read options (another scale) or another field, a step read ahead is stale.
    const session::Session& b = mAhead->base;
    if (!(b.read.scale == mState.read.scale && b.read.logFloor == mState.read.logFloor && b.field == mState.field)) {
        mAhead->ready.clear();
        mAhead->failed.clear();
    }
    mAhead->base = mState;
    mAhead->wanted = mPlayer->ahead(mOpt.seriesAheadBytes, perStep);
    std::erase_if(mAhead->ready, [&](const auto& kv) {
        return std::find(mAhead->wanted.begin(), mAhead->wanted.end(), kv.first) == mAhead->wanted.end();
    });
    mAheadStepBytes = perStep;
    mAhead->changed.notify_all();
}

std::shared_ptr<const scene::Volume> ViewerApp::takeAhead(size_t k) {
    std::unique_lock lock(mAhead->mutex);
    // The step being read now is waited for (reading it again would take as long).
    mAhead->changed.wait(lock, [&] { return mAhead->reading != k; });
    if (auto it = mAhead->failed.find(k); it != mAhead->failed.end()) {
        const std::string why = it->second;
        mAhead->failed.erase(it);  // tried again when asked again
        throw Error(why);
    }
    auto it = mAhead->ready.find(k);
    if (it == mAhead->ready.end()) return nullptr;
    std::shared_ptr<const scene::Volume> v = std::move(it->second);
    mAhead->ready.erase(it);
    return v;
}

void ViewerApp::showStep(size_t k) {
    AMRVK_CHECK(mPlayer, "internal: no series");
    AMRVK_CHECK(k < mPlayer->steps(), "step ", k, " is outside the series (steps 0..", mPlayer->steps() - 1, ")");
    if (k == mPlayer->step()) return;
    Timer t;
    session::PictureDescription d;
    d.session = mState;  // camera, TF as shown, settings, structure: only the data changes
    d.session.input = mOpt.series[k];
    std::shared_ptr<const scene::Volume> volume;
    picture::Picture p;
    try {
        volume = takeAhead(k);
        const bool wasAhead = volume != nullptr;
        whileResponsive([&] {
            if (!volume) volume = session::loadVolume(d.session);
            p = picture::makePicture(*mCtx, volume, d, pictureOptions());
        });
        mStepTimings.push_back({k, t.seconds(), wasAhead});
    } catch (const Error& e) {
        throw Error(strCat("step ", k, " (", mOpt.series[k], "): ", e.what()));
    }
    vkQueueWaitIdle(mCtx->queue());  // frames in flight may still read the old accumulation
    mVolume = std::move(volume);
    const TfHistory history = mTfHistory;  // the series' TF: its edits stay undoable across steps
    adoptPicture(std::move(p));
    mTfHistory = history;
    mApplied = mState.settings;
    mPlayer->seek(k);
    mStats.stepSeconds = t.seconds();
    noteReset("step");
    scheduleAhead();
}

std::string ViewerApp::stepLabel() const {
    if (!mPlayer) return {};
    const std::optional<amr::StepTime> when = amr::stepTimeOf(mVolume->model.attributes);
    return strCat("step ", mPlayer->step(), " of ", mPlayer->steps(), ": ",
                  fs::path(mOpt.series[mPlayer->step()]).filename().string(),
                  when ? ", " + amr::describe(*when) : std::string(", no time recorded"));
}

void ViewerApp::playSeries() {
    if (!mPlayer) return;
    const double now = std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
    if (mShown != scene::Shown::Nothing && !mNeedPreview) mPlayer->onScreen(now);
    if (mPlayer->due(now)) showStep(mPlayer->stepOn(1));
    {
        std::lock_guard lock(mAhead->mutex);  // what the panel shows as read ahead
        mStats.seriesAhead.clear();
        for (const auto& [k, v] : mAhead->ready) mStats.seriesAhead.push_back(k);
    }
    mStats.seriesAheadBytes = uint64_t(mStats.seriesAhead.size()) * mAheadStepBytes;
}

}  // namespace amrvk::viewer
