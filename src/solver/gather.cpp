// Final gather at points (gather.h).
#include "hemirad/gather.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "core/parallel.h"
#include "core/sampling.h"
#include "ff/bvh.h"
#include "ff/glazing_tracer.h"
#include "hemirad/error.h"
#include "hemirad/form_factors.h"
#include "hemirad/readout.h"
#include "solver/bright_leaves.h"
#include "solver/sky_light.h"
#include "solver/sun_light.h"

namespace hemirad {

namespace {

constexpr int kPenumbraSplit = 2; ///< a penumbra cell is re-sampled 4^2 = 16 times finer
constexpr int kMaxCellLevel = 3;  ///< at most 8 x 8 coarse cells, 32 x 32 fine ones
/// An indirect ray's first hit, and a later one nearer than this many leaf sizes, is not read
/// from the solution: the path goes on from it (the direct light sampled there, one more
/// cosine ray)...
constexpr double kTracedLeaves = 30;
/// ...for this many bounces, and past them by Russian roulette (kept with the hit's largest
/// reflectance, weighted by its inverse), for at most kMaxTracedBounces. From the second
/// bounce: the paths' weights never grow, and a path costs about what it did when half of
/// them ended at each hit (onward()); from the 8th, the office glb's 1000 points took 55-65 s
/// against 44-51 s (about 25 % longer).
constexpr int kTracedBounces = 2;
constexpr int kMaxTracedBounces = 256;
/// A noisy point is gathered again with at most 4 x 4 = 16 times the rays, and at most this
/// many ray casts for each first-pass ray (16 times the two casts of a ray with one bounce).
constexpr int kMaxRegatherSide = 4;
constexpr double kRegatherCasts = 32;
/// A point nearer a luminaire than this many times its luminous opening's size takes its light
/// from points spread over the opening (luminous_opening), at most kMaxOpeningSide a side.
constexpr double kOpeningSizes = 5;
constexpr int kMaxOpeningSide = 16;
/// A traced path's hit casts about this many shadow rays to emitter polygons (those that hold
/// a share of 1 / kEmitterRays of their light or more, and others by Russian roulette).
constexpr double kEmitterRays = 8;
/// The indirect rays sample at most this many bright leaves (bright_leaves.h), the brightest.
constexpr std::size_t kMaxBrightLeaves = std::size_t(1) << 16;

bool nonzero(const dvec3& v) {
    return v.x > 0 || v.y > 0 || v.z > 0;
}

/// The density per solid angle at x of a bright-leaf sample (BrightLeaves::Sample::density,
/// per unit area) at distance r from x, seen at cos_y from its polygon's normal.
double per_solid_angle(double density, double r, double cos_y) {
    return density * r * r / std::max(cos_y, 1e-12);
}

/// The balance heuristic's weight (Veach & Guibas 1995) of a direction at cos_x from the
/// normal at x that the bright leaves draw with density p_bright per solid angle: a cosine
/// ray draws it with cos_x / pi.
double balance(double cos_x, double p_bright) {
    const double p_cos = cos_x / std::numbers::pi;
    return p_cos / (p_cos + p_bright);
}

} // namespace

void validate_gather_options(const GatherOptions& o) {
    if (o.rays < 16 || o.rays > 65536)
        throw InputError("--gather-rays " + std::to_string(o.rays) + " must be in 16..65536");
    if (!(o.emitter_angle > 0 && o.emitter_angle <= 1))
        throw InputError("--gather-angle " + num(o.emitter_angle) + " must be in (0, 1]");
    if (!(o.indirect_error >= 0 && o.indirect_error < 1))
        throw InputError("--gather-error " + num(o.indirect_error) + " must be in [0, 1)");
    if (o.sky_cells < 4 || o.sky_cells > 256 || o.sky_split < 1 || o.sky_split > 32)
        throw InputError("gather sky cells " + std::to_string(o.sky_cells) + " and split " +
                         std::to_string(o.sky_split) + " must be in 4..256 and 1..32");
    if (!(o.bright_factor == 0 || (o.bright_factor >= 1 && o.bright_factor <= 1e6)))
        throw InputError("--gather-bright " + num(o.bright_factor) + " must be 0 or in [1, 1e6]");
    if (o.threads < 0)
        throw InputError("gather threads " + std::to_string(o.threads) + " must be >= 0");
}

FinalGather::FinalGather(const Hierarchy& h, const GatherOptions& options)
    : h_(&h), options_(options), bvh_(std::make_unique<Bvh>(h.scene())),
      glazing_(std::make_unique<GlazingTracer>(h.scene())) {
    validate_gather_options(options_);
    const Scene& scene = h.scene();
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p)
        if (nonzero(scene.material_of(scene.polygons[p]).exitance())) emitters_.push_back(p);
    bounds_ = scene.bounds();
    offset_ = 1e-9 * bounds_.diagonal();
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p)
        leaf_size_.push_back(std::sqrt(scene.polygons[p].area) / double(1u << h.depth(p)));
    bright_ = std::make_unique<BrightLeaves>(h, options_.bright_factor, kMaxBrightLeaves);
}

