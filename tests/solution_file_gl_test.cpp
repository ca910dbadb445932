// Save and resume: a run of M shots, saved and resumed to N shots, ends bit-identical to an
// uninterrupted run of N shots (GPU hybrid provider on the GL context here, and the CPU
// reference provider); damaged files are refused with an InputError, never a crash.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "hemirad/error.h"
#include "hemirad/scene_io.h"
#include "hemirad/solution_file.h"
#include "hemirad/solver.h"

using namespace hemirad;

namespace {

SolverOptions small_options(const std::string& ff) {
    SolverOptions o;
    o.ff = ff;
    o.tolerance = 1e-6;
    o.hierarchy.max_depth = ff == "reference" ? 3 : 4;
    o.provider.gpu.min_resolution = 32;
    o.provider.gpu.max_resolution = 96;
    o.provider.cpu.visibility_samples = 2;
    return o;
}

bool same_bits(const glm::vec3& a, const glm::vec3& b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

// Every node's floats and every polygon's unshot power, compared bit for bit.
void expect_identical(Solver& a, Solver& b) {
    ASSERT_EQ(a.shots(), b.shots());
    const Solver::State sa = a.save_state(), sb = b.save_state();
    ASSERT_EQ(sa.nodes.size(), sb.nodes.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < sa.nodes.size(); ++i)
        if (!same_bits(sa.nodes[i].H, sb.nodes[i].H) ||
            !same_bits(sa.nodes[i].dB, sb.nodes[i].dB) ||
            !same_bits(sa.nodes[i].dI, sb.nodes[i].dI))
            ++differ;
    EXPECT_EQ(differ, 0u) << "of " << sa.nodes.size() << " nodes";
    EXPECT_EQ(0, std::memcmp(sa.unshot.data(), sb.unshot.data(), sa.unshot.size() * sizeof(dvec3)));
    EXPECT_EQ(sa.dirty, sb.dirty);
    EXPECT_EQ(sa.enclosed, sb.enclosed);
    EXPECT_EQ(sa.provider, sb.provider);
    EXPECT_EQ(a.absorbed_power(), b.absorbed_power());
    EXPECT_EQ(a.escaped_power(), b.escaped_power());
    EXPECT_EQ(a.error_bound(), b.error_bound());
    // And after the final push-pull, the solution itself.
    const Hierarchy& ha = a.solution();
    const Hierarchy& hb = b.solution();
    differ = 0;
    for (std::uint32_t p = 0; p < ha.scene().polygons.size(); ++p)
        for (std::uint32_t i = 0; i < (1u << (2 * ha.depth(p))); ++i) {
            const PatchAddress leaf{p, std::uint32_t(ha.depth(p)), i};
            if (!same_bits(ha.node(leaf).H, hb.node(leaf).H)) ++differ;
        }
    EXPECT_EQ(differ, 0u);
}

void resume_matches_uninterrupted(const std::string& ff, long m, long n) {
    const Scene scene = make_builtin("cornell");
    SolverOptions o = small_options(ff);
    o.max_shots = n;
    Solver full(scene, o);
    while (full.step()) {}
    ASSERT_EQ(full.shots(), n);

    o.max_shots = m;
    Solver first(scene, o);
    while (first.step()) {}
    ASSERT_EQ(first.shots(), m);
    // The saved state must exercise the lazy push-pull: some polygons hold unpushed light.
    const Solver::State st = first.save_state();
    EXPECT_GT(std::count(st.dirty.begin(), st.dirty.end(), 1), 0);
    const std::string path = std::string(HEMIRAD_BINARY_DIR) + "/solution_file_test_" + ff + ".bin";
    save_solution(path, first);
    // A few more shots in the saved-from solver must not matter.
    first.step();

    const SolutionFile f = read_solution(path);
    EXPECT_EQ(f.scene_hash, scene.content_hash());
    o.max_shots = n;
    Solver resumed(scene, o);
    resume_solution(resumed, f, path);
    EXPECT_EQ(resumed.shots(), m);
    while (resumed.step()) {}
    expect_identical(full, resumed);
    std::filesystem::remove(path);
}

} // namespace

TEST(SolutionFile, ResumeIsBitIdenticalGpuHybrid) {
    resume_matches_uninterrupted("hybrid", 9, 30);
}

TEST(SolutionFile, ResumeIsBitIdenticalCpuReference) {
    resume_matches_uninterrupted("reference", 5, 14);
}

TEST(SolutionFile, DamagedFilesAreInputErrors) {
    const Scene scene = make_builtin("cornell");
    SolverOptions o = small_options("reference");
    o.hierarchy.max_depth = 1;
    o.max_shots = 2;
    Solver s(scene, o);
    while (s.step()) {}
    const std::string good = solution_bytes(s);
    EXPECT_NO_THROW(parse_solution(good, "good.bin"));
    // Every truncation, a flipped bit anywhere, trailing bytes: InputError, no crash.
    for (std::size_t len = 0; len < good.size(); len += 1 + len / 16)
        EXPECT_THROW(parse_solution(good.substr(0, len), "t.bin"), InputError) << len;
    for (std::size_t pos = 0; pos < good.size(); pos += 7) {
        std::string bad = good;
        bad[pos] = char(bad[pos] ^ 0x10);
        EXPECT_THROW(parse_solution(bad, "f.bin"), InputError) << pos;
    }
    EXPECT_THROW(parse_solution(good + "x", "x.bin"), InputError);
    EXPECT_THROW(read_solution(std::string(HEMIRAD_BINARY_DIR) + "/no/such/file.bin"), InputError);
    try {
        parse_solution(good.substr(0, 5), "short.bin");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("short.bin"), std::string::npos);
    }
}

TEST(SolutionFile, OtherSceneOrOptionsAreRefused) {
    const Scene cornell = make_builtin("cornell");
    const Scene cube = make_builtin("cube");
    SolverOptions o = small_options("reference");
    o.hierarchy.max_depth = 1;
    o.max_shots = 1;
    Solver s(cornell, o);
    s.step();
    const SolutionFile f = parse_solution(solution_bytes(s), "c.bin");
    EXPECT_NO_THROW(check_solution_scene(f, "c.bin", cornell, "cornell"));
    try {
        check_solution_scene(f, "c.bin", cube, "cube.obj");
        FAIL();
    } catch (const InputError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("c.bin"), std::string::npos) << m;
        EXPECT_NE(m.find("cube.obj"), std::string::npos) << m;
    }
    // A solver with another depth: the option is named.
    SolverOptions other = o;
    other.hierarchy.max_depth = 2;
    Solver s2(cornell, other);
    try {
        resume_solution(s2, f, "c.bin");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("--max-depth"), std::string::npos) << e.what();
    }
    // Saved options round-trip exactly.
    SolverOptions back;
    for (const SolutionOption& opt : f.options) apply_solution_option(back, opt, "c.bin");
    EXPECT_EQ(solution_options(back), solution_options(o));
}
