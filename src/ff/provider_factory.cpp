// make_provider: the one place that maps a method name to a provider.
#include "hemirad/provider.h"

#include "hemirad/error.h"

namespace hemirad {

// Defined in src/gpu/ (the GPU hemicube provider).
std::unique_ptr<FormFactorProvider> make_hemicube_provider(const std::string& mode,
                                                           const Scene& scene,
                                                           const Discretisation& disc,
                                                           const GpuProviderOptions& options);

const char* provider_names() {
    return "hybrid, analytic, hemicube, reference, pdm, sr";
}

bool is_gpu_provider(const std::string& name) {
    return name == "hybrid" || name == "analytic" || name == "hemicube";
}

std::unique_ptr<FormFactorProvider> make_provider(const std::string& name, const Scene& scene,
                                                  const Discretisation& disc,
                                                  const ProviderOptions& options) {
    if (is_gpu_provider(name)) return make_hemicube_provider(name, scene, disc, options.gpu);
    if (name == "reference" || name == "pdm" || name == "sr")
        return make_cpu_provider(name, scene, disc, options.cpu);
    throw InputError("unknown form-factor method '" + name +
                     "' (expected one of: " + provider_names() + ")");
}

} // namespace hemirad
