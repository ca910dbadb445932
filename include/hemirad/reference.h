// An independent, unbiased CPU Monte-Carlo estimate of irradiance at points: the yardstick
// against which the radiosity solver's accuracy is measured. It shares nothing with the
// solver but the scene and the ray caster (no form factors, no hierarchy).
//
// The physics is hemirad's model (scene.h): planar one-sided Lambertian polygons; a ray that
// reaches the back of a polygon finds radiance 0 (backs absorb everything and emit nothing);
// emitters emit from the front only. Per RGB channel, with Be = pi*Ke the emitted exitance,
//
//   E(x) = integral over the hemisphere of n(x) of L_in(w) cos(theta) dw     [W unit^-2]
//   L(y) = Ke(y) + rho(y)/pi * E(y)   leaving the front of a polygon at y    [W sr^-1 unit^-2]
//
// so E satisfies E(x) = E_direct(x) + integral rho(y)/pi E(y) cos(theta) dw: every bounce is
// counted (no truncation unless max_bounces asks for it). The estimator is a path tracer
// with next-event estimation and multiple importance sampling (Veach 1997, ch. 9, the
// balance heuristic, eq. 9.10) of the emitted part, and Russian roulette; point luminaires
// (photometry.h) and the sun (sun.h) by next-event estimation at every vertex; the sky (sky.h)
// by the cosine-sampled rays that leave the scene, its luminance evaluated by the tracer's own
// code; path_tracer.cpp writes out the maths.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "hemirad/report.h"
#include "hemirad/scene.h"
#include "hemirad/visibility.h"

namespace hemirad {

struct ReferenceOptions {
    /// Independent paths per point, >= 1 (a standard error needs >= 2); typical 1024..65536.
    long samples = 1024;
    std::uint64_t seed = 1; ///< point i draws from Rng(splitmix64(seed ^ splitmix64(i)))
    int threads = 0;        ///< worker threads, >= 0; 0 = all cores (hardware_concurrency)
    /// Most reflections a path may make before it reaches the point, >= 0. 0 = unlimited
    /// (paths end by Russian roulette only: unbiased). k > 0 gives the irradiance of light
    /// reflected at most k times (k = 1: direct + one bounce), a biased truncation.
    int max_bounces = 0;
};

/// Throws InputError naming the command-line option (--samples, --threads, --max-bounces)
/// and the value when an option is out of range.
HEMIRAD_API void validate_options(const ReferenceOptions& options);

struct ReferenceValue {
    dvec3 E{0.0}; ///< irradiance, mean over the samples, per channel [W unit^-2]
    /// Standard error of that mean per channel [W unit^-2]: sample standard deviation /
    /// sqrt(samples). The samples are independent, so this is an honest error estimate; NaN
    /// when samples = 1.
    dvec3 sem{0.0};
    /// The probe lies on a polygon (readout.h find_surface): E is then that polygon's
    /// irradiance at the probe's projection onto its plane, about the polygon's normal (the
    /// quantity the solver reports there), whatever the probe's own normal. Otherwise E is
    /// the irradiance at the probe's position about its (normalised) normal, in free space.
    bool on_surface = false;
    std::uint32_t polygon = 0; ///< the polygon the probe lies on; meaningful if on_surface
};

/// Called after each point is done with (points done, points in all); from the worker
/// threads, but never concurrently (calls are serialised). Must not throw. May be empty.
using ReferenceProgress = std::function<void(std::size_t done, std::size_t total)>;

/// Irradiance at every probe, each an independent Monte-Carlo estimate. The result for a
/// point depends only on (seed, its index, samples, max_bounces), not on the thread count.
/// Validates the options first (validate_options). Probes' normals need not be unit length;
/// a probe with a zero or non-finite normal or position throws InputError naming its index.
HEMIRAD_API std::vector<ReferenceValue>
reference_irradiance(const Scene& scene, const std::vector<Probe>& probes,
                     const ReferenceOptions& options, const ReferenceProgress& progress = {});

/// CSV with the columns of `hemirad solve --probe-out` (report.h probes_csv) and three more:
/// x,y,z,nx,ny,nz,E_r,E_g,E_b,polygon,group,sem_r,sem_g,sem_b. A probe on no surface has its
/// free-space E and sem, an empty polygon column and "none" as its group.
HEMIRAD_API std::string reference_csv(const Scene& scene, const std::vector<Probe>& probes,
                                      const std::vector<ReferenceValue>& values);

/// Median over the points of the largest relative standard error of a channel,
/// max_c sem_c / E_c over channels with E_c > 0 (points with no such channel, or with NaN
/// sem, are left out). 0 when no point counts.
HEMIRAD_API double median_relative_sem(const std::vector<ReferenceValue>& values);

} // namespace hemirad
