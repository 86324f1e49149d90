#pragma once
// A mutex that serves its waiters in the order they came (a ticket lock over a condition
// variable), for the Python Renderer's device calls: a long render() or accumulate() releases it
// between chunks of about a quarter second, and with std::mutex it took the lock straight back
// (the widget's sliders and image froze for the whole call, issue 52 point 15). With this one a
// call that waits is served after at most the chunk under way. BasicLockable: std::lock_guard
// takes it.
#include <condition_variable>
#include <cstdint>
#include <mutex>

namespace amrvk::python {

class FairMutex {
public:
    void lock() {
        std::unique_lock guard(mMutex);
        const uint64_t ticket = mNext++;
        mTurn.wait(guard, [&] { return mServing == ticket; });
    }
    void unlock() {
        {
            std::lock_guard guard(mMutex);
            ++mServing;
        }
        mTurn.notify_all();
    }

private:
    std::mutex mMutex;
    std::condition_variable mTurn;
    uint64_t mNext = 0, mServing = 0;  // the next ticket given, the ticket whose turn it is
};

}  // namespace amrvk::python