FinalGather::~FinalGather() = default;

dvec3 FinalGather::direct(const dvec3& x, const dvec3& n, std::uint32_t self,
                          std::uint64_t seed) const {
    const Scene& scene = h_->scene();
    Rng rng(seed);
    dvec3 E(0.0);
    for (std::uint32_t e : emitters_) {
        if (e == self) continue;
        const Polygon& P = scene.polygons[e];
        if (glm::dot(P.normal, x - P.v[0]) <= 0) continue; // x is behind the emitter
        const double F = point_to_polygon_ff(x, n, P.v.data(), P.count);
        if (F <= 0) continue;
        // Cells no wider than emitter_angle as seen from the nearest corner's distance.
        double near = 1e300;
        for (int k = 0; k < P.count; ++k) near = std::min(near, glm::length(P.v[k] - x));
        near = std::max(near, 1e-12);
        const double cells = std::sqrt(P.area) / (near * options_.emitter_angle);
        // Bounded: a point right beside an emitter would otherwise ask for millions of cells.
        const int level =
            std::clamp(int(std::ceil(std::log2(std::max(cells, 1.0)))), 0, kMaxCellLevel);
        const std::uint32_t count = 1u << (2 * level);
        // What of a cell reaches x: 0 when occluded, else the panes' transmittance (1 without).
        const auto visible = [&](const PatchGeometry& g) {
            dvec3 y = g.centre;
            if (options_.jitter) {
                const double pick = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
                y = area_point(g.corners.data(), g.count, pick, u1, u2);
            }
            return bvh_->occluded(lifted(x, n), y, self, e) ? 0.0 : glazing_->between(x, y);
        };
        std::uint32_t seen = 1; // without the coarse test: "some visible", go fine
        bool clear = false;     // every coarse cell seen whole (no pane between)
        if (options_.coarse_test) {
            seen = 0;
            clear = true;
            for (std::uint32_t c = 0; c < count; ++c) {
                const double v = visible(patch_geometry(P, std::uint32_t(level), c));
                seen += v > 0 ? 1 : 0;
                clear = clear && v == 1.0;
            }
        }
        double f = 0;
        if (seen == count && clear) {
            f = F;
        } else if (seen > 0) {
            // Penumbra: sum over fine cells of F(dx -> cell) * (one jittered ray's visibility).
            const std::uint32_t fine_level = std::uint32_t(level + kPenumbraSplit);
            const std::uint32_t fine = 1u << (2 * fine_level);
            for (std::uint32_t c = 0; c < fine; ++c) {
                const PatchGeometry g = patch_geometry(P, fine_level, c);
                const double fc = point_to_polygon_ff(x, n, g.corners.data(), g.count);
                if (fc > 0) f += fc * visible(g);
            }
        }
        E += f * scene.material_of(P).exitance();
    }
    return E + luminaires(x, n, self);
}

