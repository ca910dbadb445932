// hemirad-view's solver on a thread of its own, with a GL context of its own (a hidden GLFW
// window's), so that the window stays responsive while it shoots: a frame waits for at most the
// shot in progress, not for a per-frame solving budget (issue 21).
//
// The Solver is built, stepped and destroyed on the worker thread (its form-factor provider's
// GL objects live in the worker's context). The window's thread reads the solution and edits it
// only while it holds lock(): the worker takes the lock for each shot and, between shots, lets a
// waiting lock() in first.
#pragma once

#include <atomic>
#include <climits>
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>

#include "hemirad/solver.h"

struct GLFWwindow;

namespace hemirad::view {

class SolveThread {
  public:
    /// Starts the worker: it makes `context`'s GL context current (a window created on the
    /// main thread, not current anywhere else) and builds the Solver; errors of that (bad
    /// options, no GL) are rethrown here. The worker shoots nothing until run() or shoot().
    SolveThread(GLFWwindow* context, Scene& scene, const SolverOptions& options);
    /// Stops the worker after its shot in progress and destroys the Solver there.
    ~SolveThread();
    SolveThread(const SolveThread&) = delete;
    SolveThread& operator=(const SolveThread&) = delete;

    /// Exclusive access to solver() (reading the solution, drawing it, editing it). The worker
    /// finishes its shot in progress first.
    std::unique_lock<std::mutex> lock();
    /// Lets go of a lock() and wakes the worker.
    void release(std::unique_lock<std::mutex>& l);
    /// Only while holding lock() (or before run()/shoot()). Never lock the mutex otherwise:
    /// a worker that shoots shot after shot lets only a lock() in.
    Solver& solver() { return *solver_; }

    /// Shoot until `max_shots` shots are done in all (LONG_MAX: until the solver stops).
    void run(long max_shots = LONG_MAX);
    /// Stop shooting after the shot in progress.
    void pause();
    /// Shoot `n` more shots (fewer if the solver stops), waiting until they are done; then
    /// paused. Rethrows an error of the worker.
    void shoot(long n);
    /// After an edit (Solver::set_...): the solver may shoot again though it had stopped.
    void edited();

    long shots() const { return shots_.load(); }
    /// The solver's last step() returned false (converged, or another stop criterion) and no
    /// edit came since.
    bool stopped() const { return stopped_.load(); }
    /// Shooting now or about to (not paused, not stopped, under the target).
    bool busy() const;
    /// Rethrows an exception the worker's step() threw (then the worker has stopped).
    void check();
    /// Time the worker spent in step() so far [s].
    double shot_seconds() const { return shot_seconds_.load(); }

  private:
    void work(GLFWwindow* context, Scene* scene, SolverOptions options);

    mutable std::mutex mutex_;
    std::condition_variable wake_; ///< the worker waits on it: target, waiting, quit changed
    std::condition_variable done_; ///< shoot() waits on it: the worker reached its target
    std::unique_ptr<Solver> solver_;
    std::exception_ptr error_;
    std::atomic<long> target_{0}; ///< shoot while solver_->shots() < target_
    std::atomic<long> shots_{0};
    std::atomic<bool> stopped_{false};
    std::atomic<bool> failed_{false}; ///< error_ is set by step()
    std::atomic<int> waiting_{0};     ///< lock() calls waiting: the worker lets them in
    std::atomic<double> shot_seconds_{0};
    std::atomic<bool> quit_{false};
    bool ready_ = false; ///< under mutex_: the solver is built (or failed to be)
    std::thread thread_;
};

} // namespace hemirad::view
