// Final gather at points: irradiance at a query point evaluated at the point itself from a
// solved hierarchy, instead of interpolating the leaf patches around it.
//
//   E(x) = E_direct(x) + E_indirect(x)
//
// Direct: for every emitting polygon P facing x, exitance Be_P times the form factor from x to
// P with P's visibility sampled over its area: P is cut into cells no wider than
// `emitter_angle` as seen from x (at most 8 x 8) and one shadow ray goes to a jittered point
// of each cell; if
// every ray arrives, the exact unoccluded form factor F(dx -> P) is used (Lambert's contour
// integral, form_factors.h); if none does, P is hidden; in a penumbra each cell is split 4 x 4
// again and sum_k F(dx -> cell_k) * visible_k is used (one jittered ray per fine cell). So
// penumbrae and contact shadows at the point are resolved to a sixteenth of a coarse cell,
// whatever the leaf size of the surface the point lies on.
//
// Point luminaires (photometry.h) add their exact direct irradiance I(d) cos(theta) / (683 r^2)
// where one shadow ray from the point to the luminaire arrives (a point source casts hard
// shadows: one ray is exact). Nearer than five times the size of a luminaire's luminous opening
// (LuminousOpening, from its photometric file) the luminaire is an area source: its intensity
// is shared among points over the opening no farther apart than an eighth of the distance,
// each with its own shadow ray.
//
// Indirect: `rays` cosine-distributed directions, stratified over an m x m grid of the unit
// square (m = round(sqrt(rays))), each with one jittered sample. A ray that reaches the front
// of polygon Q at y brings the solved reflected radiosity rho_Q * H(y) (H interpolated between
// Q's leaf centres, readout.h); Q's own emission is not counted there (it is in the direct
// part); a ray that escapes or hits the back of a polygon brings nothing. With pdf cos/pi the
// estimate is E_indirect = (1/N) sum rho_Q H(y). Errors in H average over the hemisphere,
// except where the hit is near the point: there one leaf fills much of the hemisphere (a
// contact line, a corner), and in clutter (a cavity behind furniture, the wall under a shelf)
// the leaves hold too little of the light that reaches them after several bounces, since the
// hemicubes see such places through narrow openings. So the first hit of every ray, and a later
// hit nearer than 30 leaf sizes of Q, estimates H(y) at y itself instead: the direct light at y
// plus rho H of one more cosine ray from y, traced on the same way, for 8 bounces and past
// them by Russian roulette (kept with the hit's largest reflectance and weighted by its
// inverse; at most 256 bounces): the solution is read one bounce away at the nearest (its
// errors averaged over the hemispheres of all the first hits, and damped by their
// reflectance), and only where a path leaves the clutter, never inside a closed cavity.
// The direct light at a hit: one shadow ray to each point luminaire; one to each emitter
// polygon that holds an eighth or more of the hit's unoccluded emitter light (its exact form
// factor times the ray's visibility), and to the others by Russian roulette, in proportion to
// their light and weighted by its inverse (unbiased, about 8 rays however many emitter
// polygons).
//
// Bright leaves: a small surface far brighter than the rest (a desk lamp's shade or the desk
// under it, the ceiling above an uplight, a wall beside a spot) is hit by few of the cosine
// rays and brings much when it is: in the Blender office one of a floor point's 1024 rays
// carried a third of its indirect light, five carried 71 %. So the leaves whose reflected
// radiosity rho H exceeds 8 times the scene's area-weighted mean (at most 65,536, the
// brightest; bright_leaves.h) are sampled as well, a leaf in proportion to its reflected
// power rho H A, a point on it uniformly: with each primary cosine ray goes one such sample
// (a shadow ray; seen, it is traced on like a first hit), and at each traced hit the path goes
// on by one of the two, a cosine ray or a bright leaf, with even odds. Both are weighted by
// the balance heuristic of multiple importance sampling (Veach & Guibas 1995): a sample that
// reaches y on a bright leaf brings rho H(y) p_cos / (p_cos + p_bright), p_cos = cos(theta_x)/pi
// and p_bright = P(leaf) / A(leaf) * r^2 / cos(theta_y) the two densities per solid angle;
// at a traced hit, where one of the two is drawn at even odds, twice that. Unbiased whatever
// the solution holds: it only decides where the samples go (a test lights leaves of the
// solution alone and the gathered furnace stays exact).
//
// A point whose first `rays` are noisy (a small bright surface in view: the sunlit patch of a
// floor, a wall beside a spot's pool of light) is gathered again with more rays: the relative
// standard error of the first estimate is taken from the differences of neighbouring strata
// (each pair a stratum of two samples, which overstates it for a smooth field); above
// `indirect_error` the point is gathered anew with (error / indirect_error)^2 times as many
// rays, at most 16 times `rays`, and no more ray casts (indirect rays and their traced
// bounces) than 32 times `rays` (a point deep in clutter, whose paths are long, gets fewer
// rays); that estimate alone is returned.
//
// The sky (sky.h) is direct light gathered apart at the point (at() only, not direct_at()):
// stratified cosine rays that leave the scene bring the sky's or the ground's luminance, with
// the cells on the edges of openings sampled finer (solver/sky_light.h sky_irradiance). The
// indirect rays' escapes bring nothing (that light is the direct part), except for the rays
// of a traced path past its first hit, which bring the sky's radiance.
//
// Results depend only on the solution, the options and the point's index (each point has its
// own generator seeded from `seed` and the index), not on the number of threads.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "hemirad/hierarchy.h"
#include "hemirad/visibility.h"