// Point luminaires and the sun: delta lights, one shadow ray each.
dvec3 FinalGather::luminaires(const dvec3& x, const dvec3& n, std::uint32_t self) const {
    double e = 0;
    for (const Luminaire& l : h_->scene().luminaires) {
        const double size = l.opening.size();
        const double r = glm::length(x - l.position);
        if (size > 0 && r < kOpeningSizes * size) {
            e += luminous_opening(l, x, n, self, r);
            continue;
        }
        const double el = l.irradiance(x, n);
        if (el > 0 && !bvh_->occluded(lifted(x, n), l.position, self, kNoPolygon))
            e += el * glazing_->between(x, l.position);
    }
    return dvec3(e) + sun_irradiance(h_->scene(), *bvh_, x, n, self, offset_, glazing_.get());
}

double FinalGather::luminous_opening(const Luminaire& l, const dvec3& x, const dvec3& n,
                                     std::uint32_t self, double r) const {
    // Points no farther apart than an eighth of the distance (4 to 16 a side): each stands
    // for its share of the luminaire, I(d) / count from where it lies.
    const int per_side =
        std::clamp(int(std::ceil(8 * l.opening.size() / std::max(r, 1e-9))), 4, kMaxOpeningSide);
    const std::vector<dvec3> points = l.opening.points(l.c0, l.c90, per_side);
    double e = 0;
    for (const dvec3& offset : points) {
        const dvec3 y = l.position + offset;
        const double el = l.irradiance_from(y, x, n);
        if (el > 0 && !bvh_->occluded(lifted(x, n), y, self, kNoPolygon))
            e += el * glazing_->between(x, y);
    }
    return e / double(points.size());
}

dvec3 FinalGather::direct_sample(const dvec3& y, const dvec3& n, std::uint32_t self,
                                 Rng& rng) const {
    // One shadow ray to a random point of each emitter polygon that holds a fair share
    // (1 / kEmitterRays) of the unoccluded light w = F * (M.r + M.g + M.b); the others by
    // Russian roulette, kept with probability w * kEmitterRays / W (W the sum of every w) and
    // then weighted by its inverse. Unbiased, at most about kEmitterRays shadow rays.
    struct Seen {
        std::uint32_t polygon;
        double F, w;
    };
    static thread_local std::vector<Seen> seen;
    seen.clear();
    const Scene& scene = h_->scene();
    double total = 0;
    for (std::uint32_t e : emitters_) {
        if (e == self) continue;
        const Polygon& P = scene.polygons[e];
        if (glm::dot(P.normal, y - P.v[0]) <= 0) continue;
        const double F = point_to_polygon_ff(y, n, P.v.data(), P.count);
        const dvec3 M = scene.material_of(P).exitance();
        const double w = F * (M.x + M.y + M.z);
        if (!(w > 0)) continue;
        total += w;
        seen.push_back({e, F, w});
    }
    dvec3 E(0.0);
    for (const Seen& s : seen) {
        const double keep = std::min(1.0, s.w * kEmitterRays / total);
        if (keep < 1 && rng.uniform() >= keep) continue;
        const Polygon& P = scene.polygons[s.polygon];
        const double pick = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
        const dvec3 z = area_point(P.v.data(), P.count, pick, u1, u2);
        if (bvh_->occluded(lifted(y, n), z, self, s.polygon)) continue;
        E += s.F / keep * glazing_->between(y, z) * scene.material_of(P).exitance();
    }
    return E + luminaires(y, n, self);
}

dvec3 FinalGather::reflected(const dvec3& origin, const dvec3& dir, std::uint32_t self, Rng& rng,
                             int bounce, std::uint64_t& casts, FirstHit* first) const {
    const Scene& scene = h_->scene();
    Hit hit;
    ++casts;
    if (!bvh_->intersect(origin, dir, 1e300, hit, self)) {
        // Escaped: the sky (or the ground) for the rays of a traced path past its first hit;
        // the first rays' sky is the direct part (at()), gathered apart.
        if (bounce == 0 || !scene.sky) return dvec3(0.0);
        return dvec3(std::numbers::pi * scene.sky->radiance(glm::normalize(dir)) *
                     glazing_->along(origin, dir, std::numeric_limits<double>::infinity()));
    }
    if (first) {
        first->polygon = hit.polygon;
        first->u = hit.u;
        first->v = hit.v;
        first->distance = hit.t * glm::length(dir);
    }
    return shade(origin, dir, hit, rng, bounce, casts);
}

