// Wall-clock time for timings in reports, logs and progress lines: the steady clock, in
// seconds as a double. The one helper for "seconds since" in the tree.
#pragma once

#include <chrono>

namespace hemirad {

using SteadyClock = std::chrono::steady_clock;

/// Seconds from `start` to now [s].
inline double seconds_since(SteadyClock::time_point start) {
    return std::chrono::duration<double>(SteadyClock::now() - start).count();
}

/// A stopwatch: seconds() since it was made (or restarted).
class Stopwatch {
  public:
    Stopwatch() : start_(SteadyClock::now()) {}
    double seconds() const { return seconds_since(start_); } ///< [s]
    void restart() { start_ = SteadyClock::now(); }
    SteadyClock::time_point start() const { return start_; }

  private:
    SteadyClock::time_point start_;
};

} // namespace hemirad