namespace hemirad {

class BrightLeaves;
class Bvh;
class GlazingTracer;
struct Hit;
class Rng;

struct GatherOptions {
    int rays = 1024; ///< indirect: cosine rays per point, 16..65536 (typical 256-4096)
    /// Indirect: gather a point again with more rays (up to 16 x rays) when the relative
    /// standard error of its first estimate exceeds this; 0 = never. [0, 1)
    double indirect_error = 0.01;
    double emitter_angle = 0.1; ///< direct: widest emitter cell seen from the point [rad], (0, 1]
    /// Indirect: the leaves whose reflected radiosity exceeds this many times the scene's mean
    /// are sampled besides the cosine rays (see above); 0 = off (cosine rays alone). 0 or
    /// [1, 1e6].
    double bright_factor = 8;
    std::uint64_t seed = 1; ///< generator seed (reproducible)
    /// Direct light: shadow rays to jittered points of the emitter cells (unbiased on average,
    /// for points) or to their centres (deterministic and smooth from point to point, for
    /// images, at the price of steps of one fine cell in a penumbra).
    bool jitter = true;
    /// Direct light: test the coarse cells first and take the exact form factor when all are
    /// visible (fast, for points); off: always sum the fine cells (no step where one coarse
    /// ray first meets an occluder: smooth penumbrae in images).
    bool coarse_test = true;
    /// Sky (Scene::sky): sky_cells^2 stratified cosine rays per point, and sky_split^2 more in
    /// each cell on the edge of an opening or the horizon (solver/sky_light.h sky_irradiance).
    int sky_cells = 32; ///< 4..256 (typical 16-64)
    int sky_split = 8;  ///< 1..32 (typical 4-16)
    int threads = 0;    ///< worker threads; 0 = all cores
};

/// Throws InputError naming the option (--gather-rays, --gather-angle, ...) and the value.
HEMIRAD_API void validate_gather_options(const GatherOptions& o);

/// A query: a point, the unit normal of the surface element there, and the polygon it lies on
/// (kNoSurface for a point in free space: a work plane above the floor).
struct GatherPoint {
    static constexpr std::uint32_t kNoSurface = std::numeric_limits<std::uint32_t>::max();
    dvec3 position{0.0}, normal{0.0};
    std::uint32_t polygon = kNoSurface;
};

struct GatherValue {
    dvec3 direct{0.0}, indirect{0.0}; ///< [W unit^-2], RGB
    dvec3 E() const { return direct + indirect; }
};

class HEMIRAD_API FinalGather {
  public:
    /// `h` must be push-pulled (Solver::solution()) and outlive this object.
    FinalGather(const Hierarchy& h, const GatherOptions& options = {});
    ~FinalGather();
    FinalGather(const FinalGather&) = delete;
    FinalGather& operator=(const FinalGather&) = delete;

    /// One point; `index` selects its random stream.
    GatherValue at(const GatherPoint& q, std::uint64_t index) const;
    /// The direct part alone (emitters with their area visibility sampled), as in at().
    dvec3 direct_at(const GatherPoint& q, std::uint64_t index) const;
    /// Many points, on options.threads threads; point k uses index k.
    std::vector<GatherValue> at(const std::vector<GatherPoint>& points) const;

    const GatherOptions& options() const { return options_; }

