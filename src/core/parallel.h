// The one parallel loop of the tree (after pbrt-v4's ParallelFor, src/pbrt/util/parallel.h):
// indices handed out one at a time to a few threads, the calling thread one of them, with one
// rule for how many threads run and exceptions carried back to the caller.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "core/loop_threads.h"

namespace hemirad {

/// The threads a loop runs on for a requested count: `requested` when > 0, else one per core
/// (std::thread::hardware_concurrency(), at least 1).
inline unsigned thread_count(int requested) {
    if (requested > 0) return unsigned(requested);
    return std::max(1u, std::thread::hardware_concurrency());
}

/// Calls body(i) for every i in [0, count), on min(thread_count(threads), count) threads: the
/// calling thread and that many less one kept threads (core/loop_threads.h), or threads started
/// for the loop where those are lent to another loop or this is one of them. Indices are taken in
/// increasing order, one at a time, by whichever thread is free (results that must not depend on
/// the threads are keyed by i, not by thread). Returns when every call has returned.
///
/// If a call throws, no further index is started, the calls under way finish, and the first
/// exception is rethrown here (later ones are dropped); nothing reaches std::terminate.
template <class Body> void parallel_for(std::size_t count, int threads, Body&& body) {
    if (count == 0) return;
    const std::size_t n = std::min<std::size_t>(thread_count(threads), count);
    std::atomic<std::size_t> next{0};
    std::atomic<bool> failed{false};
    std::exception_ptr error;
    std::mutex error_mutex;
    const auto work = [&] {
        for (std::size_t i;
             !failed.load(std::memory_order_relaxed) && (i = next.fetch_add(1)) < count;) {
            try {
                body(i);
            } catch (...) {
                std::lock_guard lock(error_mutex);
                if (!error) error = std::current_exception();
                failed = true;
            }
        }
    };
    std::size_t helpers = n - 1;
    // (std::ref: the work is handed over without a copy, nor an allocation for one.)
    const std::function<void()> job = std::ref(work);
    detail::LoopThreads& kept = detail::LoopThreads::get();
    if (helpers > 0 && kept.lend(helpers, job)) {
        try {
            work();
        } catch (...) { // (work() keeps the body's exceptions: only a failed lock gets here)
            kept.wait();
            throw;
        }
        kept.wait();
    } else { // one thread, or the kept ones are busy: threads of this loop's own
        std::vector<std::thread> pool;
        pool.reserve(helpers);
        try {
            for (std::size_t t = 0; t < helpers; ++t) pool.emplace_back(work);
        } catch (...) { // no thread to be had: the threads started so far and this one do it all
        }
        work();
        for (std::thread& t : pool) t.join();
    }
    if (error) std::rethrow_exception(error);
}

} // namespace hemirad
