// Parallel rounds (Solver::set_collective, docs/scaling.md) without MPI: ranks are threads
// here, each with its own Solver on the CPU reference provider, exchanging through an
// in-process all-gather. Every rank must hold the bit-identical state after every round,
// conserve energy, converge within its bound of the single-process solution, and hand over
// to a solver with another rank count through save_state().
#include <gtest/gtest.h>

#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

#include "hemirad/scene_io.h"
#include "hemirad/solver.h"

using namespace hemirad;

namespace {

/// An all-gather between threads: the last to arrive publishes everyone's bytes.
class ThreadExchange {
  public:
    explicit ThreadExchange(int n) : n_(n), slots_(std::size_t(n)) {}
    std::vector<std::vector<std::uint8_t>> gather(int rank, const std::vector<std::uint8_t>& b) {
        std::unique_lock<std::mutex> lock(m_);
        const long generation = generation_;
        slots_[std::size_t(rank)] = b;
        if (++arrived_ == n_) {
            result_ = slots_;
            arrived_ = 0;
            ++generation_;
            cv_.notify_all();
        } else {
            cv_.wait(lock, [&] { return generation_ != generation; });
        }
        return result_;
    }
    int size() const { return n_; }

  private:
    int n_;
    std::mutex m_;
    std::condition_variable cv_;
    int arrived_ = 0;
    long generation_ = 0;
    std::vector<std::vector<std::uint8_t>> slots_, result_;
};

class ThreadRank final : public Collective {
  public:
    ThreadRank(ThreadExchange& x, int rank) : x_(x), rank_(rank) {}
    int rank() const override { return rank_; }
    int size() const override { return x_.size(); }
    std::vector<std::vector<std::uint8_t>>
    all_gather(const std::vector<std::uint8_t>& mine) override {
        return x_.gather(rank_, mine);
    }
    bool any(bool flag) override {
        for (const auto& b : x_.gather(rank_, {std::uint8_t(flag)}))
            if (b.at(0)) return true;
        return false;
    }

  private:
    ThreadExchange& x_;
    int rank_;
};

SolverOptions cpu_options(double tolerance) {
    SolverOptions o;
    o.ff = "reference";
    o.tolerance = tolerance;
    o.hierarchy.max_depth = 2;
    o.hierarchy.patch_size = 1e-9; // always the maximum depth
    return o;
}

Scene test_scene() {
    BuiltinOptions bo;
    bo.rho = 0.7;
    bo.subdiv = 2;
    return make_builtin("cube", bo);
}

/// Runs `body(solver, collective)` on `ranks` threads, each with its own solver.
void on_ranks(int ranks, const Scene& scene, const SolverOptions& o,
              const std::function<void(Solver&, Collective&)>& body) {
    ThreadExchange exchange(ranks);
    std::vector<std::thread> threads;
    for (int r = 0; r < ranks; ++r)
        threads.emplace_back([&, r] {
            ThreadRank rank(exchange, r);
            Solver s(scene, o);
            s.set_collective(&rank);
            body(s, rank);
        });
    for (std::thread& t : threads) t.join();
}

std::vector<std::uint8_t> bytes_of(std::uint64_t v) {
    const auto* p = reinterpret_cast<const std::uint8_t*>(&v);
    return {p, p + sizeof v};
}

} // namespace

