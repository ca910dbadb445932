// Progressive-refinement radiosity (shooting) over the patch hierarchy (paper 002 §2, §4).
// The API is a loop (docs/design.md, "The solver's API is a loop"):
//
//     Solver s(scene, options);
//     while (s.step()) show(s.last_shot());
//
// No GL types here: form factors come from a FormFactorProvider (CPU or GPU).
#pragma once

#include <chrono>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "hemirad/collective.h"
#include "hemirad/form_factors.h"
#include "hemirad/hierarchy.h"
#include "hemirad/provider.h"
#include "hemirad/scene.h"
#include "hemirad/visibility.h"

namespace hemirad {

/// SolverOptions::clusters "auto" shoots clusters in scenes of more polygons than this.
inline constexpr std::size_t kClusterPolygons = 4096;

struct SolverOptions {
    std::string ff = "hybrid";  ///< form-factor method (see provider.h)
    ProviderOptions provider;   ///< options of the form-factor providers
    HierarchyOptions hierarchy; ///< patch size and depth
    double tolerance = 0.01;    ///< stop when error bound / emitted power <= this (0, 1)
    long max_shots = 100000;    ///< stop after this many shots (>= 0)
    double time_limit = 0;      ///< stop after this many seconds (0 = none)
    /// Shooter descent (paper 002 §4.2): descend into the child with most unshot power while
    /// its unshot power is at least this fraction of the scene's total unshot power... (0,1].
    double shooter_power_fraction = 1.0 / 16.0;
    /// ...and its size (sqrt of area) at least this [scene units]; 0 = the leaf patch size.
    double shooter_min_size = 0;
    /// ...but always descend below nodes larger than this [scene units]: a hemicube sees
    /// from one point, so a large shooter's visibility is that of its centre only.
    /// 0 = no limit.
    double shooter_max_size = 0;
    bool flat = false; ///< always shoot from leaves (no hierarchy), for comparison
    /// Rescale a shot's form factors when their row sum exceeds 1 (paper 000: rows above 1
    /// create energy; in a closed cube they reached 1.0018 and put 3 % on a 5 % indirect).
    bool row_guard = true;
    /// A shooter whose hemisphere is covered by the backs of polygons for more than this
    /// fraction (its centre is enclosed: under a box, behind a light) is not shot; its
    /// children are shot instead, so that its power is not lost. (0, 1]; 1 = never refine.
    double enclosed_fraction = 0.5;
    /// A shooter whose view changes across its area (FormFactorProvider::
    /// last_parallax_fraction: silhouettes of occluders near a large shooter) misplaces the
    /// part of its power that the parallax fraction P measures. A node whose misplaced power
    /// P * (unshot power) would exceed this fraction of the emitted power is not shot from its
    /// centre; its children are shot instead. P is measured once per node, the test is made
    /// at every selection (a node that was too strong early may shoot whole later, when it
    /// holds less power). >= 0; 0 = never refine for parallax.
    double shooter_parallax = 3e-4;
    /// A patch shooter whose row sum (its links' share of its light) exceeds 1 + this, with
    /// surfaces in view nearer than its size, sees from its centre what parts of it do not
    /// (a shelf under part of a desk's underside, a bar's low frame beside it): it is not shot
    /// from its centre; its children are shot instead, and a leaf shoots as its quarters (and
    /// their quarters, kRowPartLevels deep), each from its own centre, their links summed. A
    /// leaf whose parts take less than half the excess away (its row is over 1 for another
    /// reason) shoots from its centre from then on. >= 0; 0 = never.
    double row_refine = 1e-3;
    /// Shoot groups of nearby polygons at once (cluster_tree.h; Smits, Arvo & Greenberg 1994,
    /// Sillion 1995): when the unshot power is spread over many small polygons, a node of a
    /// tree of polygon clusters shoots as one point source with its polygons' cosine lobes
    /// (a flat one: as the rectangle around its polygons), subject to the same test as a patch
    /// (its misplaced power: parallax, plus the light it sends close to itself, where a point
    /// is a poor stand-in). "auto": on for scenes of more than kClusterPolygons polygons,
    /// where shooting polygon by polygon cannot converge in reasonable time, off for smaller
    /// ones, where it does and clusters would only cost accuracy; "on", "off". GPU providers
    /// only.
    std::string clusters = "auto";
    /// Keep each luminaire's share of the solution apart (light_layers.h): dimming or switching
    /// off a luminaire afterwards (set_luminaire_multiplier, `--resume` with
    /// `--luminaire-multiplier`) rescales its share instead of shooting the difference. Costs a
    /// hierarchy's node storage per luminaire and a little time a shot. "auto": in scenes of
    /// 1 to 16 luminaires whose layers need at most 256 MB, and no clusters; "on": whenever
    /// there are luminaires and no clusters; "off".
    std::string light_layers = "auto";
    /// A cluster whose misplaced power (its share misplaced, parallax and near light, times
    /// its unshot power) would exceed this fraction of the emitted power shoots its children
    /// instead (as shooter_parallax for a patch; looser, as a cluster shot stands for many
    /// polygons' and the final gather reads the light it sends through one more bounce). >= 0.
    double cluster_parallax = 1e-3;
    /// Refuse to build a hierarchy whose estimated memory exceeds this [bytes]
    /// (memory_guard.h); 0 = the memory available (MemAvailable, or the cgroup limit).
    std::uint64_t memory_limit = 0;
};

/// One shot, as reported after it (also one line of --log).
struct ShotRecord {
    long shot = 0; ///< 1-based
    /// The luminaire shot (index into Scene::luminaires), or -1 when a patch shot: then
    /// `shooter` is the patch (for a luminaire it is {kNoPolygon-like 0xFFFFFFFF, 0, 0}).
    int luminaire = -1;
    /// The cluster shot (a node of the solver's cluster tree), or -1; then `shooter` is its
    /// first polygon's root and cluster_polygons how many polygons it holds.
    long cluster = -1;
    std::uint32_t cluster_polygons = 0;
    PatchAddress shooter;
    double shooter_power = 0; ///< unshot power shot, sum over RGB of its magnitude [W]
    std::size_t links = 0;
    int refined = 0;          ///< shooters replaced by their children before this shot
                              ///< (enclosed centre, or parallax above the limit)
    int probes = 0;           ///< coarse hemicubes rendered to decide whether a node may shoot
    int discarded = 0;        ///< full hemicubes rendered for refused nodes and thrown away
    int parts = 0;            ///< a leaf that shot as its parts (row_refine): hemicubes rendered
                              ///< for them, the leaf's own thrown away (counted in discarded)
    double parallax = -1;     ///< the shooter's parallax fraction (-1: not measured, a leaf)
    double row_sum = 0;       ///< sum_j F(j->S) A_j / A_S before any guard (1 if closed);
                              ///< for a luminaire, the fraction of its power received
    bool row_guarded = false; ///< the guard rescaled this row
    double t_select = 0, t_push_pull = 0, t_form_factors = 0, t_update = 0; ///< [s]
    std::vector<FormFactorProvider::Timing> ff_phases; ///< the provider's own split
    dvec3 unshot{0.0};          ///< total unshot power after the shot, RGB [W]
    double unshot_fraction = 0; ///< max over channels of unshot / emitted
    double error_bound = 0;     ///< relative bound on ||B - B*||_1 (see Solver::error_bound)
    int rank = 0;               ///< the rank that shot it (parallel rounds, set_collective)
    long round = 0;             ///< 1-based round of a parallel solve (0: not parallel)
};

/// Checks the options a user can get wrong (InputError naming the option and its value).
/// The Solver's constructor calls it; tools call it first, before any expensive set-up.
HEMIRAD_API void validate_options(const SolverOptions& options);

enum class StopReason { Running, Converged, MaxShots, TimeLimit, NothingToShoot };
HEMIRAD_API const char* to_string(StopReason r);

class Bvh;
class ClusterTree;
class GlazingTracer;
class LightLayers;
class PlaneCuts;
struct Photometry;

class HEMIRAD_API Solver {
  public:
    /// Builds the hierarchy and the provider named by options.ff. Throws InputError for bad
    /// options, RuntimeError if the provider cannot start (no GL context).
    Solver(const Scene& scene, const SolverOptions& options);
    /// Uses the given provider (built for discretise(scene, options.hierarchy)).
    Solver(const Scene& scene, const SolverOptions& options,
           std::unique_ptr<FormFactorProvider> provider);
    /// As Solver(const Scene&, ...), for a scene the solver may edit: the incremental
    /// re-solving edits below change its materials and luminaires (never its geometry), so
    /// that read-outs, reports and saved files see them.
    Solver(Scene& scene, const SolverOptions& options);
    ~Solver();
    Solver(const Solver&) = delete;
    Solver& operator=(const Solver&) = delete;

