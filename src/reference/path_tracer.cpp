// The path-traced irradiance reference (reference.h).
//
// Notation, per RGB channel: x a point with unit normal n; w a direction; y(w) the first
// surface point the ray x + t w meets; P(y) its polygon, A_P its area, n_P its normal;
// theta_x, theta_y the angles at x and y; r = |y - x|. Radiance leaving the back of a
// polygon is 0; leaving the front, L(y) = Ke(y) + rho(y)/pi E(y).
//
//   E(x) = I_e(x) + I_r(x),
//   I_e(x) = integral Ke(y(w)) cos(theta_x) dw        (emitted radiance, front hits only)
//   I_r(x) = integral rho(y)/pi E(y) cos(theta_x) dw  (reflected radiance, front hits only)
//
// One sample of E(x) (one path vertex; the path continues at y):
//
// I_e by two techniques, combined with the balance heuristic (Veach 1997, eq. 9.10):
//  - light sampling: pick an emitter P with probability s_P (s_P = 1 for each emitter when
//    they are few and all are sampled; else s_P = power_P / sum of powers, one pick), a
//    point y uniform on P (area pdf 1/A_P). In solid angle at x the density is
//      p_l(w) = s_P r^2 / (A_P cos(theta_y)),
//  - cosine sampling of w: p_b(w) = cos(theta_x)/pi.
//    With f(w) = Ke cos(theta_x), each technique contributes f/p * p/(p_l + p_b), i.e.
//      Ke cos(theta_x) / (p_l + p_b)
//    for an unoccluded light sample with cos(theta_x) > 0 and cos(theta_y) > 0, and for a
//    cosine-sampled ray whose first hit is the front of an emitter. The weights of the two
//    techniques sum to 1 wherever f != 0, so the sum is unbiased; and each contribution is
//    at most pi Ke (p_l >= 0), so its variance is finite even at points next to an
//    emitter's edge, where plain light sampling (Ke cos cos / r^2 A_P) has infinite
//    variance: its second moment grows as 1/h^2 at distance h from the edge, and path
//    vertices land at every h.
//
// I_r by the same cosine-sampled ray: f/p_b = rho(y)/pi E(y) cos / (cos/pi) = rho(y) E(y),
// with E(y) estimated recursively by the same estimator (unbiased: the expectation of an
// unbiased estimate of E(y) given y is E(y)). Russian roulette: the path continues with
// probability q = min(1, max_c rho_c(y)) and is weighted by rho(y)/q, whose expectation is
// rho(y) (q > 0 when any channel reflects; q = 0 only where rho = 0, and the term is 0).
// Every channel of rho/q is <= 1, so the path's throughput beta (the product of rho/q)
// never grows, and a path ends after a geometric number of bounces (mean <= 1/(1 - rho_max)).
//
// Point luminaires (photometry.h) are delta lights: at every vertex each adds
// I(w) cos(theta_x) / (683 r^2) when the segment to it is unoccluded (next-event estimation
// only; no cosine ray can hit a point). The sun (sun.h) is a delta directional light: at every
// vertex it adds E_n/683 max(0, n.s) when the ray from x along s leaves the scene unblocked.
//
// The sky (sky.h) is seen by the cosine-sampled rays alone: a ray that leaves the scene from
// vertex k brings beta_k * pi L(w)/683 (f/p_b = L cos / (cos/pi)), L the sky's luminance above
// the horizon or the ground's below. Its luminance is evaluated here by the formulas written
// out again (ReferenceSky below) and normalised by another quadrature than the solver's (sky.cpp),
// from the sky's inputs only (model, E_h, ground reflectance, zenith, sun).
//
// A sample of E(x) is then sum over vertices k of beta_k * (the I_e terms at vertex k).
// max_bounces = m > 0 stops the path after m reflections (light reflected at most m times).
#include "hemirad/reference.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <numbers>
#include <optional>

#include "core/parallel.h"
#include "core/sampling.h"
#include "ff/bvh.h"
#include "hemirad/error.h"
#include "hemirad/readout.h"

