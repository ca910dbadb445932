// Saving and resuming a solve (`hemirad solve --save-solution FILE`, `--resume FILE`).
//
// A solution file holds the complete solver state (Solver::State), so that a resumed run ends
// with results bit-identical to a run that was never interrupted (same scene, options and
// backend). It is binary, little-endian, written atomically, and laid out as:
//
//     offset  size  field
//     0       8     magic "HEMIRAD\x1a"
//     8       4     u32 format version (kSolutionFileVersion)
//     12      8     u64 scene content hash (Scene::content_hash())
//     20      ...   str scene source (as given: path or builtin:NAME), for messages
//             ...   u32 option count, then (str name, str value) per option: the options that
//                   affect results (solution_options()), named as on the command line, values
//                   as text (doubles in hexadecimal, exact)
//             ...   counters: i64 shots, f64[3] absorbed, f64[3] escaped, f64 row_min,
//                   f64 row_max, f64 row_total, i64 row_guarded, i64 last_polygon, f64 seconds
//             ...   u32 polygon count P, u64 node count N
//             N*36  per node (Hierarchy order): f32[3] H, f32[3] dB, f32[3] dI
//             P*25  per polygon: f64[3] unshot power, u8 dirty
//             N     per node: u8 view code (solver.cpp; versions 1 and 2 coded the parallax
//                   16 steps to an octave, converted when read)
//             ...   u32 count, then f64 per value: provider state (FormFactorProvider)
//             ...   u32 luminaire count L, then L*24: f64[3] unshot power per luminaire
//                   (version 2; version 1 files, without it, are read as L = 0)
//             ...   u64 cluster count C, then C*1: u8 view code per cluster-tree node,
//                   f64 landed power, f64 shot power (Solver::Counters; version 3: older
//                   files are read as C = 0 and no power shot)
//             8     u64 geometry hash (Scene::geometry_hash(); version 4)
//             P*48  per polygon: f64[3] reflectance, f64[3] emitted radiosity (version 4)
//             ...   u32 luminaire count L, then L*24: f64[3] power per luminaire (version 4)
//
// Version 4 keeps the geometry apart from the photometry (scene_edit.h): a solution resumes
// for a scene of the same geometry whose materials' reflectance or emission or luminaires'
// multipliers differ, and re-converges from it (incremental re-solving, solver.h).
//             ...   u32 light layer count K (0: none), then per layer (a luminaire's share of
//                   the solution, light_layers.h; version 5): N*36 nodes as above, P*25
//                   polygons as above, f64[3] absorbed, f64[3] escaped power
//
// Version 5's layers let a luminaire's multiplier change on resume with no shot.
//     end-8   8     u64 FNV-1a 64 hash of every byte before it (detects corruption)
//
// (str = u32 byte length + bytes.) A file that is truncated, corrupt, of another version or
// inconsistent is refused with an InputError naming it; reading never crashes.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "hemirad/scene_edit.h"
#include "hemirad/solver.h"
#include "hemirad/visibility.h"

namespace hemirad {

inline constexpr std::uint32_t kSolutionFileVersion = 5;

/// An option that affects results, as (command-line name, exact value text).
using SolutionOption = std::pair<std::string, std::string>;

/// The options of `o` that affect results, in the order of the options table
/// (solver_options.h): those whose SolverOption::saved is true, named as on the command line,
/// values as SolverOption::text() writes them. Not included, so free to change on resume: the
/// stop criteria (--tolerance, --max-shots, --time-limit), --memory-limit, and where the solve
/// runs (--backend, --device).
HEMIRAD_API std::vector<SolutionOption> solution_options(const SolverOptions& o);
/// Sets the option `name` of `o` from its saved text. Throws InputError for an unknown name
/// or a malformed value (`file` names the solution file in the message).
HEMIRAD_API void apply_solution_option(SolverOptions& o, const SolutionOption& option,
                                       const std::string& file);

struct SolutionFile {
    std::uint64_t scene_hash = 0;
    std::string scene_source;
    std::vector<SolutionOption> options;
    Solver::State state;
    /// Version 4 and later: the geometry hash and the photometry the state was computed for.
    bool has_photometry = false;
    std::uint64_t geometry_hash = 0;
    Photometry photometry;
};

/// The bytes of a solution file for the solver's current state (call between steps, before
/// Solver::solution()).
HEMIRAD_API std::string solution_bytes(const Solver& solver);
/// Writes solution_bytes() to `path` atomically. Throws RuntimeError naming the path.
HEMIRAD_API void save_solution(const std::string& path, const Solver& solver);

/// Parses solution-file bytes; `path` names the file in messages. Throws InputError.
HEMIRAD_API SolutionFile parse_solution(const std::string& bytes, const std::string& path);
/// Reads and parses a solution file. Throws InputError (missing, truncated, corrupt).
HEMIRAD_API SolutionFile read_solution(const std::string& path);

/// Checks that `file` (read from `path`) was saved for `scene` (loaded from `scene_path`), or,
/// for a version 4 file, for a scene of the same geometry (Scene::geometry_hash(): its
/// photometry may differ): throws InputError naming both files and both hashes if not.
HEMIRAD_API void check_solution_scene(const SolutionFile& file, const std::string& path,
                                      const Scene& scene, const std::string& scene_path);

/// What resume_solution() found edited: luminaires and polygons whose photometry differs from
/// the saved one (Solver::apply_photometry()); none for a resume of the same scene.
struct ResumeEdits {
    std::size_t luminaires = 0, polygons = 0;
    /// Of the luminaires changed, how many were applied exactly by rescaling their light layer
    /// (light_layers.h: no shot needed); the rest are shot.
    std::size_t rescaled = 0;
    bool any() const { return luminaires + polygons > 0; }
};
/// Restores the solver's state from `file` (read from `path`); the solver must have been built
/// for the same scene, or one of the same geometry (check_solution_scene()), and with the
/// saved options. Where the scene's photometry differs from the saved one, the differences
/// become unshot power and further steps re-converge. Throws InputError naming `path`.
HEMIRAD_API ResumeEdits resume_solution(Solver& solver, const SolutionFile& file,
                                        const std::string& path);

} // namespace hemirad