    /// Shoots once. Returns false (and shoots nothing) once a stop criterion holds.
    /// With a collective of N > 1 ranks, one step is a round of up to N shots, one per rank
    /// (every rank calls step(); all hold the bit-identical solution afterwards).
    bool step();
    /// Shoots in parallel rounds with the ranks of `c` (docs/scaling.md); nullptr or a
    /// collective of one: shoot alone. Every rank must build its Solver from the same scene
    /// and options, restore the same state, and call step() as often as the others.
    void set_collective(Collective* c) { collective_ = c; }
    int ranks() const { return collective_ ? collective_->size() : 1; }
    /// The shots of the last step(): one, or a round's (in rank order).
    const std::vector<ShotRecord>& last_round() const { return round_; }
    /// What the parallel rounds cost so far (on this rank; zero when shooting alone).
    struct ParallelStats {
        long rounds = 0;
        double bytes = 0;            ///< gathered per rank, all rounds together
        double max_bytes = 0;        ///< the largest round
        double seconds = 0;          ///< in the collectives (including waiting for the others)
        double transfer_seconds = 0; ///< of which moving the bytes (Collective)
    };
    const ParallelStats& parallel_stats() const { return parallel_; }
    /// A hash (FNV-1a, 64 bits) of the state later shots depend on (save_state(): nodes,
    /// unshot powers, dirty flags, view codes, luminaires, counters but the time): ranks that
    /// hold the bit-identical solution have equal checksums.
    std::uint64_t state_checksum() const;
    StopReason stop_reason() const { return stop_; }
    bool converged() const { return stop_ == StopReason::Converged; }