// Three ranks: the same state on every rank after every round, energy balanced, every shot
// recorded once in rank order, and the solution within the two bounds of one rank's.
TEST(SolverRounds, RanksStayBitIdenticalAndAgreeWithOneRank) {
    const Scene scene = test_scene();
    const SolverOptions o = cpu_options(1e-3);
    Solver alone(scene, o);
    while (alone.step()) {}
    ASSERT_TRUE(alone.converged());
    const Hierarchy& h1 = alone.solution();

    std::mutex m;
    int mismatches = 0, rounds = 0;
    std::vector<double> leaf_b3;
    double bound3 = 0;
    long shots3 = 0;
    on_ranks(3, scene, o, [&](Solver& s, Collective& c) {
        const dvec3 phi = s.emitted_power();
        long shots = 0;
        while (s.step()) {
            // Compare the ranks' state hashes after every round.
            const auto all = c.all_gather(bytes_of(s.state_checksum()));
            const std::lock_guard<std::mutex> lock(m);
            for (const auto& b : all) mismatches += b != all[0];
            const auto& round = s.last_round();
            EXPECT_FALSE(round.empty());
            for (std::size_t i = 0; i < round.size(); ++i) {
                EXPECT_EQ(round[i].shot, shots + long(i) + 1);
                EXPECT_EQ(round[i].rank, int(i));
            }
            shots += long(round.size());
            const dvec3 total = s.absorbed_power() + s.escaped_power() + s.unshot_power();
            EXPECT_NEAR(total.x, phi.x, 1e-5 * phi.x);
            if (c.rank() == 0) ++rounds;
        }
        const std::lock_guard<std::mutex> lock(m);
        EXPECT_TRUE(s.converged());
        EXPECT_EQ(s.shots(), shots);
        EXPECT_EQ(s.ranks(), 3);
        if (c.rank() == 0) {
            const Hierarchy& h = s.solution();
            for (const Hierarchy::Node& n : h.nodes()) leaf_b3.push_back(double(n.H.x));
            bound3 = s.error_bound();
            shots3 = s.shots();
            EXPECT_EQ(s.parallel_stats().rounds, rounds);
            EXPECT_GT(s.parallel_stats().bytes, 0);
        }
    });
    EXPECT_EQ(mismatches, 0);
    EXPECT_GT(rounds, 5);
    EXPECT_LT(rounds, shots3); // rounds of more than one shot
    // Each solution is within its bound of the converged one (power norm): the received power
    // sum_j |H1_j - H3_j| A_j is within (b1 + b3) * emitted.
    ASSERT_EQ(leaf_b3.size(), h1.nodes().size());
    double diff = 0;
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p)
        for (std::uint32_t i = 0; i < 16; ++i) {
            const PatchAddress a{p, 2, i};
            const std::uint64_t id = h1.node_id(a);
            diff += std::abs(double(h1.nodes()[id].H.x) - leaf_b3[id]) * h1.nodes()[id].area;
        }
    EXPECT_LE(diff, (alone.error_bound() + bound3) * alone.emitted_power().x);
    EXPECT_GT(diff, 0); // the rounds do shoot in another order
}

// A state saved by 2 ranks resumes on 1, and one saved by 1 on 2: the counts carry on and
// the ranks of the resumed run agree.
TEST(SolverRounds, SaveOnTwoRanksResumeOnOneAndBack) {
    const Scene scene = test_scene();
    SolverOptions o = cpu_options(1e-3);
    o.max_shots = 10;
    Solver::State two;
    on_ranks(2, scene, o, [&](Solver& s, Collective& c) {
        while (s.step()) {}
        if (c.rank() == 0) two = s.save_state();
    });
    EXPECT_EQ(two.counters.shots, 10);
    o.max_shots = 20;
    Solver one(scene, o);
    one.restore_state(two);
    while (one.step()) {}
    EXPECT_EQ(one.shots(), 20);
    const Solver::State from_one = one.save_state();
    o.max_shots = 25;
    std::uint64_t sums[2] = {0, 1};
    on_ranks(2, scene, o, [&](Solver& s, Collective& c) {
        s.restore_state(from_one);
        while (s.step()) {}
        EXPECT_EQ(s.shots(), 25);
        sums[c.rank()] = s.state_checksum();
    });
    EXPECT_EQ(sums[0], sums[1]);
}

// One rank through a collective of one shoots exactly as a solver without one.
TEST(SolverRounds, CollectiveOfOneIsTheSingleProcess) {
    const Scene scene = test_scene();
    const SolverOptions o = cpu_options(1e-2);
    Solver a(scene, o), b(scene, o);
    ThreadExchange x(1);
    ThreadRank r(x, 0);
    b.set_collective(&r);
    while (a.step()) ASSERT_TRUE(b.step());
    EXPECT_FALSE(b.step());
    EXPECT_EQ(a.state_checksum(), b.state_checksum());
    EXPECT_EQ(a.shots(), b.shots());
}