namespace hemirad {

void validate_options(const ReferenceOptions& o) {
    if (o.samples < 1) throw InputError("--samples " + std::to_string(o.samples) + " must be >= 1");
    if (o.threads < 0)
        throw InputError("--threads " + std::to_string(o.threads) +
                         " must be >= 0 (0 = all cores)");
    if (o.max_bounces < 0)
        throw InputError("--max-bounces " + std::to_string(o.max_bounces) +
                         " must be >= 0 (0 = unlimited)");
}

namespace {

constexpr double kPi = std::numbers::pi;
/// Up to this many emitters, every vertex samples each of them (one point each); above it,
/// one emitter is picked by power.
constexpr std::size_t kSumAllEmitters = 8;
/// Ray origins leave a surface by this fraction of the scene diagonal along its normal.
constexpr double kOffset = 1e-9;

double max_channel(const dvec3& v) {
    return std::max({v.x, v.y, v.z});
}

/// The sky's luminance for the reference, from Sky's inputs only (not Sky::shape, scale).
/// Relative luminance in terms of the zenith angle Z and the angle chi from the sun:
///   overcast  (1 + 2 cos Z)/3 (CIE 1955, Moon & Spencer); uniform 1;
///   CIE S 011 type 12 (clear) and 7 (intermediate):
///     (1 + a e^(b / cos Z)) (1 + c (e^(d chi) - e^(d pi/2)) + e cos^2 chi).
/// With the horizon blend (Radiance's skybright.cal: wmean((cos Z + 1.01)^10, sky,
/// (cos Z + 1.01)^-10, ground)) on both sides of the horizon.
/// Normalised so that integral of L cos Z over the upper hemisphere is E_h, by the midpoint
/// rule in (Z, azimuth) with weight sin Z cos Z (sky.cpp uses the cosine-weighted square).
class ReferenceSky {
  public:
    explicit ReferenceSky(const Sky& sky)
        : model_(sky.model), up_(glm::normalize(sky.up)), sun_(glm::normalize(sky.sun)),
          blend_(sky.horizon_blend) {
        ground_ = sky.ground_reflectance * (sky.illuminance + sky.sun_horizontal) / kPi;
        // An orthonormal frame about the zenith for the quadrature.
        const dvec3 any = std::abs(up_.y) < 0.9 ? dvec3(0, 1, 0) : dvec3(1, 0, 0);
        const dvec3 e1 = glm::normalize(glm::cross(any, up_)), e2 = glm::cross(up_, e1);
        constexpr int kZ = 720, kA = 1440;
        const double dz = (kPi / 2) / kZ, da = 2 * kPi / kA;
        double integral = 0, ground = 0; // the sky's and the blended ground's parts
        for (int i = 0; i < kZ; ++i) {
            const double z = (i + 0.5) * dz;
            double ring = 0;
            for (int k = 0; k < kA; ++k) {
                const double a = (k + 0.5) * da;
                ring += relative(std::sin(z) * (std::cos(a) * e1 + std::sin(a) * e2) +
                                 std::cos(z) * up_);
            }
            const double weight = std::sin(z) * std::cos(z) * dz * da;
            integral += sky_share(std::cos(z)) * ring * weight;
            ground += (1 - sky_share(std::cos(z))) * kA * weight;
        }
        const double sky_part = sky.illuminance - ground_ * ground;
        scale_ = sky.illuminance > 0 && sky_part > 0 ? sky_part / integral : 0.0;
    }

    /// Luminance seen along unit w [cd m^-2].
    double luminance(const dvec3& w) const {
        const double cz = glm::dot(w, up_);
        if (!blend_) return cz > 0 ? scale_ * relative(w) : ground_;
        const double f = sky_share(cz);
        return f * scale_ * std::max(relative(w), 0.0) + (1 - f) * ground_;
    }

  private:
    /// wmean's weight of the sky: (c + 1.01)^10 / ((c + 1.01)^10 + (c + 1.01)^-10); 1 (above
    /// the horizon) without the blend.
    double sky_share(double cz) const {
        if (!blend_) return cz > 0 ? 1.0 : 0.0;
        const double up = std::pow(cz + 1.01, 10.0), down = std::pow(cz + 1.01, -10.0);
        return up / (up + down);
    }

    double relative(const dvec3& w) const {
        const double cz = glm::dot(w, up_);
        const double zenith_angle = std::acos(std::clamp(cz, -1.0, 1.0));
        if (model_ == SkyModel::Uniform) return 1.0;
        if (model_ == SkyModel::CieOvercast) return (1 + 2 * std::cos(zenith_angle)) / 3;
        const bool clear = model_ == SkyModel::CieClear;
        const double a = clear ? -1.0 : 0.0, b = clear ? -0.32 : -1.0, c = clear ? 10.0 : 5.0,
                     d = clear ? -3.0 : -2.5, e = clear ? 0.45 : 0.30;
        const double chi = std::atan2(glm::length(glm::cross(w, sun_)), glm::dot(w, sun_));
        const double gradation =
            zenith_angle < kPi / 2 ? 1 + a * std::exp(b / std::cos(zenith_angle)) : 1.0;
        return gradation * (1 + c * (std::exp(d * chi) - std::exp(d * kPi / 2)) +
                            e * std::pow(std::cos(chi), 2));
    }