    const ShotRecord& last_shot() const { return last_; }
    long shots() const { return shots_; }
    double seconds() const; ///< wall time spent in step() so far

    /// Error bound in the power (L1, area-weighted) norm, relative to the emitted power:
    /// max over channels of U_c / ((1 - rho_max) * Phi_c) (paper 001 eq. 27 and 33). U and Phi
    /// count the luminaires' power (a luminaire not yet shot is all unshot). In a channel that
    /// an edit left emitting nothing, Phi_c is the most it emitted before (incremental.cpp).
    double error_bound() const;
    /// Unshot power, RGB [W]: the patches' plus the luminaires' not yet shot, each polygon's
    /// and luminaire's by its magnitude per channel (an edit's negative power counts too).
    dvec3 unshot_power() const;
    /// Per luminaire (Scene::luminaires), its unshot power, RGB [W]: all of it until it has
    /// shot (once, over the whole sphere), then 0; after an edit of its multiplier, the
    /// difference (negative where light was removed).
    const std::vector<dvec3>& luminaire_unshot() const { return luminaire_unshot_; }
    double unshot_fraction() const;
    dvec3 emitted_power() const { return emitted_; }
    dvec3 absorbed_power() const { return absorbed_; } ///< (1-rho)*received, summed [W]
    dvec3 escaped_power() const { return escaped_; }   ///< shot power that hit nothing [W]
    struct RowSumStats {
        double min = 0, mean = 0, max = 0;
        long guarded = 0;
    };
    RowSumStats row_sums() const;

