// The shared helpers of src/core/: the number parser reads what std::strtod / std::strtoll
// read (a differential test against them), and refuses what they refuse; the parallel loop
// runs every index once, honours its thread limit and hands a worker's exception to the
// caller; the sRGB pair are inverses; the projections put the near plane at depth 1 and
// infinity at 0.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <glm/glm.hpp>

#include "core/colour.h"
#include "core/parallel.h"
#include "core/parse.h"
#include "core/projection.h"
#include "core/timer.h"

using namespace hemirad;

namespace {

// --- numbers -------------------------------------------------------------------------------

// What strtod makes of `text`: (characters read, value, ERANGE).
struct Strtod {
    long used;
    double value;
    bool range;
};
Strtod strtod_of(const std::string& text) {
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    return {long(end - text.c_str()), v, errno == ERANGE};
}

void expect_like_strtod(const std::string& text) {
    SCOPED_TRACE("'" + text + "'");
    const Strtod ref = strtod_of(text);
    double v = -7;
    const NumberRead r = read_double(text.data(), text.data() + text.size(), v);
    ASSERT_EQ(long(r.end - text.data()), ref.used);
    if (ref.used == 0) return; // nothing read: `v` is untouched, as it should be
    EXPECT_EQ(r.range_error, ref.range);
    if (std::isnan(ref.value))
        EXPECT_TRUE(std::isnan(v));
    else
        EXPECT_EQ(std::memcmp(&v, &ref.value, sizeof v), 0) << v << " vs " << ref.value;
}

TEST(Parse, ReadsWhatStrtodReads) {
    for (const char* t : {"0",
                          "1",
                          "-1",
                          "+1",
                          "1.5",
                          ".5",
                          "5.",
                          "1e3",
                          "1E-3",
                          "1e",
                          "1e+",
                          "-.5e-2",
                          "  7",
                          "\t-8",
                          "0x1p-4",
                          "0X1.8P1",
                          "-0x10",
                          "0x",
                          "0x.8p1",
                          "0xg",
                          "inf",
                          "-Infinity",
                          "nan",
                          "nan(12)",
                          "1e400",
                          "-1e400",
                          "1e-400",
                          "1e-310",
                          "4.9e-324",
                          "2.2250738585072014e-308",
                          "0e-400",
                          "1.5abc",
                          "abc",
                          "",
                          "-",
                          "+",
                          "+-1",
                          "-+1",
                          "--1",
                          ".",
                          "e5",
                          "1_000",
                          "123456789012345678901234567890",
                          "0.1",
                          "0.30000000000000004",
                          "1e308",
                          "1.8e308"})
        expect_like_strtod(t);
    // And random numbers written every way printf writes them.
    std::mt19937_64 rng(7);
    for (int i = 0; i < 20000; ++i) {
        double x;
        const std::uint64_t bits = rng();
        std::memcpy(&x, &bits, sizeof x);
        if (!std::isfinite(x)) continue;
        char buf[64];
        const char* formats[] = {"%.17g", "%.3g", "%a", "%.6e", "%f"};
        std::snprintf(buf, sizeof buf, formats[i % 5], x);
        expect_like_strtod(buf);
    }
}

TEST(Parse, WholeTexts) {
    EXPECT_EQ(parse_double("0.25"), 0.25);
    EXPECT_EQ(parse_double("+0.25"), 0.25);
    EXPECT_EQ(parse_double("0x1p-2"), 0.25); // printf %a, as solution files hold doubles
    EXPECT_EQ(parse_double("-0x1.8p+1"), -3.0);
    EXPECT_FALSE(parse_double(""));
    EXPECT_FALSE(parse_double("0.25 ")) << "anything after the number";
    EXPECT_FALSE(parse_double("0.25x"));
    EXPECT_FALSE(parse_double("x0.25"));
    EXPECT_FALSE(parse_double("1e400")) << "out of range";
    EXPECT_FALSE(parse_double("1e-400")) << "out of range";
    EXPECT_FALSE(parse_double(std::string("1\0", 2))) << "a NUL is not the end of the text";
    EXPECT_TRUE(std::isinf(*parse_double("inf"))) << "inf is a number; callers check";

    EXPECT_EQ(parse_integer("42"), 42);
    EXPECT_EQ(parse_integer("-42"), -42);
    EXPECT_EQ(parse_integer("+7"), 7);
    EXPECT_EQ(parse_integer(" 7"), 7);
    EXPECT_EQ(parse_integer("-9223372036854775808"), std::numeric_limits<long long>::min());
    EXPECT_FALSE(parse_integer("9223372036854775808")) << "out of range";
    EXPECT_FALSE(parse_integer("7 "));
    EXPECT_FALSE(parse_integer("1.0"));
    EXPECT_FALSE(parse_integer("0x10"));
    EXPECT_FALSE(parse_integer(""));
    EXPECT_FALSE(parse_integer("-"));

    long long i = 0;
    const std::string big = "99999999999999999999";
    const NumberRead r = read_integer(big.data(), big.data() + big.size(), i);
    EXPECT_TRUE(r.range_error);
    EXPECT_EQ(i, std::numeric_limits<long long>::max()) << "saturates, as strtoll";

    EXPECT_EQ(parse_unsigned("18446744073709551615"), ~0ull);
    EXPECT_FALSE(parse_unsigned("18446744073709551616"));
    EXPECT_FALSE(parse_unsigned("-1")) << "no wrapped-around negatives";
}

// --- the parallel loop -----------------------------------------------------------------------

TEST(ParallelFor, RunsEveryIndexOnce) {
    for (std::size_t count : {0, 1, 7, 1000}) {
        std::vector<std::atomic<int>> seen(count);
        parallel_for(count, 4, [&](std::size_t i) { seen[i].fetch_add(1); });
        for (std::size_t i = 0; i < count; ++i) EXPECT_EQ(seen[i].load(), 1) << i;
    }
}

// The threads that ran the calls: at most the limit, and never more than the calls.
std::size_t threads_used(std::size_t count, int limit) {
    std::mutex m;
    std::set<std::thread::id> ids;
    parallel_for(count, limit, [&](std::size_t) {
        std::this_thread::sleep_for(std::chrono::microseconds(200)); // let others take some
        std::lock_guard lock(m);
        ids.insert(std::this_thread::get_id());
    });
    return ids.size();
}

TEST(ParallelFor, HonoursTheThreadLimit) {
    EXPECT_LE(threads_used(200, 3), 3u);
    EXPECT_LE(threads_used(2, 8), 2u);
    EXPECT_LE(threads_used(200, 0), std::size_t(thread_count(0)));
    // One thread: the caller's own.
    std::set<std::thread::id> ids;
    parallel_for(50, 1, [&](std::size_t) { ids.insert(std::this_thread::get_id()); });
    EXPECT_EQ(ids, std::set<std::thread::id>{std::this_thread::get_id()});
    EXPECT_EQ(thread_count(5), 5u);
    EXPECT_GE(thread_count(0), 1u);
}

TEST(ParallelFor, HandsAWorkersExceptionToTheCaller) {
    for (int threads : {1, 4}) {
        std::atomic<int> calls{0};
        try {
            parallel_for(1000, threads, [&](std::size_t i) {
                calls.fetch_add(1);
                if (i == 17) throw std::runtime_error("index 17 failed");
            });
            FAIL() << "no exception";
        } catch (const std::runtime_error& e) {
            EXPECT_STREQ(e.what(), "index 17 failed");
        }
        // One thread: nothing after the failing index is started. More: the calls other
        // threads had under way finish (how many is up to the scheduler).
        if (threads == 1) {
            EXPECT_EQ(calls.load(), 18);
        }
        EXPECT_LE(calls.load(), 1000);
    }
    // Every call throwing: one exception arrives, nothing reaches std::terminate.
    EXPECT_THROW(parallel_for(100, 4, [](std::size_t) { throw std::logic_error("all"); }),
                 std::logic_error);
}

// The helpers are kept between loops (core/loop_threads.h): a helper's thread-local count of
// the calls it made goes on from loop to loop. A thread started for one loop makes at most that
// loop's 64 calls; kept threads (at most the 7 that earlier tests asked for) share 40 loops'.
TEST(ParallelFor, KeepsItsThreadsBetweenLoops) {
    const std::thread::id caller = std::this_thread::get_id();
    std::atomic<int> most{0};
    for (int loop = 0; loop < 40; ++loop)
        parallel_for(64, 2, [&](std::size_t) {
            thread_local int calls = 0;
            std::this_thread::sleep_for(std::chrono::microseconds(100)); // let the helper take some
            if (std::this_thread::get_id() == caller) return;
            const int c = ++calls;
            for (int m = most.load(); c > m && !most.compare_exchange_weak(m, c);) {}
        });
    EXPECT_GT(most.load(), 64);
}

// A loop inside a loop's body, and loops on two threads at once: the kept threads serve one
// loop at a time, the others start threads of their own; every index runs once, nothing hangs.
TEST(ParallelFor, LoopsInsideLoopsAndSideBySide) {
    std::vector<std::atomic<int>> seen(40 * 30);
    parallel_for(40, 3, [&](std::size_t i) {
        parallel_for(30, 3, [&](std::size_t j) { seen[i * 30 + j].fetch_add(1); });
    });
    for (std::size_t k = 0; k < seen.size(); ++k) EXPECT_EQ(seen[k].load(), 1) << k;
    std::vector<std::atomic<int>> a(5000), b(5000);
    std::thread other([&] {
        for (int r = 0; r < 20; ++r)
            parallel_for(250, 2, [&](std::size_t i) { a[i + 250 * std::size_t(r)].fetch_add(1); });
    });
    for (int r = 0; r < 20; ++r)
        parallel_for(250, 2, [&](std::size_t i) { b[i + 250 * std::size_t(r)].fetch_add(1); });
    other.join();
    for (std::size_t k = 0; k < a.size(); ++k) {
        EXPECT_EQ(a[k].load(), 1) << k;
        EXPECT_EQ(b[k].load(), 1) << k;
    }
}

// --- sRGB, projections, timer ----------------------------------------------------------------

TEST(Colour, SrgbPairAreInverses) {
    for (int i = 0; i <= 1000; ++i) {
        const double v = i / 1000.0;
        EXPECT_NEAR(srgb_decode(srgb_encode(v)), v, 1e-12) << v;
    }
    EXPECT_EQ(srgb_decode(0.0), 0.0);
    EXPECT_EQ(srgb_decode(1.0), 1.0);
    EXPECT_EQ(srgb_decode(std::nan("")), 0.0);
}

TEST(Projection, ReversedZPutsNearAtOneAndInfinityAtZero) {
    const double near = 0.01;
    for (const glm::mat4& m : {reversed_z_perspective(glm::radians(60.0), 1.5, near),
                               reversed_z_frustum(-near, near, -near, near, near)}) {
        const auto depth = [&](double distance) {
            const glm::vec4 c = m * glm::vec4(0, 0, float(-distance), 1);
            return double(c.z / c.w);
        };
        EXPECT_NEAR(depth(near), 1.0, 1e-6);
        EXPECT_NEAR(depth(2 * near), 0.5, 1e-6);
        EXPECT_NEAR(depth(1e9), 0.0, 1e-6);
    }
}

TEST(Timer, CountsUpwards) {
    const Stopwatch w;
    const double a = w.seconds();
    const double b = seconds_since(w.start());
    EXPECT_GE(a, 0.0);
    EXPECT_GE(b, a);
}

} // namespace