dvec3 FinalGather::shade(const dvec3& origin, const dvec3& dir, const Hit& hit, Rng& rng,
                         int bounce, std::uint64_t& casts) const {
    const Scene& scene = h_->scene();
    if (!hit.front) return dvec3(0.0);
    const double distance = hit.t * glm::length(dir);
    if (bounce > 0 && distance >= kTracedLeaves * leaf_size_[hit.polygon])
        return read_off(origin, dir, hit); // a far hit past the first: the solution's leaves
    // Through window panes: what comes back is attenuated by them.
    const double through = glazing_->along(origin, dir, hit.t);
    if (!(through > 0)) return dvec3(0.0);
    const Polygon& q = scene.polygons[hit.polygon];
    const dvec3 rho = reflectance_at(scene, hit.polygon, hit.u, hit.v); // the texel there
    if (!(rho.x > 0 || rho.y > 0 || rho.z > 0)) return dvec3(0.0);
    const dvec3 y = origin + hit.t * dir;
    // Past kTracedBounces the path goes on by Russian roulette: in a closed cavity (the
    // inside of a box on a shelf, of a wall slab) it never leaves the near hits, and
    // reading the leaves there after a fixed count of bounces would bring whatever light
    // they hold (with reflectance 0.98, 85 % of it after 8 bounces), where no light
    // enters; near a narrow opening it finds the light that comes after many bounces.
    double keep = 1;
    if (bounce >= kTracedBounces) {
        keep = std::min(1.0, std::max({rho.x, rho.y, rho.z}));
        if (bounce >= kMaxTracedBounces || rng.uniform() >= keep) return dvec3(0.0);
    }
    // Near the point a leaf's value is too coarse (a contact shadow, a corner), and in
    // clutter (a cavity behind furniture, under a shelf) the leaves hold too little of the
    // light that reaches them after several bounces; at the first hit, the solution's
    // errors (a few per cent low where light arrives after several bounces) pass to the
    // point undamped, one bounce later they average out: estimate H(y) at the hit itself, the
    // direct light sampled there plus one more cosine ray, traced on the same way. One
    // sample each; the primary rays average them.
    const dvec3 direct_y = direct_sample(y, q.normal, hit.polygon, rng);
    const dvec3 y_off = y + offset_ * q.normal;
    return through * rho / keep *
           (direct_y + onward(y_off, q.normal, hit.polygon, rng, bounce + 1, casts));
}

dvec3 FinalGather::read_off(const dvec3& origin, const dvec3& dir, const Hit& hit) const {
    if (!hit.front) return dvec3(0.0);
    return glazing_->along(origin, dir, hit.t) *
           reflectance_at(h_->scene(), hit.polygon, hit.u, hit.v) *
           irradiance_at(*h_, SurfacePoint{hit.polygon, hit.u, hit.v, 0.0});
}

dvec3 FinalGather::bright_sample(const dvec3& origin, const dvec3& n, std::uint32_t self, Rng& rng,
                                 int bounce, std::uint64_t& casts, bool traced) const {
    const double pick = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
    const BrightLeaves::Sample s = bright_->sample(pick, u1, u2, u3);
    if (s.polygon == self) return dvec3(0.0);
    const dvec3 to = s.point - origin;
    const double r = glm::length(to);
    if (!(r > 0)) return dvec3(0.0);
    const dvec3 dir = to / r;
    const double cos_x = glm::dot(dir, n);
    const double cos_y = -glm::dot(dir, h_->scene().polygons[s.polygon].normal);
    if (!(cos_x > 0 && cos_y > 0)) return dvec3(0.0);
    if (!traced && r < kTracedLeaves * leaf_size_[s.polygon]) return dvec3(0.0);
    Hit hit;
    ++casts;
    // Seen when the ray's first hit is the sampled polygon (a plane: at the sampled point).
    if (!bvh_->intersect(origin, dir, 1e300, hit, self) || hit.polygon != s.polygon)
        return dvec3(0.0);
    const double weight = balance(cos_x, per_solid_angle(s.density, r, cos_y));
    if (traced) return shade(origin, dir, hit, rng, bounce, casts) * weight;
    return read_off(origin, dir, hit) * weight;
}