    /// The solution: push-pulls every polygon so that node values are complete.
    Hierarchy& solution();
    const Hierarchy& hierarchy() const { return hierarchy_; }
    FormFactorProvider& provider() { return *provider_; }
    const SolverOptions& options() const { return options_; }
    const Scene& scene() const { return *scene_; }

    /// An estimate of the irradiance still to arrive at every surface from the power not yet
    /// shot, RGB [W unit^-2]: an ambient term after Cohen, Chen, Wallace & Greenberg (1988)
    /// that knows light escapes. The unshot power U lands at the rate r (the power-weighted
    /// mean row sum of the patch and cluster shots so far; 1 before any), is reflected with
    /// rho (the area-weighted mean reflectance), lands again..., so the irradiance power still
    /// to arrive is U r / (1 - rho r), spread evenly over the scene's area A:
    ///     E_a = U r / ((1 - rho r) A)   per channel.
    /// solution() puts it into every read-out (Hierarchy::unshot_estimate()), so that an
    /// unconverged solution does not read low; the error bound still counts U as unshot.
    dvec3 ambient_irradiance() const;

    // Incremental re-solving (issue 21; incremental.cpp, scene_edit.h). An edit of the
    // scene's light turns the difference into unshot power, negative where light is removed,
    // and the usual shooting distributes it (the solver runs again: step() until converged):
    //   - a luminaire's multiplier f0 -> f1 (0 = off): (f1 - f0) P of unshot power; its direct
    //     light in read-outs (FinalGather) uses the new multiplier;
    //   - a reflectance rho0 -> rho1: dB = (rho1 - rho0) H on every leaf patch (H, the
    //     irradiance received, is kept per node: hierarchy.h); light received but not yet
    //     pushed to the leaves is reflected with rho1 when it is;
    //   - an emission Be0 -> Be1: dB = Be1 - Be0.
    // Shooter selection and the error bound count unshot power by its magnitude,
    // |dB| per channel (unshot_power()); the estimate of the light still to arrive
    // (ambient_irradiance()) keeps its sign. Throws InputError for a bad name or value
    // (scene_edit.h), or if the solver was built from a const Scene.
    /// Sets the multiplier of the luminaire named `name` (>= 0; 0 = off).
    void set_luminaire_multiplier(const std::string& name, double multiplier);
    /// Moves and aims the luminaire named `name` (scene_edit.h, set_luminaire_placement): its
    /// light leaves its old place at once (its light layer is taken out of the solution) and
    /// all its power is unshot at the new one. Needs light layers (has_light_layers(); else
    /// InputError: without them its old light could only be taken out from a luminaire that
    /// is no longer there). A change of the scene's geometry: a solution saved afterwards
    /// resumes only for the moved scene.
    void place_luminaire(const std::string& name, const dvec3& position, const dvec3& aim);
    /// Sets the reflectance of surface group `group` (each channel in [0, 1); untextured).
    void set_reflectance(const std::string& group, const dvec3& rho);
    /// Sets the emitted radiance Ke [W sr^-1 unit^-2] of surface group `group` (>= 0).
    void set_emission(const std::string& group, const dvec3& Ke);
    /// Turns the difference between the scene's photometry now and `before` (the photometry
    /// the solver's state was computed for: a resumed solution of an edited scene) into unshot
    /// power as the edits above do. Throws InputError if the sizes differ or a textured
    /// polygon's reflectance changed. Returns how many luminaires and polygons changed.
    std::pair<std::size_t, std::size_t> apply_photometry(const Photometry& before);
    /// Does the solver keep each luminaire's share apart (SolverOptions::light_layers)? Then a
    /// luminaire's multiplier edit from f0 > 0 is exact at once, with no shot.
    bool has_light_layers() const { return layers_ != nullptr; }
    /// How many luminaire edits so far were applied by rescaling a light layer.
    long rescaled_luminaires() const { return rescaled_; }

    /// Resets the timer origin (for resumed runs) and restores counters (save/resume).
    struct Counters {
        long shots = 0;
        dvec3 absorbed{0.0}, escaped{0.0};
        double row_min = 0, row_max = 0, row_total = 0;
        long row_guarded = 0;
        double landed = 0; ///< sum over patch and cluster shots of min(row sum, 1) * power [W]
        double shot = 0;   ///< sum over patch and cluster shots of their power [W]
        std::int64_t last_polygon = -1;
        double seconds = 0;
    };
    Counters counters() const;
    void restore(const Counters& c);