    SkyModel model_;
    dvec3 up_, sun_;
    bool blend_ = true;
    double scale_ = 0, ground_ = 0;
};

class PathTracer {
  public:
    /// offset: how far ray origins leave a surface along its normal [unit].
    PathTracer(const Scene& scene, int max_bounces, double offset)
        : scene_(scene), bvh_(scene), max_bounces_(max_bounces), offset_(offset) {
        if (scene.sky) sky_.emplace(*scene.sky);
        select_.assign(scene.polygons.size(), 0.0);
        double total = 0;
        for (std::uint32_t i = 0; i < scene.polygons.size(); ++i) {
            const Polygon& p = scene.polygons[i];
            const dvec3 Ke = scene.material_of(p).Ke;
            // Power up to the constant pi; |Ke| so that any non-zero channel can be picked.
            const double w = p.area * (std::abs(Ke.x) + std::abs(Ke.y) + std::abs(Ke.z));
            if (!(w > 0)) continue;
            emitters_.push_back(i);
            total += w;
            cdf_.push_back(total);
            select_[i] = w;
        }
        sum_all_ = emitters_.size() <= kSumAllEmitters;
        for (const std::uint32_t i : emitters_) select_[i] = sum_all_ ? 1.0 : select_[i] / total;
    }

    /// One sample of E at x (unit normal n, on polygon `ignore` or kNoPolygon).
    dvec3 sample(dvec3 x, dvec3 n, std::uint32_t ignore, Rng& rng) const {
        dvec3 E(0.0), beta(1.0);
        for (int bounce = 0;; ++bounce) {
            E += beta * light_samples(x, n, ignore, rng);
            dvec3 t, b;
            orthonormal_basis(n, t, b);
            const double u1 = rng.uniform(), u2 = rng.uniform();
            const dvec3 w = cosine_direction(n, t, b, u1, u2);
            const double cos_x = glm::dot(n, w);
            if (!(cos_x > 0)) break; // measure zero: the tangent plane
            Hit hit;
            if (!bvh_.intersect(x, w, std::numeric_limits<double>::infinity(), hit, ignore)) {
                // Escaped: the sky or the ground, if any (pi L / 683 per unit of beta), through
                // the panes on the way.
                if (sky_)
                    E += beta * (kPi * sky_->luminance(w) / kLumensPerWatt) *
                         panes(x, w, std::numeric_limits<double>::infinity());
                break;
            }
            if (!hit.front) break; // a back: radiance 0, and it reflects nothing either
            beta *= panes(x, w, hit.t);
            if (!(max_channel(beta) > 0)) break;
            const Polygon& p = scene_.polygons[hit.polygon];
            const Material& m = scene_.material_of(p);
            const double s = select_[hit.polygon];
            if (s > 0) { // the cosine-sampling half of I_e
                const double cos_y = -glm::dot(p.normal, w);
                if (cos_y > 0) {
                    const double p_l = s * hit.t * hit.t / (p.area * cos_y);
                    E += beta * m.Ke * (cos_x / (p_l + cos_x / kPi));
                }
            }
            if (max_bounces_ > 0 && bounce + 1 > max_bounces_) break;
            const dvec3 rho = reflectance_at(scene_, hit.polygon, hit.u, hit.v); // the texel
            const double q = std::min(1.0, max_channel(rho));
            if (!(q > 0) || rng.uniform() >= q) break;
            beta *= rho / q;
            x = x + hit.t * w + offset_ * p.normal;
            n = p.normal;
            ignore = hit.polygon;
        }
        return E;
    }

  private:
    /// The light-sampling half of I_e at x: sum over the sampled emitters of
    /// Ke cos(theta_x) / (p_l + p_b) for unoccluded points facing x.
    dvec3 light_samples(const dvec3& x, const dvec3& n, std::uint32_t ignore, Rng& rng) const {
        dvec3 sum = point_lights(x, n, ignore, rng);
        if (emitters_.empty()) return sum;
        if (sum_all_) {
            for (const std::uint32_t e : emitters_) sum += light_sample(x, n, ignore, e, rng);
            return sum;
        }
        const double u = rng.uniform() * cdf_.back();
        const std::size_t k = std::min<std::size_t>(
            std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin(), cdf_.size() - 1);
        return sum + light_sample(x, n, ignore, emitters_[k], rng);
    }

