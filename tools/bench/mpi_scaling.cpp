// mpi_scaling: runs `hemirad solve cornell --tolerance 0.001` alone and with mpirun -np 1, 2
// (the hemirad next to this hemirad-bench), reads the reports and prints the figures
// docs/scaling.md quotes: shots, rounds, seconds, bytes and seconds of the exchange per round,
// and the largest group difference from the single process against the two error bounds.
#include "mpi_scaling.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/timer.h"
#include "hemirad/error.h"
#include "hemirad/json.h"
#include "parallel/world.h"
#include "sibling.h"

namespace hemirad::bench {

namespace {

namespace fs = std::filesystem;

/// Runs one solve (ranks = 0: without mpirun) and returns its report.
nlohmann::json solve(const std::string& hemirad, int ranks, const fs::path& dir) {
    const fs::path report = dir / ("r" + std::to_string(ranks) + ".json");
    std::string cmd;
    if (ranks > 0) {
        cmd = "mpirun --oversubscribe ";
        if (geteuid() == 0) cmd += "--allow-run-as-root ";
        cmd += "-np " + std::to_string(ranks) + " ";
    }
    cmd += "'" + hemirad + "' solve cornell --tolerance 0.001 --quiet --report '" +
           report.string() + "'";
    if (std::system(cmd.c_str()) != 0) throw RuntimeError("mpi_scaling: failed: " + cmd);
    std::ifstream f(report);
    return nlohmann::json::parse(f);
}

/// Under mpirun (HEMIRAD_BENCH_MPI_PROBE=SPARSE:DENSE, bytes a round): the exchange alone, no
/// solve competing for the cores: the sparse all-gather (each rank SPARSE / ranks bytes) and
/// the dense sum of DENSE / 4 floats (reduce on rank 0 + broadcast), the median of 200 each.
/// Rank 0 prints "PROBE ranks sparse_ms dense_ms".
void run_probe(const char* spec) {
    double sparse = 0, dense = 0;
    if (std::sscanf(spec, "%lf:%lf", &sparse, &dense) != 2 || !(sparse > 0) || !(dense > 0))
        throw InputError("HEMIRAD_BENCH_MPI_PROBE: '" + std::string(spec) +
                         "' is not SPARSE:DENSE");
    int argc = 0;
    char** argv = nullptr;
    parallel::World world(argc, argv);
    const std::vector<std::uint8_t> mine(std::size_t(sparse / world.size()), 1);
    std::vector<float> values(std::size_t(dense / 4), 0.5f);
    // The median of 200 (each after a barrier): this machine's other loads make the mean noisy.
    const auto median_ms = [&](const std::function<void()>& exchange) {
        std::vector<double> ms;
        for (int i = 0; i < 200; ++i) {
            world.barrier();
            const auto t0 = SteadyClock::now();
            exchange();
            ms.push_back(1e3 * seconds_since(t0));
        }
        std::nth_element(ms.begin(), ms.begin() + 100, ms.end());
        return ms[100];
    };
    const double sparse_ms = median_ms([&] { world.all_gather(mine); });
    const double dense_ms = median_ms([&] { world.sum_to_all(values); });
    if (world.rank() == 0) std::printf("PROBE %d %.6g %.6g\n", world.size(), sparse_ms, dense_ms);
}

/// Runs the probe on `ranks` ranks; returns {sparse ms, dense ms} a round.
std::pair<double, double> probe(int ranks, double sparse, double dense) {
    char buf[4096];
    const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
    if (n <= 0) throw RuntimeError("mpi_scaling: cannot read /proc/self/exe");
    buf[n] = 0;
    std::string cmd = "HEMIRAD_BENCH_MPI_PROBE=" + std::to_string(sparse) + ":" +
                      std::to_string(dense) + " mpirun --oversubscribe ";
    if (geteuid() == 0) cmd += "--allow-run-as-root ";
    cmd +=
        "-np " + std::to_string(ranks) + " '" + std::string(buf) + "' --child --only mpi_scaling";
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) throw RuntimeError("mpi_scaling: cannot run " + cmd);
    char line[512];
    int got_ranks = 0;
    double s = -1, d = -1;
    while (std::fgets(line, sizeof line, p))
        std::sscanf(line, "PROBE %d %lf %lf", &got_ranks, &s, &d);
    if (pclose(p) != 0 || s < 0 || got_ranks != ranks)
        throw RuntimeError("mpi_scaling: the exchange probe failed: " + cmd);
    return {s, d};
}

} // namespace