dvec3 FinalGather::onward(const dvec3& origin, const dvec3& n, std::uint32_t self, Rng& rng,
                          int bounce, std::uint64_t& casts) const {
    // Without bright leaves a cosine ray's weight is 1.
    if (bright_->empty()) return cosine_sample(origin, n, self, rng, bounce, casts);
    // Both samples of the multiple importance sampling (balance heuristic), the bright leaf's
    // light read off the solution, as a cosine ray's far hit is (shade()), so that paths do not
    // branch; a bright leaf near the hit is left to the cosine rays, which trace it on (the
    // solution steers no traced path's weights). Taking one of the two at random with even
    // odds, weighted by 2, a path's weight doubled at every hit where the chosen sample found
    // nothing (a bright leaf hidden from it): in clutter, where paths went on for 8 bounces and
    // more, one path in 256 carried 256 times the light. In the office glb a point under a desk
    // read 130 times the reference (0.0044 W/m² for 3.4e-5) and a lit point 46 times. Against
    // the reference at our 1000 points (three gather seeds, one solve; with the roulette from
    // the second bounce, kTracedBounces): the office's lit points median 1.65 / 1.78 / 2.12 %
    // -> 1.91 / 1.69 / 1.94 %, p95 20.8 / 15.6 / 22.2 % -> 17.6 / 16.2 / 16.5 %, worst 93 /
    // 4565 / 222 % -> 74 / 302 / 58 %, in 40-49 s -> 44-51 s; lit by point sources 0.28 /
    // 5.86 % -> 0.27 / 4.25 % (worst 71 -> 63 %). The bright leaf beside the first traced hit's
    // cosine ray alone: 2.17 / 2.01 / 2.06 %; none past the primary rays: 2.31 %.
    return cosine_sample(origin, n, self, rng, bounce, casts) +
           bright_sample(origin, n, self, rng, bounce, casts, false);
}

dvec3 FinalGather::cosine_sample(const dvec3& origin, const dvec3& n, std::uint32_t self, Rng& rng,
                                 int bounce, std::uint64_t& casts) const {
    dvec3 t, b;
    orthonormal_basis(n, t, b);
    const double u1 = rng.uniform(), u2 = rng.uniform();
    const dvec3 dir = cosine_direction(n, t, b, u1, u2);
    FirstHit first;
    const dvec3 v = reflected(origin, dir, self, rng, bounce, casts, &first);
    return v * cosine_weight(dir, n, first, bounce);
}

double FinalGather::cosine_weight(const dvec3& dir, const dvec3& n, const FirstHit& first,
                                  int bounce) const {
    if (first.polygon == kNoPolygon) return 1.0; // escaped
    if (bounce > 0 && first.distance < kTracedLeaves * leaf_size_[first.polygon]) return 1.0;
    const double density = bright_->density(first.polygon, first.u, first.v);
    if (!(density > 0)) return 1.0;
    const double cos_y = -glm::dot(dir, h_->scene().polygons[first.polygon].normal);
    return balance(glm::dot(dir, n), per_solid_angle(density, first.distance, cos_y));
}

dvec3 FinalGather::indirect(const dvec3& x, const dvec3& n, std::uint32_t self,
                            std::uint64_t seed) const {
    const int m = std::max(1, int(std::lround(std::sqrt(double(options_.rays)))));
    double error = 0, casts_a_ray = 0;
    const dvec3 first = indirect_pass(x, n, self, seed, m, &error, &casts_a_ray);
    if (!(options_.indirect_error > 0) || !(error > options_.indirect_error)) return first;
    // Noisy: (error / target)^2 times the rays, that is m * error / target strata a side,
    // within the caps on rays and ray casts (long traced paths in clutter cost more a ray).
    const int affordable =
        int(std::floor(m * std::sqrt(kRegatherCasts / std::max(1.0, casts_a_ray))));
    const int again = std::min(
        {kMaxRegatherSide * m, affordable, int(std::ceil(m * error / options_.indirect_error))});
    if (again <= m) return first;
    return indirect_pass(x, n, self, splitmix64(seed + 0x9e3779b97f4a7c15ull), again, nullptr,
                         nullptr);
}