    /// Point luminaires (delta lights: no ray can hit one, so light sampling is their only
    /// technique, weight 1): sum over all of I(w) cos(theta_x) / (683 r^2) if unoccluded.
    /// A luminaire with a luminous opening (LuminousOpening) is, within five times its size,
    /// an area source: the light comes from a uniformly random point of the opening.
    dvec3 point_lights(const dvec3& x, const dvec3& n, std::uint32_t ignore, Rng& rng) const {
        double e = 0;
        for (const Luminaire& l : scene_.luminaires) {
            dvec3 y = l.position;
            if (const double size = l.opening.size();
                size > 0 && glm::length(x - l.position) < 5 * size)
                y += opening_point(l, rng);
            const double el = l.irradiance_from(y, x, n);
            if (el > 0 && !bvh_.occluded(x, y, ignore, kNoPolygon)) e += el * panes(x, y - x, 1.0);
        }
        return dvec3(e + sun(x, n, ignore));
    }

    /// A uniformly random point of l's opening, relative to its position: the rectangle
    /// length x width along c0, c90, or the disc of diameter length (by rejection).
    static dvec3 opening_point(const Luminaire& l, Rng& rng) {
        const LuminousOpening& o = l.opening;
        for (;;) {
            const double a = rng.uniform() - 0.5, b = rng.uniform() - 0.5;
            if (o.round && a * a + b * b > 0.25) continue;
            return a * o.length * l.c0 + b * (o.round ? o.length : o.width) * l.c90;
        }
    }

    /// The sun, a delta directional light: E_n/683 (n.s) if the ray x + t s (t > 0) meets
    /// nothing.
    double sun(const dvec3& x, const dvec3& n, std::uint32_t ignore) const {
        if (!scene_.sun || !(scene_.sun->illuminance > 0) || !(scene_.sun->altitude_deg > 0))
            return 0;
        const dvec3 s = scene_.sun->direction;
        const double cos_x = glm::dot(n, s);
        if (!(cos_x > 0)) return 0;
        Hit hit;
        if (bvh_.intersect(x, s, std::numeric_limits<double>::infinity(), hit, ignore)) return 0;
        return scene_.sun->illuminance / kLumensPerWatt * cos_x *
               panes(x, s, std::numeric_limits<double>::infinity());
    }

    dvec3 light_sample(const dvec3& x, const dvec3& n, std::uint32_t ignore, std::uint32_t e,
                       Rng& rng) const {
        const double pick = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
        // A polygon sees nothing of itself (planar); nor does the cosine ray (ignored).
        if (e == ignore) return dvec3(0.0);
        const Polygon& p = scene_.polygons[e];
        const dvec3 y = area_point(p.v.data(), p.count, pick, u1, u2);
        const dvec3 d = y - x;
        const double r2 = glm::dot(d, d);
        if (!(r2 > 0)) return dvec3(0.0);
        const dvec3 w = d / std::sqrt(r2);
        const double cos_x = glm::dot(n, w), cos_y = -glm::dot(p.normal, w);
        if (!(cos_x > 0 && cos_y > 0)) return dvec3(0.0);
        if (bvh_.occluded(x, y, ignore, e)) return dvec3(0.0);
        const double p_l = select_[e] * r2 / (p.area * cos_y);
        return scene_.material_of(p).Ke * (cos_x / (p_l + cos_x / kPi)) * panes(x, d, 1.0);
    }

    /// What the window panes (Scene::glazing) let through along x + t d, t in (0, t_max): the
    /// product of the transmittances of those the ray crosses. Its own test, pane by pane (the
    /// solver's goes through a BVH, ff/glazing_tracer.h): the crossing of each pane's plane,
    /// inside every edge.
    double panes(const dvec3& x, const dvec3& d, double t_max) const {
        double T = 1;
        const double length = glm::length(d);
        for (const GlazingPane& pane : scene_.glazing) {
            const Polygon& p = pane.polygon;
            const double dn = glm::dot(d, p.normal);
            if (dn == 0) continue;
            const double t = glm::dot(p.v[0] - x, p.normal) / dn;
            if (!(t > 1e-9 && t < t_max * (1 - 1e-7))) continue;
            const dvec3 y = x + t * d;
            bool inside = true;
            for (int k = 0; k < p.count && inside; ++k) {
                const dvec3& a = p.v[k];
                const dvec3& b = p.v[(k + 1) % p.count];
                inside = glm::dot(glm::cross(b - a, y - a), p.normal) >= 0;
            }
            if (inside) T *= pane.transmittance.at(dn / length);
        }
        return T;
    }