void run_mpi_scaling() {
    if (const char* spec = std::getenv("HEMIRAD_BENCH_MPI_PROBE")) return run_probe(spec);
    if (std::system("command -v mpirun > /dev/null") != 0)
        throw RuntimeError("mpi_scaling: mpirun not found (Debian: openmpi-bin)");
    const std::string hemirad = sibling_tool("hemirad", "mpi_scaling");
    const fs::path dir = fs::temp_directory_path() / ("hemirad-mpi-" + std::to_string(getpid()));
    fs::create_directories(dir);
    const nlohmann::json alone = solve(hemirad, 0, dir);
    Json runs = Json::array();
    for (int ranks : {1, 2}) {
        const nlohmann::json r = solve(hemirad, ranks, dir);
        // |dE_avg| * area / emitted per group and channel, against the sum of the two bounds
        // (each solution is within its bound of the converged one).
        double worst = 0;
        for (std::size_t g = 0; g < r["groups"].size(); ++g)
            for (int c = 0; c < 3; ++c) {
                const double d = std::abs(double(r["groups"][g]["E_avg"][c]) -
                                          double(alone["groups"][g]["E_avg"][c])) *
                                 double(alone["groups"][g]["area"]) /
                                 double(alone["emitted_power"][c]);
                worst = std::max(worst, d);
            }
        const double bound = double(alone["error_bound"]) + double(r["error_bound"]);
        const int got_ranks = r["ranks"];
        Json j = Json::object();
        j["ranks"] = got_ranks;
        j["shots"] = long(r["shots"]);
        j["seconds"] = double(r["seconds"]);
        j["converged"] = bool(r["converged"]);
        j["max_group_difference"] = worst;
        j["bound_sum"] = bound;
        j["agrees"] = worst <= bound;
        double bytes = 0, dense = 12.0 * double(r["leaf_patches"]), comm = 0, transfer = 0;
        long rounds = r["shots"];
        if (r.contains("parallel")) {
            rounds = r["parallel"]["rounds"];
            bytes = r["parallel"]["bytes_per_round"];
            dense = r["parallel"]["dense_bytes_per_round"];
            comm = r["parallel"]["exchange_seconds_per_round"];
            transfer = r["parallel"]["transfer_seconds_per_round"];
        }
        j["rounds"] = rounds;
        j["bytes_per_round"] = bytes;
        j["dense_bytes_per_round"] = dense;
        j["exchange_seconds_per_round"] = comm;
        j["transfer_seconds_per_round"] = transfer;
        if (ranks > 1) {
            // The exchange alone (no solve running): sparse lists vs the dense sum.
            const auto [sparse_ms, dense_ms] = probe(ranks, bytes, dense);
            j["probe_sparse_ms"] = sparse_ms;
            j["probe_dense_ms"] = dense_ms;
            std::printf("ROW mpi_scaling np %d exchange alone: sparse all-gather of %.0f bytes "
                        "%.3f ms, dense sum of %.0f bytes (reduce + broadcast) %.3f ms\n",
                        ranks, bytes, sparse_ms, dense, dense_ms);
        }
        runs.push_back(j);
        std::printf("ROW mpi_scaling np %d: ranks %d, %ld shots in %ld rounds, %.2f s; exchange "
                    "%.0f bytes (dense would be %.0f), %.2f ms a round (%.3f ms moving bytes); max "
                    "group difference "
                    "%.2e vs bounds %.2e: %s\n",
                    ranks, got_ranks, long(r["shots"]), rounds, double(r["seconds"]), bytes, dense,
                    1e3 * comm, 1e3 * transfer, worst, bound,
                    worst <= bound ? "agrees" : "DISAGREES");
        std::fflush(stdout);
    }
    fs::remove_all(dir);
    Json j = Json::object();
    j["name"] = "mpi_scaling";
    j["scene"] = "cornell";
    j["tolerance"] = 0.001;
    j["alone_shots"] = long(alone["shots"]);
    j["alone_seconds"] = double(alone["seconds"]);
    j["leaf_patches"] = long(alone["leaf_patches"]);
    j["runs"] = runs;
    std::printf("JSON %s\n", j.dump(0).c_str());
    std::fflush(stdout);
}

} // namespace hemirad::bench