    /// The complete state that later shots depend on (save/resume, solution_file.h): resuming
    /// from it gives results bit-identical to a run that was never interrupted. Taken between
    /// steps and before solution() (whose push-pull would change the float sums' order).
    struct State {
        Counters counters;
        std::vector<Hierarchy::Node> nodes; ///< every node, in Hierarchy order
        std::vector<dvec3> unshot;          ///< per polygon, unshot power [W]
        std::vector<std::uint8_t> dirty;    ///< per polygon, needs a push-pull
        std::vector<std::uint8_t> enclosed; ///< per node, a view code (see Solver::view_)
        std::vector<double> provider;       ///< FormFactorProvider::save_state()
        std::vector<dvec3> luminaires;      ///< per luminaire, unshot power [W]
        std::vector<std::uint8_t> clusters; ///< per cluster-tree node, a view code
        /// Per luminaire, its share of the solution (light_layers.h), or none (no layers).
        struct Layer {
            std::vector<Hierarchy::Node> nodes;
            std::vector<dvec3> unshot;
            std::vector<std::uint8_t> dirty;
            dvec3 absorbed{0.0}, escaped{0.0}; ///< of the luminaire's light [W]
        };
        std::vector<Layer> layers;
    };
    State save_state() const;
    /// Restores a state saved by a solver with the same scene and options. Throws InputError
    /// if the sizes do not fit this solver's hierarchy or provider, or a value is not finite.
    /// A state without light layers drops this solver's (an edit is then shot); one with
    /// layers, restored into a solver without, drops them.
    void restore_state(const State& state);

  private:
    void init();
    Scene& editable_scene(const char* what); ///< the scene, if built from a modifiable one
    dvec3 signed_unshot_power() const;       ///< unshot power, signs kept
    PatchAddress select_shooter(std::uint32_t polygon);
    void shoot_luminaire(std::size_t k, ShotRecord& rec);
    /// Multiplies each link's form factor by the transmittance of the window panes between
    /// `origin` (the shooting point) and its receiver's centre (Scene::glazing; none: nothing).
    void attenuate_through_glazing(const dvec3& origin);
    /// Delivers the links of a shot of unshot radiosity dB from a shooter of area A_S (a
    /// luminaire: its power, A_S = 1): row sum, guard, receive, absorbed and escaped power.
    /// Returns the guard's scale of the form factors (1 when the row was not rescaled).
    double deliver(const dvec3& dB, double area_s, ShotRecord& rec);
    /// Luminaire k's light-layer share of the solution times s (LightLayers::rescale), its
    /// absorbed and escaped power with it.
    void rescale_layer(std::size_t k, double s);
    void finish_shot(ShotRecord& rec, std::chrono::steady_clock::time_point start);
    void check_stop();
    /// Shoots from `polygon` (pushed): the greedy shooter, replaced by its children while
    /// must_split says so. Returns the shooter, its unshot radiosity and area; links_ holds
    /// its links and learned_ the view codes measured.
    PatchAddress shoot_patch(std::uint32_t polygon, ShotRecord& rec, dvec3& dB, double& area_s);
    /// Adds the provider's timings of its last shoot() to rec.ff_phases.
    void add_timings(ShotRecord& rec) const;
    /// Does a patch shot's row (links_ for `shooter`) exceed 1 + row_refine with surfaces
    /// nearer than the shooter's size in view (SolverOptions::row_refine)?
    bool overcounted(const Shooter& shooter, const std::vector<Link>& links) const;
    /// Shoots `whole` (a leaf, or a part of one) as its quarters, each from its own centre;
    /// where they took at least half the excess of `whole_row` (the whole's row from its
    /// centre) away, a quarter still overcounted as its own quarters, while `levels` > 1.
    /// `links` becomes their links, summed (F(j->S) is the sum of F(j->part)).
    void shoot_parts(const Shooter& whole, double whole_row, int levels, std::vector<Link>& links,
                     ShotRecord& rec);
    /// sum_j F(j->S) A_j / A_S of `links` for a shooter of area `area_s`.
    double row_of(const std::vector<Link>& links, double area_s) const;
    bool step_round(); ///< step() with a collective of more than one rank (solver_round.cpp)
    /// Shoots the cluster tree's shooter, a cluster node; or returns false, leaving in
    /// `polygon` the polygon to shoot when the descent ends at a single polygon.
    bool shoot_cluster(ShotRecord& rec, std::uint32_t& polygon);
    /// Whether more than kHiddenFromCentre of cluster c's light (its members' unshot `power`)
    /// cannot leave from its centre (light_hidden_from_centre).
    bool light_hidden(const ClusterShooter& c, const std::vector<double>& power);
    /// The BVH of the clusters' ray casts (cluster_bvh_), built on the first call.
    const Bvh& cluster_bvh();
    void update_cluster_power();
    bool must_split_cluster(std::uint32_t node) const;

