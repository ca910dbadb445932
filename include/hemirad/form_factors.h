// The interface between the solver and whatever computes form factors (docs/design.md,
// "Data flow"): the solver asks "form factors from this shooter", a provider answers with
// links. The CPU reference providers and the GPU hemicube provider stand behind it alike.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hemirad/error.h"
#include "hemirad/patch.h"
#include "hemirad/scene.h"
#include "hemirad/visibility.h"

namespace hemirad {

/// The patch that shoots: a node of some polygon's quadtree.
struct Shooter {
    PatchAddress address;
    PatchGeometry geometry;    ///< corners, centre, area of the shooting patch
    dvec3 normal{0.0};         ///< the polygon's unit normal
    double unshot_power = 0;   ///< sum over RGB of |dB|*area [W]; providers may adapt to it
    double power_fraction = 1; ///< unshot_power / total unshot power now (0..1]
    /// Where its unshot radiosity is uneven, the radiosity of the quadtree nodes below it over
    /// its own mean, `emission_levels` levels deep, in pre-order (each node's four children,
    /// each followed by its own descendants); empty: even. Receivers near the shooter, where
    /// the shooter's extent matters, weight its parts' kernels by them.
    std::vector<float> emission;
    int emission_levels = 0;
};

/// A cluster of polygons that shoots as one point (cluster_tree.h; Sillion 1995): from
/// `centre`, with the intensity of the sum of its polygons' cosine lobes per watt emitted,
///   I(d) = sum_k weight_k max(0, normal_k . d) / pi   [sr^-1], sum_k weight_k = 1,
/// which integrates to 1 over the sphere: the far field of its polygons' unshot light.
struct ClusterShooter {
    dvec3 centre{0.0};           ///< the point it shoots from [unit]
    dvec3 axis{0.0, 1.0, 0.0};   ///< unit; the two hemicubes look along +axis and -axis
    double radius = 0;           ///< of its bounding sphere [unit]
    std::vector<dvec3> normals;  ///< emission lobes (unit normals)...
    std::vector<double> weights; ///< ...and their shares of the power (sum 1)...
    /// ...and the planes its polygons lie in front of (add_lobe_planes). Light from a plane
    /// reaches only receivers in front of it (share_in_front): one behind it is inside the
    /// object the cluster wraps, or behind the wall it covers.
    struct Plane {
        std::uint32_t lobe = 0;      ///< index into normals
        double offset = 0;           ///< the plane: normal . x = offset
        double weight = 0;           ///< its share of the power (a lobe's planes sum to its weight)
        dvec3 lo{-1e300}, hi{1e300}; ///< the box around its polygons
    };
    std::vector<Plane> planes;
    /// Its polygons, sorted: not drawn (they do not occlude its light), never linked.
    std::vector<std::uint32_t> members;
    /// Its polygons that carry the most light (up to kMaxSources, brightest first), their
    /// shares of the power, and whether they do not see `centre` from in front (it lies
    /// behind their plane, or a segment to it crosses a polygon): a receiver near a point
    /// cluster takes light only from those it can see, and one that sees the centre is taken
    /// to see what the centre sees (a jar's inside, which the point sees from within, sees
    /// none of its outside).
    struct Source {
        std::uint32_t polygon = 0;
        double share = 0;
        bool hidden_from_centre = false;
    };
    static constexpr std::size_t kMaxSources = 16;
    std::vector<Source> sources;
    double unshot_power = 0;   ///< sum over RGB [W]; providers may adapt to it
    double power_fraction = 1; ///< unshot_power / total unshot power now (0..1]
    /// A flat cluster (its polygons in one plane, facing `axis`) shoots instead as the
    /// rectangle `rect` around them in that plane, emitting uniformly: per watt, E_j =
    /// F(dA_j -> rect) / area(rect), the analytic value of a patch shooter (exact in the near
    /// field, where a point is not). count 0: not flat.
    PatchGeometry rect;
    /// I(d) for a unit direction d [sr^-1 per watt].
    double intensity(const dvec3& d) const;
    /// Share of the power emitted into the half space d . axis < 0.
    double back_share() const;
    /// Of the intensity towards a receiver at x facing n, the share from planes that x is in
    /// front of and that have some of their box in front of x's plane (by more than eps):
    /// what the cluster's polygons could send it, where its centre alone would send it more
    /// (a centre inside a wall sees the wall's inner faces). 1 without planes, 0 where no lobe
    /// emits towards x.
    double share_in_front(const dvec3& x, const dvec3& n, double eps) const;
    /// Adds lobe `lobe`'s planes from its polygons' planes (offset: the min over a polygon's
    /// corners of normal . corner; weight; box): polygons whose offsets lie within `gap` of
    /// the next share a plane at their lowest offset, so that planes a wall's thickness apart
    /// (a slab's two faces, a floor and a table top) stay apart. Over `max_planes`, the
    /// closest neighbours merge first.
    void add_lobe_planes(std::uint32_t lobe, std::vector<Plane> polygons, double gap,
                         std::size_t max_planes);
};

/// One receiving node and the form factor from it to the shooter, F(j -> S): the fraction
/// of the power leaving receiver j that arrives at the shooter. The solver uses `ff`.
struct Link {
    PatchAddress receiver;
    float ff = 0;          ///< the value the solver uses, F(j->S)
    float ff_analytic = 0; ///< analytic dA_j -> S at the receiver centre (unoccluded)
    float ff_pixel = 0;    ///< hemicube pixel sum converted to F(j->S) (0 where not computed)
    bool partial = false;  ///< estimated partially occluded
};

/// Per-polygon quadtree depths: the deepest level each polygon may be linked at.
struct Discretisation {
    std::vector<std::uint8_t> depth; ///< per polygon, 0..kMaxDepth
};

class HEMIRAD_API FormFactorProvider {
  public:
    virtual ~FormFactorProvider() = default;
    virtual std::string name() const = 0;
    /// Appends to `links` one entry per receiving node visible from the shooter (links is
    /// cleared first). Receivers on the shooter's own polygon are never returned.
    virtual void shoot(const Shooter& shooter, std::vector<Link>& links) = 0;
    /// A point shot: the luminaire (photometry.h) shoots from its position over the whole
    /// sphere, with the same linking as shoot(). Appends one entry per receiving node visible
    /// from the luminaire (links is cleared first), its values per watt the luminaire emits
    /// per channel, P = luminaire.power():
    ///   ff = ff_analytic = E_j / P = I(d) cos(theta_j) / (683 r^2 P) at the node's centre
    ///   [unit^-2] (exact for an unoccluded node), ff_pixel = the flux through the node's
    ///   hemicube pixels / (P A_j) (GPU providers), and ff as shoot() picks it (hybrid: the
    ///   pixel value, clamped to the analytic one, for partially occluded nodes).
    /// So sum_j ff A_j is the fraction of the luminaire's power received (its row sum).
    /// Default: InputError (the provider cannot shoot luminaires).
    virtual void shoot_point(const Luminaire& luminaire, std::vector<Link>& links) {
        (void)luminaire;
        links.clear();
        throw InputError("form-factor method " + name() + " cannot shoot point luminaires");
    }
    /// A cluster shot (ClusterShooter): its light from its centre over the whole sphere, with
    /// the same linking as shoot_point(); per watt emitted, ff = ff_analytic = E_j =
    /// I(d) cos(theta_j) / r^2 at the node's centre [unit^-2]; ff_pixel the flux through the
    /// node's pixels per watt / A_j. Default: InputError (see can_shoot_clusters()).
    virtual void shoot_cluster(const ClusterShooter& cluster, std::vector<Link>& links) {
        (void)cluster;
        links.clear();
        throw InputError("form-factor method " + name() + " cannot shoot clusters");
    }
    virtual bool can_shoot_clusters() const { return false; }
    /// Share of the last cluster shot's received power that landed within twice the
    /// cluster's radius of its centre, where a point is a poor stand-in for the cluster.
    virtual double last_near_fraction() const { return 0; }
    /// When true, receivers are linked at their leaves (depth of the Discretisation);
    /// used by the matrix solver and by tests. Default: adaptive linking.
    virtual void set_link_at_leaves(bool leaves) { link_at_leaves_ = leaves; }
    /// Timings of the last shoot() in seconds, by phase name (render, readback, reduce, ...).
    struct Timing {
        const char* phase;
        double seconds;
    };
    virtual std::vector<Timing> last_timings() const { return {}; }
    /// Fraction of the shooter's hemisphere (by form factor) covered by the backs of
    /// polygons in the last shoot(): near 1 when the shooter's centre is enclosed (under a
    /// box, behind a light), where a point-sampled shot would lose the patch's power.
    virtual double last_backface_fraction() const { return 0; }
    /// Fraction of the last patch shooter's hemisphere (by form factor) that is either the
    /// backs of polygons or surfaces nearer than a quarter of the shooter's size (sqrt of its
    /// area): near 1 when its centre is shut in (under a box, inside a shelf that stands
    /// against it, whose inner faces are fronts when the shelf is two-sided), where one
    /// point cannot stand for the patch. Computed on demand; default: last_backface_fraction().
    virtual double last_enclosed_fraction() const { return last_backface_fraction(); }
    /// Does the last patch shooter's centre see the front of a surface nearer than `distance`?
    /// (Something within reach of its area, whose view then changes across it.) Computed on
    /// demand; false where not known.
    virtual bool last_sees_within(double /*distance*/) const { return false; }
    /// Share of the last shooter's form factor whose visibility changes across the shooter's
    /// area (silhouettes of nearby occluders; gpu/hemicube.h, parallax_fraction): large when a
    /// shot from the centre misrepresents what the shooter's area sees. Computed on demand
    /// from the last shoot(); 0 for providers that sample the shooter's area themselves.
    virtual double last_parallax_fraction() const { return 0; }
    /// What a patch shooter's centre sees, measured without its form factors: the enclosed
    /// and parallax fractions (as last_enclosed_fraction() and last_parallax_fraction() would
    /// give after shoot()), from a coarse hemicube, so that a shooter the solver refuses costs
    /// a fraction of a full one. Returns false where the provider has no cheaper way than
    /// shoot() (CPU providers; a shooter whose own hemicube is no finer than the probe's).
    struct ViewProbe {
        double enclosed = 0;
        double parallax = 0;
    };
    virtual bool probe_view(const Shooter& shooter, ViewProbe& probe) {
        (void)shooter, (void)probe;
        return false;
    }
    /// A cluster's shares as the solver reads them after shoot_cluster() (misplaced:
    /// last_parallax_fraction() + last_near_fraction() + last_backface_fraction(); backface:
    /// last_backface_fraction()), from coarse hemicubes of polygon IDs before it shoots, so
    /// that a cluster the solver refuses costs a fraction of a shot. Returns false where the
    /// provider has no cheaper way than shoot_cluster().
    struct ClusterProbe {
        double misplaced = 0;
        double backface = 0;
    };
    virtual bool probe_cluster(const ClusterShooter& cluster, ClusterProbe& probe) {
        (void)cluster, (void)probe;
        return false;
    }
    /// The hemicube rendered by the last shoot() (GPU providers; for display and tests):
    /// width x height RGBA floats, row 0 at the bottom (GL order), laid out as
    /// gpu::HemicubeLayout (top face at (0,0) res x res, four half faces around it). Per
    /// pixel: R the patch index within its level, G the level, B polygon + 1 (0: nothing;
    /// -(polygon + 1): the back of a polygon), A the analytic form factor dA_j -> shooter.
    /// Empty (rgba null) for providers without one, or before the first shot; valid until
    /// the next shoot().
    struct HemicubeImage {
        int width = 0, height = 0; ///< [pixels]
        const float* rgba = nullptr;
    };
    virtual HemicubeImage last_hemicube() const { return {}; }
    /// State that affects later shots (adaptive resolutions, ...), for save/resume
    /// (solution_file.h). Default: none. restore_state() gets what save_state() returned and
    /// throws InputError if it cannot be this provider's.
    virtual std::vector<double> save_state() const { return {}; }
    virtual void restore_state(const std::vector<double>& state) {
        if (!state.empty())
            throw InputError("form-factor provider " + name() + " keeps no state, but " +
                             std::to_string(state.size()) + " values were saved for it");
    }

