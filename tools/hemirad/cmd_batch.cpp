// hemirad batch: many scenes (lighting scenarios, design variants) solved independently, split
// across the MPI ranks (scene i on rank i mod N; one rank does them all), one folder per scene
// and a summary at the end. The embarrassingly parallel case: no collective until the summary.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <set>

#include "cli/cli_options.h"
#include "commands.h"
#include "core/timer.h"
#include "hemirad/error.h"
#include "hemirad/gl/context.h"
#include "hemirad/json.h"
#include "hemirad/report.h"
#include "hemirad/solver.h"
#include "parallel/world.h"
#include "solve_outputs.h"

namespace hemirad::cli {

namespace {

namespace fs = std::filesystem;

/// Folder names for the scenes: the file's stem or the built-in name, made unique ("-2", ...)
/// and safe (letters, digits, '-', '_', '.').
std::vector<std::string> folder_names(const std::vector<std::string>& scenes) {
    std::vector<std::string> names;
    std::set<std::string> used;
    for (const std::string& s : scenes) {
        std::string base = fs::path(s).stem().string();
        for (char& c : base)
            if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.')
                c = '_';
        if (base.empty() || base == "." || base == "..") base = "scene";
        std::string name = base;
        for (int k = 2; used.count(name); ++k) name = base + "-" + std::to_string(k);
        used.insert(name);
        names.push_back(name);
    }
    return names;
}

/// One scene's line of the summary: its JSON object and its printed row.
struct SceneResult {
    std::size_t index = 0;
    bool failed = false;
    std::string json, row;
};

/// Solves one scene into `dir`.
SceneResult solve_one(const std::string& scene_name, const fs::path& dir, const SolverOptions& so,
                      const BuiltinOptions& builtin, const ObjOptions& obj, bool quiet) {
    Json j = Json::object();
    j["scene"] = scene_name;
    j["folder"] = dir.filename().string();
    SceneResult r;
    const Stopwatch timer;
    char row[512];
    try {
        const Scene scene = load_scene(scene_name, builtin, obj);
        print_warnings(scene, quiet);
        Solver solver(scene, so);
        while (!interrupted() && solver.step()) {}
        const bool stopped = interrupted();
        fs::create_directories(dir);
        Json report = solve_report(solver);
        if (stopped) report["stop_reason"] = "interrupted";
        write_text_file((dir / "report.json").string(), report.dump() + "\n");
        const std::string status = stopped ? "interrupted" : to_string(solver.stop_reason());
        j["status"] = status;
        j["polygons"] = scene.polygons.size();
        j["leaf_patches"] = solver.hierarchy().leaf_count();
        j["shots"] = solver.shots();
        j["error_bound"] = solver.error_bound();
        j["converged"] = solver.converged();
        r.failed = stopped;
        std::snprintf(row, sizeof row, "%-24s %-12s %7ld shots  bound %.3e  %8.2f s",
                      dir.filename().string().c_str(), status.c_str(), solver.shots(),
                      solver.error_bound(), timer.seconds());
    } catch (const std::exception& e) {
        j["status"] = "error";
        j["error"] = e.what();
        r.failed = true;
        std::snprintf(row, sizeof row, "%-24s error: %s", dir.filename().string().c_str(),
                      e.what());
    }
    j["seconds"] = timer.seconds();
    r.row = row;
    r.json = j.dump(0);
    return r;
}

// The results travel to rank 0 as bytes: per scene its index, failed flag and two strings.
void put_u64(std::vector<std::uint8_t>& b, std::uint64_t v) {
    for (int i = 0; i < 8; ++i) b.push_back(std::uint8_t(v >> (8 * i)));
}
void put_string(std::vector<std::uint8_t>& b, const std::string& s) {
    put_u64(b, s.size());
    b.insert(b.end(), s.begin(), s.end());
}
std::vector<SceneResult> read_results(const std::vector<std::uint8_t>& b) {
    std::size_t at = 0;
    const auto u64 = [&] {
        HEMIRAD_CHECK(at + 8 <= b.size());
        std::uint64_t v = 0;
        for (int i = 0; i < 8; ++i) v |= std::uint64_t(b[at++]) << (8 * i);
        return v;
    };
    const auto str = [&] {
        const std::uint64_t n = u64();
        HEMIRAD_CHECK(n <= b.size() - at);
        std::string s(b.begin() + std::ptrdiff_t(at), b.begin() + std::ptrdiff_t(at + n));
        at += n;
        return s;
    };
    std::vector<SceneResult> out;
    while (at < b.size()) {
        SceneResult r;
        r.index = u64();
        r.failed = u64() != 0;
        r.json = str();
        r.row = str();
        out.push_back(std::move(r));
    }
    return out;
}

} // namespace

int cmd_batch(int argc, char** argv) {
    // The scenes come first (every argument before the first option), then the options.
    std::vector<std::string> scenes;
    int first_option = 2;
    while (first_option < argc && argv[first_option][0] != '-')
        scenes.push_back(argv[first_option++]);
    std::string out;
    bool quiet = false;
    SolverOptions so;
    BuiltinOptions builtin;
    ObjOptions obj;
    ArgParser args("hemirad batch", "hemirad batch SCENE... --out DIR [options]",
                   "Solves each SCENE on its own (same options for all), the scenes split\n"
                   "across the MPI ranks when launched by mpirun -np N (scene i on rank i mod N).\n"
                   "Writes DIR/NAME/report.json per scene (NAME: the file's stem or the built-in\n"
                   "name, made unique) and DIR/summary.json; rank 0 prints the summary. A scene\n"
                   "that fails is reported in the summary and the others carry on (exit 1).\n"
                   "SCENE: OBJ file, SCENE.json or built-in scene (" +
                       std::string(builtin_names()) + ").");
    args.option("--out", &out, "DIR", "the output folder (created if missing)");
    add_solver_options(args, so);
    args.flag("--quiet", &quiet, "print nothing but errors");
    add_scene_options(args, builtin, obj);
    if (!args.parse(argc, argv, first_option)) return 0;
    if (scenes.empty()) throw InputError("hemirad batch: no SCENE given (scenes come first)");
    if (out.empty()) throw InputError("hemirad batch: --out DIR is required");
    if (fs::exists(out) && !fs::is_directory(out))
        throw InputError("--out " + out + ": exists and is not a folder");
    validate_options(so);

    parallel::World& world = parallel::world();
    const bool lead = world.rank() == 0;
    const bool quiet_here = quiet || !lead;
    install_interrupt_handler();
    std::error_code ec;
    fs::create_directories(out, ec);
    if (ec) throw RuntimeError("cannot create --out " + out + ": " + ec.message());

    const std::vector<std::string> names = folder_names(scenes);
    std::unique_ptr<gl::Context> context;
    if (is_gpu_provider(so.ff)) {
        gl::ContextOptions co;
        co.backend = gl::parse_backend(so.provider.gpu.backend);
        co.device = so.provider.gpu.device;
        if (!args.given("--device") && world.local_size() > 1) {
            const std::size_t devices = gl::Context::egl_devices().size();
            if (devices >= 2) co.device = int(std::size_t(world.local_rank()) % devices);
        }
        context = gl::Context::create(co);
        so.provider.gpu.use_current_context = true;
    }
    if (!quiet_here)
        std::fprintf(stderr, "hemirad: batch of %zu scenes on %d rank%s into %s\n", scenes.size(),
                     world.size(), world.size() > 1 ? "s" : "", out.c_str());
    const Stopwatch timer;
    std::vector<std::uint8_t> mine;
    for (std::size_t i = std::size_t(world.rank()); i < scenes.size();
         i += std::size_t(world.size())) {
        SceneResult r;
        if (interrupted()) {
            Json j = Json::object();
            j["scene"] = scenes[i];
            j["folder"] = names[i];
            j["status"] = "skipped";
            r.json = j.dump(0);
            r.row = names[i] + " skipped (interrupted)";
            r.failed = true;
        } else {
            r = solve_one(scenes[i], fs::path(out) / names[i], so, builtin, obj, quiet_here);
        }
        if (!quiet_here)
            std::fprintf(stderr, "hemirad: [%zu/%zu] %s\n", i + 1, scenes.size(), r.row.c_str());
        put_u64(mine, i);
        put_u64(mine, r.failed ? 1 : 0);
        // The rank goes into the scene's JSON object, before its closing brace.
        put_string(mine, r.json.substr(0, r.json.size() - 1) +
                             ",\"rank\":" + std::to_string(world.rank()) + "}");
        put_string(mine, r.row);
    }

    // The summary: every rank's results, gathered, in scene order.
    const std::vector<std::vector<std::uint8_t>> all = world.all_gather(mine);
    if (!lead) return 0;
    std::map<std::size_t, SceneResult> results;
    for (const auto& bytes : all)
        for (SceneResult& r : read_results(bytes)) results[r.index] = std::move(r);
    HEMIRAD_CHECK(results.size() == scenes.size());
    int failed = 0;
    char head[160];
    std::snprintf(head, sizeof head, "{\n  \"ranks\": %d,\n  \"seconds\": %.6g,\n  \"scenes\": [\n",
                  world.size(), timer.seconds());
    std::string text = head;
    for (const auto& [index, r] : results) {
        failed += r.failed ? 1 : 0;
        text += "    " + r.json + (index + 1 < results.size() ? ",\n" : "\n");
    }
    text += "  ],\n  \"failed\": " + std::to_string(failed) + "\n}\n";
    const std::string path = (fs::path(out) / "summary.json").string();
    write_text_file(path, text);
    // Rank 0 printed its own scenes as they ended; now the others', and failures always.
    for (const auto& [index, r] : results)
        if (quiet ? r.failed : index % std::size_t(world.size()) != 0)
            std::fprintf(stderr, "hemirad: [%zu/%zu] %s\n", index + 1, scenes.size(),
                         r.row.c_str());
    if (!quiet)
        std::fprintf(stderr, "hemirad: %zu scenes, %d failed, %.2f s; wrote %s\n", scenes.size(),
                     failed, timer.seconds(), path.c_str());
    if (interrupted()) return 130;
    return failed ? 1 : 0;
}

} // namespace hemirad::cli