  private:
    dvec3 direct(const dvec3& x, const dvec3& n, std::uint32_t self, std::uint64_t seed) const;
    dvec3 indirect(const dvec3& x, const dvec3& n, std::uint32_t self, std::uint64_t seed) const;
    /// A luminaire's direct irradiance at x from points spread over its luminous opening (a
    /// point r away, nearer than five times the opening's size) [W unit^-2].
    double luminous_opening(const Luminaire& l, const dvec3& x, const dvec3& n, std::uint32_t self,
                            double r) const;
    /// One pass of m x m stratified rays; with relative_error, the estimate's relative
    /// standard error from the differences of neighbouring strata; with casts_a_ray, the
    /// rays cast (indirect rays and their traced bounces) per indirect ray.
    dvec3 indirect_pass(const dvec3& x, const dvec3& n, std::uint32_t self, std::uint64_t seed,
                        int m, double* relative_error, double* casts_a_ray) const;
    /// What an indirect ray brings (rho H at its hit), its path traced on through hits near
    /// its origin (bounce: the hits before this one); counts its ray casts in casts.
    /// Where a ray met its first polygon (reflected()'s, with `first`).
    struct FirstHit {
        std::uint32_t polygon = std::numeric_limits<std::uint32_t>::max(); ///< max: escaped
        double u = 0, v = 0, distance = 0;
    };
    dvec3 reflected(const dvec3& origin, const dvec3& dir, std::uint32_t self, Rng& rng, int bounce,
                    std::uint64_t& casts, FirstHit* first = nullptr) const;
    /// What a ray from `origin` along unit `dir` brings from its hit `hit` (reflected()
    /// after its ray cast).
    dvec3 shade(const dvec3& origin, const dvec3& dir, const Hit& hit, Rng& rng, int bounce,
                std::uint64_t& casts) const;
    /// What that ray brings read off the solution: the hit's leaves' irradiance times its
    /// reflectance, through the panes on the way (nothing from a polygon's back).
    dvec3 read_off(const dvec3& origin, const dvec3& dir, const Hit& hit) const;
    /// One sample of the bright leaves (bright_leaves.h) seen from `origin` (normal n): what it
    /// brings, weighted for its multiple importance sampling with the cosine rays; its path
    /// traced on (shade()), or with `traced` false its leaf's value read off the solution,
    /// for a leaf as far as shade() reads leaves (nothing from a nearer one).
    dvec3 bright_sample(const dvec3& origin, const dvec3& n, std::uint32_t self, Rng& rng,
                        int bounce, std::uint64_t& casts, bool traced = true) const;
    /// One cosine ray from `origin`, weighted for its multiple importance sampling with the
    /// bright leaves.
    dvec3 cosine_sample(const dvec3& origin, const dvec3& n, std::uint32_t self, Rng& rng,
                        int bounce, std::uint64_t& casts) const;
    /// The balance heuristic's weight of a cosine ray along `dir` that met `first`; past the
    /// first hit (bounce > 0) only far bright leaves are sampled (see onward()).
    double cosine_weight(const dvec3& dir, const dvec3& n, const FirstHit& first, int bounce) const;
    /// A traced path's next step from a hit: a cosine ray, traced on, and a far bright leaf,
    /// read off the solution, each weighted for their multiple importance sampling.
    dvec3 onward(const dvec3& origin, const dvec3& n, std::uint32_t self, Rng& rng, int bounce,
                 std::uint64_t& casts) const;
    dvec3 direct_sample(const dvec3& y, const dvec3& n, std::uint32_t self, Rng& rng) const;
    /// The luminaires' and the sun's direct irradiance at x (one shadow ray each), RGB.
    dvec3 luminaires(const dvec3& x, const dvec3& n, std::uint32_t self) const;
    /// Where a shadow ray from surface point x (normal n) starts: x lifted off its surface
    /// by offset_ along n. A point on a surface is on it only to rounding (or to the digits
    /// of a probe file); from just behind it, a ray towards a light near the surface's plane
    /// (a bar passing through it, grazing) would be blocked by the surface's twin or a
    /// coplanar neighbour. The indirect rays start there too.
    dvec3 lifted(const dvec3& x, const dvec3& n) const { return x + offset_ * n; }

    const Hierarchy* h_;
    GatherOptions options_;
    std::unique_ptr<Bvh> bvh_;
    std::unique_ptr<GlazingTracer> glazing_; ///< the window panes (glazing.h)
    std::unique_ptr<BrightLeaves> bright_;   ///< the solution's secondary sources
    std::vector<std::uint32_t> emitters_;    ///< polygons with exitance > 0
    std::vector<double> leaf_size_;          ///< per polygon, sqrt(area) / 2^depth [unit]
    double offset_ = 0;                      ///< origin offset along the normal [unit]
    Bounds bounds_;                          ///< the scene's
};

} // namespace hemirad