dvec3 FinalGather::indirect_pass(const dvec3& x, const dvec3& n, std::uint32_t self,
                                 std::uint64_t seed, int m, double* relative_error,
                                 double* casts_a_ray) const {
    Rng rng(seed);
    dvec3 t, b;
    orthonormal_basis(n, t, b);
    const dvec3 origin = x + offset_ * n;
    dvec3 sum(0.0);
    std::uint64_t casts = 0;
    // Per stratum pair (i, i + 1) on a row: the squared difference of their sums over RGB.
    double pair_variance = 0, previous = 0;
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i) {
            const double u1 = (i + rng.uniform()) / m, u2 = (j + rng.uniform()) / m;
            const dvec3 dir = cosine_direction(n, t, b, u1, u2);
            FirstHit first;
            dvec3 v = reflected(origin, dir, self, rng, 0, casts, &first);
            if (!bright_->empty()) {
                // Multiple importance sampling (balance heuristic, one sample of each kind a
                // ray): either way a sample brings rho H * p_cos / (p_cos + p_bright), both
                // densities per solid angle at x.
                if (nonzero(v)) v *= cosine_weight(dir, n, first, 0);
                v += bright_sample(origin, n, self, rng, 0, casts);
            }
            sum += v;
            const double y = v.x + v.y + v.z;
            if (i % 2 == 1) pair_variance += (y - previous) * (y - previous);
            previous = y;
        }
    const double N = double(m) * double(m);
    if (relative_error) {
        // Var(mean) ~ sum over pairs of (a - b)^2 / N^2 (each pair a stratum of two samples).
        const double total = sum.x + sum.y + sum.z;
        *relative_error = total > 0 ? std::sqrt(pair_variance) / total : 0.0;
    }
    if (casts_a_ray) *casts_a_ray = double(casts) / N;
    return sum / N;
}

GatherValue FinalGather::at(const GatherPoint& q, std::uint64_t index) const {
    GatherValue v;
    const double len = glm::length(q.normal);
    if (!(len > 0)) return v;
    const dvec3 n = q.normal / len;
    const std::uint32_t self = q.polygon == GatherPoint::kNoSurface ? kNoPolygon : q.polygon;
    const std::uint64_t seed = splitmix64(options_.seed ^ splitmix64(index));
    v.direct = direct(q.position, n, self, seed);
    if (h_->scene().sky) {
        Rng rng(splitmix64(seed + 2));
        v.direct +=
            sky_irradiance(*h_->scene().sky, bounds_, *bvh_, q.position, n, self, offset_, rng,
                           options_.sky_cells, options_.sky_split, nullptr, glazing_.get());
    }
    v.indirect = indirect(q.position, n, self, splitmix64(seed + 1));
    return v;
}

dvec3 FinalGather::direct_at(const GatherPoint& q, std::uint64_t index) const {
    const double len = glm::length(q.normal);
    if (!(len > 0)) return dvec3(0.0);
    const std::uint32_t self = q.polygon == GatherPoint::kNoSurface ? kNoPolygon : q.polygon;
    return direct(q.position, q.normal / len, self, splitmix64(options_.seed ^ splitmix64(index)));
}

std::vector<GatherValue> FinalGather::at(const std::vector<GatherPoint>& points) const {
    std::vector<GatherValue> out(points.size());
    // At least 8 points a thread: fewer are not worth a thread's start.
    const unsigned threads = unsigned(std::min<std::size_t>(
        thread_count(options_.threads), std::max<std::size_t>(1, points.size() / 8)));
    parallel_for(points.size(), int(threads), [&](std::size_t k) { out[k] = at(points[k], k); });
    return out;
}

} // namespace hemirad
