// The memory guard: the estimate counts the nodes discretise() makes at their sizes, the
// limit is parsed with units, and a discretisation over the limit is refused with a message
// that names the estimate, the limit and the options to change.
#include <gtest/gtest.h>

#include "hemirad/error.h"
#include "hemirad/memory_guard.h"
#include "hemirad/scene_io.h"
#include "hemirad/solver.h"

using namespace hemirad;

namespace {

std::string message_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(MemoryGuard, EstimateCountsEveryNode) {
    const Scene s = make_builtin("cube");
    SolverOptions o;
    o.ff = "reference"; // CPU: no GL, no provider arrays
    o.hierarchy.patch_size = 1e-9;
    o.hierarchy.max_depth = 3;
    const MemoryEstimate e = estimate_memory(s, discretise(s, o.hierarchy), o);
    EXPECT_EQ(e.nodes, s.polygons.size() * tree_size(3));
    EXPECT_EQ(e.leaves, s.polygons.size() * 64u);
    EXPECT_EQ(e.hierarchy, e.nodes * (sizeof(Hierarchy::Node) + 1));
    EXPECT_EQ(e.gl, 0u);
    o.ff = "hybrid";
    const MemoryEstimate g = estimate_memory(s, discretise(s, o.hierarchy), o);
    // 20 bytes a node, 160 a polygon for the BVH of centre_seen()'s ray casts.
    EXPECT_EQ(g.provider, g.nodes * 20 + s.polygons.size() * 160);
    o.ff = "hemicube"; // pixels only: no ray casts
    EXPECT_EQ(estimate_memory(s, discretise(s, o.hierarchy), o).provider, g.nodes * 20);
    // 8x8 patch IDs with mipmaps, 512x384 framebuffer at the default --max-resolution 256.
    EXPECT_EQ(g.gl, 8u * 8 * 8 * 4 / 3 + 512u * 384 * 36);
}

TEST(MemoryGuard, ParsesSizes) {
    EXPECT_EQ(parse_memory_size("0", "--memory-limit"), 0u);
    EXPECT_EQ(parse_memory_size("1000", "--memory-limit"), 1000u);
    EXPECT_EQ(parse_memory_size("512M", "--memory-limit"), 512u << 20);
    EXPECT_EQ(parse_memory_size("1.5g", "--memory-limit"), 3u << 29);
    EXPECT_EQ(parse_memory_size("2GiB", "--memory-limit"), 2ull << 30);
    EXPECT_EQ(parse_memory_size("4KB", "--memory-limit"), 4096u);
    for (const char* bad : {"", "-1", "12Q", "M", "1e999", "nan", "inf", "1G2", " 1G", "99999999T"})
        EXPECT_NE(message_of([&] {
                      parse_memory_size(bad, "--memory-limit");
                  }).find("--memory-limit '" + std::string(bad) + "'"),
                  std::string::npos)
            << bad;
}

TEST(MemoryGuard, RefusesWhatDoesNotFitAndNamesTheOptions) {
    const Scene s = make_builtin("cube");
    SolverOptions o;
    o.ff = "reference";
    o.hierarchy.patch_size = 1e-9;
    o.hierarchy.max_depth = 6; // 6 x 5461 nodes x 41 bytes = 1.3 MiB
    o.memory_limit = 1 << 20;
    const std::string m = message_of([&] { check_memory(s, discretise(s, o.hierarchy), o); });
    EXPECT_NE(m.find("needs about 1.3 MiB"), std::string::npos) << m;
    EXPECT_NE(m.find("1.0 MiB is available (--memory-limit)"), std::string::npos) << m;
    EXPECT_NE(m.find("--max-depth 5 would fit (now 6)"), std::string::npos) << m;
    EXPECT_NE(m.find("--patch-size"), std::string::npos) << m;
    // The solver refuses before it allocates.
    EXPECT_THROW(Solver(s, o), InputError);
    o.memory_limit = 2 << 20;
    EXPECT_NO_THROW(check_memory(s, discretise(s, o.hierarchy), o));
}

TEST(MemoryGuard, AvailableMemoryIsKnownHere) {
    std::string source;
    const std::uint64_t a = available_memory(&source);
    EXPECT_GT(a, 0u);
    EXPECT_FALSE(source.empty());
}

TEST(MemoryGuard, BytesText) {
    EXPECT_EQ(bytes_text(100), "100 bytes");
    EXPECT_EQ(bytes_text(1536), "1.5 KiB");
    EXPECT_EQ(bytes_text(300ull << 20), "300 MiB");
}

} // namespace