    const Scene* scene_;
    Scene* editable_ = nullptr; ///< the same scene, when built from a modifiable one
    SolverOptions options_;
    Hierarchy hierarchy_;
    std::unique_ptr<FormFactorProvider> provider_;
    std::unique_ptr<GlazingTracer> glazing_; ///< the scene's window panes (glazing.h)
    std::vector<Link> links_;
    std::vector<dvec3> luminaire_unshot_;
    bool must_split(std::uint64_t node) const;
    /// Is the node's view unknown, or predicted near the limit of must_split()?
    bool worth_probing(std::uint64_t node) const;
    /// Does the plane of a polygon in front of the node pass through it, near enough and
    /// with enough of the node's power to matter (plane_cuts.h)?
    bool cut_by_plane(const PatchAddress& a) const;

    /// Per node, what its hemicube showed, once measured: 0 not yet, 1 enclosed centre (always
    /// shoot the children), 2..255 its parallax fraction, P = 1e-4 * 2^((code - 2) / 16).
    std::vector<std::uint8_t> view_;
    std::vector<std::pair<std::uint64_t, std::uint8_t>> learned_; ///< view_ codes of this shot
    std::unique_ptr<PlaneCuts> plane_cuts_;                       ///< null: no shooter refinement
    std::unique_ptr<ClusterTree> clusters_;  ///< null: clusters off (or a CPU provider)
    std::unique_ptr<Bvh> cluster_bvh_;       ///< the clusters' ray casts, built when needed
    std::vector<double> cluster_power_;      ///< per cluster node, unshot power summed over RGB
    std::vector<std::uint8_t> cluster_view_; ///< per cluster node, a view code (as view_)
    std::unique_ptr<LightLayers> layers_;    ///< null: no light layers (light_layers.h)
    long rescaled_ = 0;                      ///< luminaire edits applied by rescaling
    ShotRecord last_;
    std::vector<ShotRecord> round_;
    Collective* collective_ = nullptr;
    ParallelStats parallel_;
    double apply_seconds_ = 0; ///< this rank's time applying the last round (parallel)
    long shots_ = 0;
    StopReason stop_ = StopReason::Running;
    dvec3 emitted_{0.0}, absorbed_{0.0}, escaped_{0.0};
    dvec3 peak_emitted_{0.0}; ///< the most emitted before and after edits (incremental.cpp)
    /// What the sun and the sky delivered before the first shot (init()), part of emitted_:
    /// not the scene's to change, so an edit keeps it (apply_photometry).
    dvec3 daylight_{0.0};
    double rho_max_ = 0;
    double min_size_ = 0;
    double max_size_ = 0;
    double row_min_ = 1e300, row_max_ = 0, row_total_ = 0;
    long row_guarded_ = 0;
    double landed_ = 0, shot_ = 0; ///< Counters::landed, Counters::shot
    std::int64_t last_polygon_ = -1;
    double seconds_ = 0;
};

} // namespace hemirad
