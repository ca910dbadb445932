// The threads parallel_for (parallel.h) borrows: started once and kept, asleep between loops.
// Starting a thread costs about 56 us here (2 vCPU), and a patch shot runs three loops: 0.17 ms
// of a 21 ms shot. Waking a kept thread costs less, and the caller works in the meantime.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace hemirad::detail {

class LoopThreads {
  public:
    /// The process's one set (never destroyed: its threads sleep until the process ends).
    static LoopThreads& get() {
        static LoopThreads* threads = new LoopThreads;
        return *threads;
    }

    /// Hands `work` to `helpers` kept threads (starting more if there are fewer) and returns
    /// true; the caller then runs work itself and calls wait(). Returns false, handing nothing,
    /// when the threads are lent to another loop (one on another thread of the caller's
    /// program) or the caller is one of them (a loop inside a loop): the caller starts threads
    /// of its own, as before. May give fewer helpers than asked where no thread can be
    /// started; `helpers` says how many work.
    bool lend(std::size_t& helpers, const std::function<void()>& work) {
        if (inside()) return false;
        std::unique_lock lock(mutex_);
        if (busy_) return false;
        try {
            while (threads_.size() < helpers) threads_.emplace_back([this] { serve(); });
        } catch (...) { // no thread to be had: those there are
        }
        helpers = std::min(helpers, threads_.size());
        if (helpers == 0) return false;
        busy_ = true;
        job_ = &work;
        wanted_ = helpers;
        taken_ = finished_ = 0;
        ++generation_;
        wake_.notify_all();
        return true;
    }

    /// Returns once every helper that took the work has returned from it. Called when the
    /// caller's own share is done (every index handed out): a helper not yet awake by then
    /// would find nothing left, so it is no longer waited for.
    void wait() {
        std::unique_lock lock(mutex_);
        wanted_ = taken_;
        done_.wait(lock, [this] { return finished_ == wanted_; });
        job_ = nullptr;
        busy_ = false;
    }

  private:
    LoopThreads() = default;

    static bool& inside() {
        thread_local bool is_helper = false;
        return is_helper;
    }

    // A kept thread: takes a share of each loop while the loop wants helpers, sleeps between.
    void serve() {
        inside() = true;
        std::uint64_t seen = 0;
        std::unique_lock lock(mutex_);
        for (;;) {
            wake_.wait(lock, [&] { return generation_ != seen; });
            seen = generation_;
            if (taken_ >= wanted_) continue; // enough helpers took this one
            ++taken_;
            const std::function<void()>* job = job_;
            lock.unlock();
            try {
                (*job)(); // parallel_for's work keeps a body's exception for the caller
            } catch (...) {}
            lock.lock();
            if (++finished_ == wanted_) done_.notify_one();
        }
    }

    std::mutex mutex_;
    std::condition_variable wake_, done_;
    std::vector<std::thread> threads_; ///< never joined: they end with the process
    const std::function<void()>* job_ = nullptr;
    std::uint64_t generation_ = 0; ///< one more for each loop lent
    std::size_t wanted_ = 0, taken_ = 0, finished_ = 0;
    bool busy_ = false;
};

} // namespace hemirad::detail
