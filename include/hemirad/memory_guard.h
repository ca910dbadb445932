// The memory guard: before the patch hierarchy is built, estimate the memory a solve needs
// and refuse (InputError naming the estimate, the memory available and the options to change)
// instead of being killed by the OS half-way through.
//
// The estimate counts what grows with the discretisation (the rest of a solve, a few MB plus
// the scene, is left out):
//   - hierarchy: 40 bytes a node (Hierarchy::Node) + 1 byte of view code (Solver);
//   - GPU providers: 20 bytes a node (pixel sum, analytic value, area, two visit stamps);
//   - GL: the patch-ID texture, 8 bytes a texel of a 2^D x 2^D texture and its mipmaps
//     (D = the deepest quadtree), the hemicube framebuffer, 2R x 1.5R pixels of RGBA32F
//     colour + 32-bit depth (R = --max-resolution, or --resolution), and its read-back copy
//     of 16 bytes a pixel in main memory. llvmpipe keeps GL memory in main memory too.
// A node count is sum over polygons of (4^(d+1) - 1)/3, d the polygon's depth (discretise()).
#pragma once

#include <cstdint>
#include <string>

#include "hemirad/form_factors.h"
#include "hemirad/scene.h"
#include "hemirad/visibility.h"

namespace hemirad {

struct SolverOptions;

struct MemoryEstimate {
    std::uint64_t nodes = 0, leaves = 0;
    int deepest = 0;             ///< deepest quadtree level of any polygon
    std::uint64_t hierarchy = 0; ///< node storage [bytes]
    std::uint64_t provider = 0;  ///< the form-factor provider's per-node storage and BVH [bytes]
    std::uint64_t gl = 0;        ///< GL textures, framebuffer and read-back [bytes]
    std::uint64_t total() const { return hierarchy + provider + gl; }
};

HEMIRAD_API MemoryEstimate estimate_memory(const Scene& scene, const Discretisation& disc,
                                           const SolverOptions& options);

/// Memory this process may still use [bytes]: /proc/meminfo MemAvailable, or the cgroup's
/// memory.max minus memory.current where that is lower (cgroup v2, then v1). `source` says
/// which ("MemAvailable", "cgroup limit"). 0 if neither can be read.
HEMIRAD_API std::uint64_t available_memory(std::string* source = nullptr);

/// Throws InputError if the estimate for `disc` exceeds options.memory_limit (0 =
/// available_memory()), naming the estimate and its parts, the limit and where it came from,
/// and the options to change: --max-depth (with the largest that would fit), --patch-size,
/// --max-resolution, --memory-limit.
HEMIRAD_API void check_memory(const Scene& scene, const Discretisation& disc,
                              const SolverOptions& options);

/// Parses a size for --memory-limit: bytes, or a number with K, M, G, T (powers of 1024; an
/// optional trailing B or iB), e.g. "512M", "1.5G". 0 means automatic. Throws InputError
/// naming `option` and the text.
HEMIRAD_API std::uint64_t parse_memory_size(const std::string& text, const std::string& option);

/// "1.5 GiB", "312 MiB", "12 KiB", "100 bytes".
HEMIRAD_API std::string bytes_text(std::uint64_t bytes);

} // namespace hemirad
