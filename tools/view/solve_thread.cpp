#include "solve_thread.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <chrono>

namespace hemirad::view {

SolveThread::SolveThread(GLFWwindow* context, Scene& scene, const SolverOptions& options) {
    thread_ = std::thread(&SolveThread::work, this, context, &scene, options);
    std::unique_lock<std::mutex> l(mutex_);
    done_.wait(l, [&] { return ready_; });
    if (error_) {
        l.unlock();
        thread_.join();
        std::rethrow_exception(error_);
    }
}

SolveThread::~SolveThread() {
    // Atomic, not under the mutex: a worker that shoots shot after shot holds it nearly always.
    quit_.store(true);
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
}

std::unique_lock<std::mutex> SolveThread::lock() {
    ++waiting_;
    std::unique_lock<std::mutex> l(mutex_);
    --waiting_;
    return l;
}

void SolveThread::release(std::unique_lock<std::mutex>& l) {
    if (l.owns_lock()) l.unlock();
    wake_.notify_all();
}

void SolveThread::run(long max_shots) {
    if (target_.exchange(max_shots) != max_shots) wake_.notify_all();
}

void SolveThread::pause() {
    target_.store(0);
}

void SolveThread::shoot(long n) {
    std::unique_lock<std::mutex> l = lock(); // lets a running worker finish its shot first
    target_.store(solver_->shots() + n);
    wake_.notify_all();
    done_.wait(l, [&] { return error_ || stopped_.load() || solver_->shots() >= target_.load(); });
    target_.store(0);
    if (error_) std::rethrow_exception(error_);
}

void SolveThread::edited() {
    stopped_.store(false);
    wake_.notify_all();
}

bool SolveThread::busy() const {
    return !stopped_.load() && shots_.load() < target_.load();
}

void SolveThread::check() {
    if (!failed_.load()) return;
    auto l = lock();
    std::rethrow_exception(error_);
}

void SolveThread::work(GLFWwindow* context, Scene* scene, SolverOptions options) {
    glfwMakeContextCurrent(context);
    {
        std::lock_guard<std::mutex> l(mutex_);
        try {
            options.provider.gpu.use_current_context = true;
            solver_ = std::make_unique<Solver>(*scene, options);
        } catch (...) {
            error_ = std::current_exception();
        }
        ready_ = true;
    }
    done_.notify_all();
    if (!solver_) {
        glfwMakeContextCurrent(nullptr);
        return;
    }
    std::unique_lock<std::mutex> l(mutex_);
    for (;;) {
        // Between shots: let a waiting lock() in first, then wait for work.
        // (A lock() holder wakes no one when it lets go: poll every few milliseconds.)
        const auto ready = [&] {
            return quit_.load() || (waiting_.load() == 0 && !error_ && !stopped_.load() &&
                                    solver_->shots() < target_.load());
        };
        while (!ready()) wake_.wait_for(l, std::chrono::milliseconds(4));
        if (quit_.load()) break;
        try {
            const auto t0 = std::chrono::steady_clock::now();
            const bool more = solver_->step();
            shot_seconds_.store(
                shot_seconds_.load() +
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
            if (!more) stopped_.store(true);
        } catch (...) {
            error_ = std::current_exception();
            failed_.store(true);
        }
        shots_.store(solver_->shots());
        done_.notify_all();
    }
    solver_.reset(); // its GL objects, in this thread's context
    glfwMakeContextCurrent(nullptr);
}

} // namespace hemirad::view