    const Scene& scene_;
    Bvh bvh_;
    int max_bounces_;
    double offset_;                       ///< [unit]
    std::vector<std::uint32_t> emitters_; ///< polygons with Ke != 0
    std::vector<double> cdf_;             ///< running sums of emitters' power weights
    std::vector<double> select_;          ///< per polygon: s_P (0 for non-emitters)
    bool sum_all_ = true;
    std::optional<ReferenceSky> sky_; ///< the scene's sky, if any
};

// Throws InputError for a probe the estimator cannot place (checked before any thread starts:
// an exception must not leave a worker).
void check_probes(const std::vector<Probe>& probes) {
    for (std::size_t i = 0; i < probes.size(); ++i) {
        const Probe& p = probes[i];
        const double length = glm::length(p.normal);
        if (!(length > 0 && std::isfinite(length)) ||
            !std::isfinite(glm::dot(p.position, p.position)))
            throw InputError("probe " + std::to_string(i) +
                             ": the position and normal must be finite and the normal non-zero");
    }
}

ReferenceValue estimate(const PathTracer& tracer, const Scene& scene, double offset,
                        const Probe& probe, std::size_t index, const ReferenceOptions& o) {
    ReferenceValue r;
    dvec3 x = probe.position, n = glm::normalize(probe.normal);
    std::uint32_t ignore = kNoPolygon;
    if (const auto sp = find_surface(scene, probe.position, probe.normal)) {
        // On a surface: that surface's irradiance at the projection of the probe, `offset`
        // above it.
        const Polygon& p = scene.polygons[sp->polygon];
        n = p.normal;
        x = probe.position - glm::dot(probe.position - p.v[0], n) * n + offset * n;
        ignore = sp->polygon;
        r.on_surface = true;
        r.polygon = sp->polygon;
    }
    Rng rng(splitmix64(o.seed ^ splitmix64(std::uint64_t(index))));
    // Welford's running mean and sum of squared deviations, per channel.
    dvec3 mean(0.0), m2(0.0);
    for (long k = 1; k <= o.samples; ++k) {
        const dvec3 s = tracer.sample(x, n, ignore, rng);
        const dvec3 delta = s - mean;
        mean += delta / double(k);
        m2 += delta * (s - mean);
    }
    r.E = mean;
    const double N = double(o.samples);
    r.sem = o.samples > 1 ? glm::sqrt(m2 / ((N - 1) * N))
                          : dvec3(std::numeric_limits<double>::quiet_NaN());
    return r;
}

} // namespace

std::vector<ReferenceValue> reference_irradiance(const Scene& scene,
                                                 const std::vector<Probe>& probes,
                                                 const ReferenceOptions& options,
                                                 const ReferenceProgress& progress) {
    validate_options(options);
    check_probes(probes);
    std::vector<ReferenceValue> values(probes.size());
    if (probes.empty()) return values;
    const double offset = kOffset * scene.bounds().diagonal();
    const PathTracer tracer(scene, options.max_bounces, offset);
    std::mutex progress_mutex;
    std::size_t done = 0;
    parallel_for(probes.size(), options.threads, [&](std::size_t i) {
        values[i] = estimate(tracer, scene, offset, probes[i], i, options);
        std::lock_guard lock(progress_mutex);
        ++done;
        if (progress) progress(done, probes.size());
    });
    return values;
}

double median_relative_sem(const std::vector<ReferenceValue>& values) {
    std::vector<double> rel;
    for (const ReferenceValue& v : values) {
        double worst = -1;
        bool nan = false;
        for (int c = 0; c < 3; ++c) {
            if (std::isnan(v.sem[c])) nan = true;
            if (v.E[c] > 0) worst = std::max(worst, v.sem[c] / v.E[c]);
        }
        if (!nan && worst >= 0) rel.push_back(worst);
    }
    if (rel.empty()) return 0;
    const std::size_t mid = rel.size() / 2;
    std::nth_element(rel.begin(), rel.begin() + mid, rel.end());
    if (rel.size() % 2) return rel[mid];
    const double upper = rel[mid];
    return 0.5 * (upper + *std::max_element(rel.begin(), rel.begin() + mid));
}

} // namespace hemirad
