// Choosing a form-factor provider by name: CPU references (reference, pdm, sr) or the GPU
// hemicube (hemicube, analytic, hybrid).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "hemirad/form_factors.h"
#include "hemirad/scene.h"
#include "hemirad/visibility.h"

namespace hemirad {

/// Options of the GPU hemicube provider (paper 002 §2-§3).
struct GpuProviderOptions {
    int resolution = 0; ///< fixed hemicube resolution (pixels per full face side); 0 = adaptive
    int min_resolution = 64;  ///< adaptive: resolution for the weakest shooters (16..4096)
    int max_resolution = 256; ///< adaptive: resolution for the strongest shooters (16..4096)
    /// Added to the mip level GL chooses (+1 = patches 2x larger). 0.5 makes every linked
    /// patch cover at least about a pixel, so that none falls between pixel centres (at 0,
    /// rows of a closed furnace summed to 0.979 on average; at 0.5, to 0.9998).
    double lod_bias = 0.5;
    bool builtin_acos = false;    ///< use GLSL acos instead of the 2048-entry lookup table
    bool atan_angle = false;      ///< use GLSL atan(|a x b|, a.b) (most precise); wins over both
    std::string backend = "auto"; ///< GL context backend: auto, egl, osmesa
    bool use_current_context = false; ///< render in the caller's current GL context (viewer)
    int device = -1;                  ///< EGL device index (-1 = default)
};

struct ProviderOptions {
    CpuProviderOptions cpu;
    GpuProviderOptions gpu;
};

/// "reference", "pdm", "sr", "hemicube", "analytic", "hybrid". Unknown → InputError.
HEMIRAD_API std::unique_ptr<FormFactorProvider> make_provider(const std::string& name,
                                                              const Scene& scene,
                                                              const Discretisation& disc,
                                                              const ProviderOptions& options);
HEMIRAD_API const char* provider_names();
/// Checks the GPU options a user can get wrong (resolutions, LOD bias): InputError naming the
/// option. validate_options() calls it for the GPU providers, before the memory guard.
HEMIRAD_API void validate_gpu_options(const GpuProviderOptions& options);
HEMIRAD_API bool is_gpu_provider(const std::string& name);

} // namespace hemirad

namespace hemirad {

/// Form factors from one surface group to every group (paper 000's experiment): shoots from
/// every leaf patch of every polygon of `group` and sums, by reciprocity,
/// F(G -> H) = sum over shooters s in G, receivers j in H of A_j F(j -> s) / A_G.
struct GroupFormFactors {
    std::vector<double> to; ///< per group of the scene
    double row_sum = 0;     ///< sum of `to` (1 in a closed scene)
    double seconds = 0;
    long shots = 0;
};
HEMIRAD_API GroupFormFactors group_form_factors(const Scene& scene, const Discretisation& disc,
                                                FormFactorProvider& provider, std::uint32_t group);

} // namespace hemirad
