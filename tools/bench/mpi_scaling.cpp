// mpi_scaling: runs `hemirad solve cornell --tolerance 0.001` alone and with mpirun -np 1, 2
// (the hemirad next to this hemirad-bench), reads the reports and prints the figures
// docs/scaling.md quotes: shots, rounds, seconds, bytes and seconds of the exchange per round,
// and the largest group difference from the single process against the two error bounds.
#include "mpi_scaling.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hemirad/error.h"
#include "hemirad/json.h"

namespace hemirad::bench {

namespace {

namespace fs = std::filesystem;

std::string hemirad_path() {
    char buf[4096];
    const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
    if (n <= 0) throw RuntimeError("mpi_scaling: cannot read /proc/self/exe");
    buf[n] = 0;
    const fs::path p = fs::path(buf).parent_path() / "hemirad";
    if (!fs::exists(p)) throw RuntimeError("mpi_scaling: no hemirad next to hemirad-bench: " + p.string());
    return p.string();
}

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

} // namespace

void run_mpi_scaling() {
    if (std::system("command -v mpirun > /dev/null") != 0)
        throw RuntimeError("mpi_scaling: mpirun not found (Debian: openmpi-bin)");
    const std::string hemirad = hemirad_path();
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
        runs.push_back(j);
        std::printf("ROW mpi_scaling np %d: ranks %d, %ld shots in %ld rounds, %.2f s; exchange "
                    "%.0f bytes (dense would be %.0f), %.2f ms a round (%.3f ms moving bytes); max "
                    "group difference "
                    "%.2e vs bounds %.2e: %s\n",
                    ranks, got_ranks, long(r["shots"]), rounds, double(r["seconds"]), bytes, dense,
                    1e3 * comm, 1e3 * transfer, worst, bound, worst <= bound ? "agrees" : "DISAGREES");
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