  protected:
    bool link_at_leaves_ = false;
};

/// Options shared by the CPU providers.
struct CpuProviderOptions {
    /// Adaptive linking: a receiver node is refined while its size / distance to the shooter
    /// exceeds this (about one hemicube pixel at resolution 256: 2/256). Range (0, 1].
    double link_angle = 2.0 / 256.0;
    int visibility_samples = 4; ///< reference: shooter points per side for ray visibility (1..16)
    int gauss_order = 4;        ///< pdm: Gauss-Legendre nodes per side on each patch (1..16)
    int sr_rays = 1024;         ///< sr: cosine-distributed rays per shooter sample point
    int sr_points = 16;         ///< sr: random sample points on the shooter
    std::uint64_t seed = 1;     ///< sr: random seed (reproducible)
};

/// CPU providers: "reference" (analytic point-to-polygon + ray-cast visibility),
/// "pdm" (paper 000's parametric differential method), "sr" (paper 000's shooting rays).
/// Throws InputError for an unknown name.
HEMIRAD_API std::unique_ptr<FormFactorProvider>
make_cpu_provider(const std::string& name, const Scene& scene, const Discretisation& disc,
                  const CpuProviderOptions& options = {});

/// Analytic form factor from a differential area at `p` with unit normal `n` to the
/// polygon `corners[0..count)` (Lambert/Nusselt contour integral), the polygon first
/// clipped to the half-space n.(x-p) >= 0. Double precision. Returns a value in [0,1].
HEMIRAD_API double point_to_polygon_ff(const dvec3& p, const dvec3& n, const dvec3* corners,
                                       int count);

} // namespace hemirad
