// Progressive shooting over the patch hierarchy with greedy shooter selection and lazy
// push-pull (paper 002 §2, §4.1-4.2), error bound from paper 001 (eq. 27, 33).
#include "hemirad/solver.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "ff/bvh.h"
#include "ff/glazing_tracer.h"
#include "hemirad/error.h"
#include "hemirad/memory_guard.h"
#include "hemirad/solver_options.h"
#include "solver/cluster_tree.h"
#include "solver/light_layers.h"
#include "solver/plane_cuts.h"
#include "solver/sky_light.h"
#include "solver/solver_detail.h"
#include "solver/sun_light.h"

namespace hemirad {

using solver_detail::Clock;
using solver_detail::deliver_links;
using solver_detail::has_negative;
using solver_detail::magnitude;
using solver_detail::node_power;
using solver_detail::since;
using solver_detail::sum;

void validate_options(const SolverOptions& o) {
    validate_solver_options(o, SolverOption::Check::Solver); // the ranges: solver_options.h
    if (is_gpu_provider(o.ff)) validate_gpu_options(o.provider.gpu);
}

namespace {

// View codes (Solver::view_, cluster_view_): what a shooter's hemicube showed. 0 not known,
// 1 an enclosed centre; 2..127 a measured parallax fraction (clusters: parallax plus near
// light), P = 1e-4 * 2^((code - 2) / 8); the same plus 128: predicted from the parent's,
// not yet measured (a node whose parent was refused inherits its parent's share scaled by
// its size: the band a silhouette moves across grows with the shooter's size).
// 127: its row ran over with surfaces near it in view (Solver::overcounted): a node shoots
// its children, a leaf its parts; 126: a leaf whose parts did not bring its row down (it
// shoots from its centre). A parallax fraction never reaches these codes (4.3 and more).
constexpr std::uint8_t kViewUnknown = 0, kViewEnclosed = 1, kViewPartsInVain = 126,
                       kViewOvercounted = 127, kViewPredicted = 128;
std::uint8_t parallax_code(double p, bool predicted = false) {
    const double c = 2 + std::round(8 * std::log2(std::max(p, 1e-4) / 1e-4));
    return std::uint8_t(std::clamp(c, 2.0, 125.0)) | (predicted ? kViewPredicted : 0);
}
double code_parallax(std::uint8_t code) {
    return 1e-4 * std::exp2(((code & 127) - 2) / 8.0);
}
bool measured(std::uint8_t code) {
    return code != kViewUnknown && !(code & kViewPredicted);
}

// Shooter::emission: a shooter's unshot radiosity is uneven (a wall half in a desk's
// shadow) where its nodes this many levels below differ by more than kUnevenEmission. Near
// receivers then weight its parts by their radiosity: the back of a whiteboard 1.3 cm from
// a wall sees the dark wall behind the board, not the wall's mean.
constexpr int kEmissionLevels = 3;
constexpr double kUnevenEmission = 1.5;

// A leaf whose row runs over (Solver::overcounted) shoots as its quarters, and a quarter
// whose row runs over too as its own: two levels, 4 to 20 hemicubes.
constexpr int kRowPartLevels = 2;

void describe_emission(const Hierarchy& h, Shooter& s) {
    s.emission.clear();
    s.emission_levels = 0;
    const PatchAddress& a = s.address;
    const int levels = std::min(kEmissionLevels, h.depth(a.polygon) - int(a.level));
    const double mean = magnitude(dvec3(h.node(a).dB));
    if (levels <= 0 || !(mean > 0)) return;
    const bool tri = h.scene().polygons[a.polygon].is_triangle();
    double lo = 1e300, hi = 0;
    const auto visit = [&](const auto& self, std::uint32_t level, std::uint32_t index) -> void {
        for (std::uint32_t c : patch_children(tri, level, index)) {
            const double w = magnitude(dvec3(h.node({a.polygon, level + 1, c}).dB)) / mean;
            s.emission.push_back(float(w));
            if (int(level + 1 - a.level) < levels)
                self(self, level + 1, c);
            else
                lo = std::min(lo, w), hi = std::max(hi, w);
        }
    };
    visit(visit, a.level, a.index);
    if (hi > kUnevenEmission * lo)
        s.emission_levels = levels;
    else
        s.emission.clear();
}

// A cluster lobe's planes (ClusterShooter::add_lobe_planes): polygons whose planes lie more
// than this share of the cluster's radius apart shoot from planes of their own (a 3.75 m
// cluster keeps a 20 cm slab's faces apart down to 4 mm), at most kLobePlanes a lobe.
constexpr double kLobePlaneGap = 1e-3;
constexpr std::size_t kLobePlanes = 16;
// A cluster whose centre lies between two of its polygons closer than this share of its
// radius (in_thin_gap) is refused: 15 % keeps a 3.75 m cluster's centre out of a 20 cm wall
// while a room's clusters shoot from the air between its floor and ceiling.
constexpr double kThinGap = 0.15;
// A cluster whose light comes from away from its centre (the centroid of its polygons'
// unshot power farther from it than this share of its radius) is refused: its point would
// send that light from where it does not leave. In the office glb a median split left a
// bar of an LED light in a cluster of three with two faces of a bookshelf 1.5 m away; from
// their area-weighted centre, 7 mm in front of the shelf's side, 99.9 % of the bar's light
// went into that side.
constexpr double kLightOffCentre = 0.5;
// A cluster more than this share of whose light cannot leave from its centre (the points of
// its polygons that carry it do not see the centre: light_hidden_from_centre) is refused. In
// the office glb lit by three point sources a cluster of a bookshelf board's underside and
// the inner face of the wall slab behind it (7.5 m², so that their area-weighted centre lay
// in the slab) shot the board's light into the slab: 51 of 674 dark points leaked, 14 with
// this rule (at 0.5 and 0.65 too, for more shots).
constexpr double kHiddenFromCentre = 0.8;

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool finite(const dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// The discretisation, once the memory guard has found that it fits (memory_guard.h).
Discretisation guarded_discretise(const Scene& scene, const SolverOptions& options) {
    Discretisation d = discretise(scene, options.hierarchy);
    check_memory(scene, d, options);
    return d;
}

} // namespace

const char* to_string(StopReason r) {
    switch (r) {
    case StopReason::Running:
        return "running";
    case StopReason::Converged:
        return "converged";
    case StopReason::MaxShots:
        return "max-shots";
    case StopReason::TimeLimit:
        return "time-limit";
    case StopReason::NothingToShoot:
        return "nothing-to-shoot";
    }
    return "?";
}

Solver::Solver(const Scene& scene, const SolverOptions& options)
    : scene_(&scene), options_((validate_options(options), options)),
      hierarchy_(scene, guarded_discretise(scene, options)) {
    provider_ = make_provider(options.ff, scene, hierarchy_.discretisation(), options.provider);
    init();
}

Solver::Solver(const Scene& scene, const SolverOptions& options,
               std::unique_ptr<FormFactorProvider> provider)
    : scene_(&scene), options_((validate_options(options), options)),
      hierarchy_(scene, guarded_discretise(scene, options)), provider_(std::move(provider)) {
    HEMIRAD_CHECK(provider_ != nullptr);
    init();
}

Solver::~Solver() = default;

void Solver::init() {
    view_.assign(hierarchy_.node_count(), kViewUnknown);
    const bool clusters = options_.clusters == "on" || (options_.clusters == "auto" &&
                                                        scene_->polygons.size() > kClusterPolygons);
    if (clusters && provider_->can_shoot_clusters() && scene_->polygons.size() > 1) {
        clusters_ = std::make_unique<ClusterTree>(*scene_);
        cluster_power_.assign(clusters_->nodes().size(), 0.0);
        cluster_view_.assign(clusters_->nodes().size(), kViewUnknown);
    }
    // Each luminaire's share of the solution apart, for edits without shots (light_layers.h).
    if (LightLayers::wanted(options_.light_layers, hierarchy_, clusters_ != nullptr))
        layers_ = std::make_unique<LightLayers>(hierarchy_);
    // Window panes (glazing.h) are no polygons: hemicubes look through them, and the links they
    // find are attenuated by the panes between (attenuate_through_glazing).
    if (!scene_->glazing.empty()) glazing_ = std::make_unique<GlazingTracer>(*scene_);
    // Polygons whose plane cuts a shooter: the hemicube shows them edge-on (plane_cuts.h).
    if (options_.shooter_parallax > 0) plane_cuts_ = std::make_unique<PlaneCuts>(*scene_, 1.0);
    emitted_ = scene_->emitted_power();
    peak_emitted_ = emitted_;
    luminaire_unshot_.clear();
    for (const Luminaire& l : scene_->luminaires) luminaire_unshot_.push_back(dvec3(l.power()));
    // The sun's direct light, once, before the first shot (sun_light.h): what it delivers is
    // emitted power, its reflected part the leaves' unshot power. The sky's (and the
    // ground's) likewise (sky_light.h); their shadow rays share one BVH.
    daylight_ = dvec3(0.0);
    if (scene_->sun || scene_->sky) {
        const Bvh bvh(*scene_);
        const GlazingTracer panes(*scene_);
        const SunDelivery sun = deliver_sunlight(*scene_, bvh, panes, hierarchy_);
        const SkyDelivery sky = deliver_skylight(*scene_, bvh, panes, hierarchy_);
        absorbed_ += sun.absorbed + sky.absorbed;
        daylight_ = sun.power + sky.power;
    }
    emitted_ += daylight_;
    rho_max_ = scene_->max_reflectance();
    // Default minimum shooter size: the size of the smallest leaf patches' polygons' leaves.
    max_size_ = options_.shooter_max_size > 0 ? options_.shooter_max_size : 1e300;
    min_size_ = options_.shooter_min_size;
    if (min_size_ <= 0) {
        double smallest = 1e300;
        for (std::size_t p = 0; p < scene_->polygons.size(); ++p) {
            const double leaf = std::sqrt(scene_->polygons[p].area) /
                                double(1u << hierarchy_.depth(std::uint32_t(p)));
            smallest = std::min(smallest, leaf);
        }
        min_size_ = 0.5 * smallest;
    }
    check_stop();
}

double Solver::seconds() const {
    return seconds_;
}

dvec3 Solver::unshot_power() const {
    dvec3 u(0.0);
    for (const dvec3& p : hierarchy_.unshot_powers()) u += glm::abs(p);
    for (const dvec3& l : luminaire_unshot_) u += glm::abs(l);
    return u;
}

double Solver::unshot_fraction() const {
    const dvec3 u = unshot_power();
    double f = 0;
    for (int c = 0; c < 3; ++c) {
        // A channel an edit switched off entirely: relative to what it emitted before.
        const double e = emitted_[c] > 0 ? emitted_[c] : peak_emitted_[c];
        if (e > 0) f = std::max(f, u[c] / e);
    }
    return f;
}

double Solver::error_bound() const {
    return unshot_fraction() / (1.0 - rho_max_);
}

void Solver::check_stop() {
    if (error_bound() <= options_.tolerance)
        stop_ = StopReason::Converged;
    else if (shots_ >= options_.max_shots)
        stop_ = StopReason::MaxShots;
    else if (options_.time_limit > 0 && seconds_ >= options_.time_limit)
        stop_ = StopReason::TimeLimit;
    else if (sum(unshot_power()) <= 0)
        stop_ = StopReason::NothingToShoot;
    else
        stop_ = StopReason::Running;
}

PatchAddress Solver::select_shooter(std::uint32_t polygon) {
    const bool tri = scene_->polygons[polygon].is_triangle();
    const int depth = hierarchy_.depth(polygon);
    const double threshold = options_.shooter_power_fraction * sum(unshot_power());
    PatchAddress a{polygon, 0, 0};
    while (int(a.level) < depth) {
        const std::uint64_t id = hierarchy_.node_id(a);
        const bool refused = must_split(id);
        const bool split = refused || cut_by_plane(a);
        if (refused && view_[id] != kViewEnclosed && view_[id] != kViewOvercounted) {
            // Refused for parallax: the children, half as large, inherit half its share (a
            // prediction that spares rendering a hemicube only to refuse it).
            const std::uint8_t predicted = parallax_code(0.5 * code_parallax(view_[id]), true);
            for (std::uint32_t c : patch_children(tri, a.level, a.index)) {
                const std::uint64_t cid = hierarchy_.node_id({polygon, a.level + 1, c});
                if (int(a.level) + 1 < depth && view_[cid] == kViewUnknown) {
                    view_[cid] = predicted;
                    learned_.emplace_back(cid, predicted);
                }
            }
        }
        const bool must_descend = split || std::sqrt(double(hierarchy_.node(a).area)) > max_size_;
        PatchAddress best = a;
        double best_power = -1;
        for (std::uint32_t c : patch_children(tri, a.level, a.index)) {
            const PatchAddress ca{polygon, a.level + 1, c};
            const double power = node_power(hierarchy_.node(ca));
            if (power > best_power) best_power = power, best = ca;
        }
        if (!options_.flat && !must_descend) {
            const double size = std::sqrt(double(hierarchy_.node(best).area));
            if (best_power < threshold || size < min_size_) break;
        }
        a = best;
    }
    return a;
}

bool Solver::step() {
    check_stop();
    if (stop_ != StopReason::Running) return false;
    round_.clear();
    if (collective_ && collective_->size() > 1) return step_round();
    const auto t_start = Clock::now();
    ShotRecord rec;
    rec.shot = shots_ + 1;

    // 1. Select: the polygon with the greatest unshot power, push-pulled, then greedy descent.
    auto t0 = Clock::now();
    std::uint32_t polygon = 0;
    double best = -1;
    bool negative = false; // an edit's negative power (incremental.cpp): no cluster shots
    for (std::uint32_t p = 0; p < scene_->polygons.size(); ++p) {
        const auto unshot = hierarchy_.unshot_power(p);
        const double u = magnitude(unshot);
        negative = negative || has_negative(unshot);
        if (u > best) best = u, polygon = p;
    }
    // A luminaire competes with the polygons by its unshot power (all of it, until it shoots).
    std::size_t luminaire = 0;
    double best_luminaire = 0;
    for (std::size_t k = 0; k < luminaire_unshot_.size(); ++k) {
        const double u = magnitude(luminaire_unshot_[k]);
        if (u > best_luminaire) best_luminaire = u, luminaire = k;
    }
    rec.t_select = since(t0);
    if (best_luminaire > 0 && best_luminaire >= best) {
        shoot_luminaire(luminaire, rec);
        finish_shot(rec, t_start);
        return true;
    }
    // Clusters: the descent from the cluster tree's root ends at a cluster, which shoots, or
    // at a single polygon, which shoots as a patch.
    if (clusters_ && !negative && shoot_cluster(rec, polygon)) {
        finish_shot(rec, t_start);
        return true;
    }
    t0 = Clock::now();
    if (hierarchy_.needs_push_pull(polygon)) hierarchy_.push_pull(polygon);
    if (layers_) layers_->push_pull(polygon);
    rec.t_push_pull = since(t0);
    dvec3 dB;
    double area_s = 0;
    const PatchAddress sa = shoot_patch(polygon, rec, dB, area_s);

    // 3. Update: dI_j += F(j->S) dB_S (irradiance); row sum sum_j F(j->S) A_j / A_S.
    const double scale = deliver(dB, area_s, rec);
    auto t1 = Clock::now();
    if (layers_) layers_->deliver_patch(sa, area_s, links_, scale);
    hierarchy_.clear_unshot(sa);
    rec.t_update += since(t1);
    last_polygon_ = polygon;
    finish_shot(rec, t_start);
    return true;
}

PatchAddress Solver::shoot_patch(std::uint32_t polygon, ShotRecord& rec, dvec3& dB,
                                 double& area_s) {
    learned_.clear();
    const Polygon& poly = scene_->polygons[polygon];
    PatchAddress sa;
    Shooter shooter;
    Clock::time_point t0;
    for (;;) {
        t0 = Clock::now();
        sa = select_shooter(polygon);
        rec.t_select += since(t0);
        shooter.address = sa;
        shooter.geometry = patch_geometry(poly, sa.level, sa.index);
        shooter.normal = poly.normal;
        dB = dvec3(hierarchy_.node(sa).dB);
        area_s = double(hierarchy_.node(sa).area);
        shooter.unshot_power = magnitude(dB) * area_s;
        const double total = sum(unshot_power());
        shooter.power_fraction = total > 0 ? std::min(1.0, shooter.unshot_power / total) : 1.0;
        describe_emission(hierarchy_, shooter);

        // A node whose view nothing is known of yet, or whose predicted view is near the
        // limit, is measured on a coarse hemicube first, where the provider has one: a
        // refused node then costs a fraction of a shot. Other nodes with a predicted view
        // (nearly all are accepted) are measured on their own hemicube after the shot.
        const bool inner = int(sa.level) < hierarchy_.depth(polygon);
        if (inner) {
            const std::uint64_t id = hierarchy_.node_id(sa);
            FormFactorProvider::ViewProbe probe;
            t0 = Clock::now();
            if (worth_probing(id) && provider_->probe_view(shooter, probe)) {
                ++rec.probes;
                view_[id] = probe.enclosed > options_.enclosed_fraction
                                ? kViewEnclosed
                                : parallax_code(probe.parallax);
                learned_.emplace_back(id, view_[id]);
            }
            rec.t_form_factors += since(t0);
            if (measured(view_[id]) && must_split(id)) {
                ++rec.refined;
                continue;
            }
        }

        // 2. Form factors F(j -> S) for every receiving node.
        t0 = Clock::now();
        const std::uint64_t id = hierarchy_.node_id(sa);
        if (!inner && view_[id] == kViewOvercounted) { // as before: its parts, not its centre
            shoot_parts(shooter, 1e300, kRowPartLevels, links_, rec);
            rec.t_form_factors += since(t0);
            break;
        }
        provider_->shoot(shooter, links_);
        add_timings(rec);
        rec.t_form_factors += since(t0);
        // An enclosed centre would lose the patch's power, and a centre beside a near
        // occluder would misplace it (parallax), or see what parts of the patch do not (its
        // row runs over): shoot the children instead, or a leaf's quarters.
        rec.parallax = -1;
        if (inner) {
            if (!measured(view_[id])) { // no probe: measured on the shot's own hemicube
                view_[id] = provider_->last_enclosed_fraction() > options_.enclosed_fraction
                                ? kViewEnclosed
                                : parallax_code(provider_->last_parallax_fraction());
                learned_.emplace_back(id, view_[id]);
            }
            if (view_[id] != kViewEnclosed) rec.parallax = code_parallax(view_[id]);
            if (!must_split(id) && overcounted(shooter, links_)) {
                view_[id] = kViewOvercounted;
                learned_.emplace_back(id, view_[id]);
            }
            if (must_split(id)) {
                ++rec.refined;
                ++rec.discarded;
                continue;
            }
        } else if (view_[id] == kViewUnknown && int(sa.level) < kMaxDepth &&
                   overcounted(shooter, links_)) {
            t0 = Clock::now();
            ++rec.discarded;
            const double row = row_of(links_, shooter.geometry.area);
            shoot_parts(shooter, row, kRowPartLevels, links_, rec);
            // Parts that take less than half the excess away see what the centre saw (a row
            // over 1 for another reason): the leaf shoots from its centre from now on.
            const double parts_row = row_of(links_, shooter.geometry.area);
            view_[id] = parts_row - 1 < 0.5 * (row - 1) ? kViewOvercounted : kViewPartsInVain;
            learned_.emplace_back(id, view_[id]);
            rec.t_form_factors += since(t0);
        }
        break;
    }
    attenuate_through_glazing(shooter.geometry.centre);
    rec.shooter = sa;
    rec.shooter_power = shooter.unshot_power;
    rec.links = links_.size();
    return sa;
}

void Solver::add_timings(ShotRecord& rec) const {
    // Every hemicube of the shot counts, those of nodes whose children shoot instead too.
    for (const FormFactorProvider::Timing& t : provider_->last_timings()) {
        auto it = std::find_if(rec.ff_phases.begin(), rec.ff_phases.end(),
                               [&](const auto& p) { return !std::strcmp(p.phase, t.phase); });
        if (it == rec.ff_phases.end())
            rec.ff_phases.push_back(t);
        else
            it->seconds += t.seconds;
    }
}

double Solver::row_of(const std::vector<Link>& links, double area_s) const {
    double row = 0;
    for (const Link& l : links) row += double(l.ff) * double(hierarchy_.node(l.receiver).area);
    return row / area_s;
}

// The centre's view is one point's: where something stands within the shooter's reach,
// parts of the shooter see less of the room than the centre (a desk's underside over a
// shelf 5.7 cm below part of it gave the floor 2 % too much, row 1.0088), or more (what the
// shelf hides from the centre). Rays from the parts (the provider's see_from_parts) take
// away the first and cannot add the second; the parts' own hemicubes see both. Rows over 1
// for other reasons (the hybrid's analytic values at nodes' centres: room402's ceiling
// lights, 1.001-1.005, nothing near them) would not fall with smaller shooters, so a row
// counts only with surfaces within the shooter's size in view.
bool Solver::overcounted(const Shooter& shooter, const std::vector<Link>& links) const {
    if (!(options_.row_refine > 0)) return false;
    if (!(row_of(links, shooter.geometry.area) > 1 + options_.row_refine)) return false;
    return provider_->last_sees_within(std::sqrt(shooter.geometry.area));
}

void Solver::shoot_parts(const Shooter& whole, double whole_row, int levels,
                         std::vector<Link>& links, ShotRecord& rec) {
    const Polygon& poly = scene_->polygons[whole.address.polygon];
    const std::uint32_t level = whole.address.level + 1;
    const auto children =
        patch_children(poly.is_triangle(), whole.address.level, whole.address.index);
    std::array<Shooter, 4> quarter;
    std::array<std::vector<Link>, 4> part;
    std::array<double, 4> row{};
    double sum = 0;
    for (std::size_t k = 0; k < 4; ++k) {
        Shooter& q = quarter[k];
        q = whole;
        q.address = {whole.address.polygon, level, children[k]};
        q.geometry = patch_geometry(poly, level, children[k]);
        const double share = q.geometry.area / whole.geometry.area;
        q.unshot_power = whole.unshot_power * share;
        q.power_fraction = whole.power_fraction * share;
        q.emission.clear(); // a leaf's radiosity is even
        q.emission_levels = 0;
        provider_->shoot(q, part[k]);
        add_timings(rec);
        ++rec.parts;
        row[k] = overcounted(q, part[k]) ? row_of(part[k], q.geometry.area) : 0;
        sum += row_of(part[k], whole.geometry.area);
    }
    // Deeper only where splitting works, the quarters having taken at least half the excess
    // away: a quarter still over goes on as its own quarters.
    if (levels > 1 && int(level) < kMaxDepth && sum - 1 < 0.5 * (whole_row - 1))
        for (std::size_t k = 0; k < 4; ++k)
            if (row[k] > 0) shoot_parts(quarter[k], row[k], levels - 1, part[k], rec);
    links.clear();
    for (const std::vector<Link>& p : part) links.insert(links.end(), p.begin(), p.end());
}

// A luminaire shoots all its power once, over the whole sphere (FormFactorProvider::
// shoot_point): E_j = ff_j * P, its row sum the fraction of P received.
void Solver::shoot_luminaire(std::size_t k, ShotRecord& rec) {
    const dvec3 power = luminaire_unshot_[k];
    rec.luminaire = int(k);
    rec.shooter = {0xFFFFFFFFu, 0, 0};
    rec.shooter_power = magnitude(power);
    auto t0 = Clock::now();
    Luminaire spare;
    provider_->shoot_point(solver_detail::shooting_luminaire(scene_->luminaires[k], spare), links_);
    attenuate_through_glazing(scene_->luminaires[k].position);
    rec.t_form_factors = since(t0);
    rec.ff_phases = provider_->last_timings();
    rec.links = links_.size();
    const double scale = deliver(power, 1.0, rec);
    if (layers_) layers_->deliver_luminaire(k, power, links_, scale);
    luminaire_unshot_[k] = dvec3(0.0);
}

void Solver::update_cluster_power() {
    const std::vector<ClusterTree::Node>& nodes = clusters_->nodes();
    for (std::size_t i = nodes.size(); i-- > 0;) {
        const ClusterTree::Node& n = nodes[i];
        cluster_power_[i] = n.leaf()
                                ? magnitude(hierarchy_.unshot_power(clusters_->order()[n.begin]))
                                : cluster_power_[n.left] + cluster_power_[n.right];
    }
}

bool Solver::must_split_cluster(std::uint32_t node) const {
    const std::uint8_t code = cluster_view_[node];
    if (code == kViewEnclosed) return true;
    if (code == kViewUnknown || options_.cluster_parallax <= 0) return false;
    return code_parallax(code) * cluster_power_[node] > options_.cluster_parallax * sum(emitted_);
}

const Bvh& Solver::cluster_bvh() {
    if (!cluster_bvh_) cluster_bvh_ = std::make_unique<Bvh>(*scene_);
    return *cluster_bvh_;
}

bool Solver::light_hidden(const ClusterShooter& c, const std::vector<double>& power) {
    const std::vector<double> hidden = light_hidden_from_centre(*scene_, cluster_bvh(), c.members,
                                                                power, c.centre, 1e-4 * c.radius);
    double all = 0, not_seen = 0;
    for (std::size_t i = 0; i < power.size(); ++i) {
        all += power[i];
        not_seen += power[i] * hidden[i];
    }
    return not_seen > kHiddenFromCentre * all;
}

bool Solver::shoot_cluster(ShotRecord& rec, std::uint32_t& polygon) {
    auto t0 = Clock::now();
    update_cluster_power();
    const ClusterTree& tree = *clusters_;
    const double total = sum(unshot_power());
    const double threshold = options_.shooter_power_fraction * total;
    std::uint32_t node = 0;
    for (;;) {
        const ClusterTree::Node& n = tree.node(node);
        if (n.leaf()) {
            polygon = tree.order()[n.begin];
            rec.t_select += since(t0);
            return false;
        }
        const std::uint32_t best =
            cluster_power_[n.left] >= cluster_power_[n.right] ? n.left : n.right;
        const bool split = must_split_cluster(node);
        if (split && cluster_view_[node] != kViewEnclosed) {
            // Refused: the children inherit its misplaced share scaled by their size.
            for (std::uint32_t c : {n.left, n.right})
                if (cluster_view_[c] == kViewUnknown && !tree.node(c).leaf())
                    cluster_view_[c] =
                        parallax_code(code_parallax(cluster_view_[node]) * tree.node(c).radius() /
                                          std::max(n.radius(), 1e-300),
                                      true);
        }
        if (cluster_power_[best] >= threshold || split) {
            node = best;
            continue;
        }
        rec.t_select += since(t0);
        // Its polygons, pushed, and what they emit: the lobes of their normals (within about
        // 14 degrees merged), weighted by their unshot power.
        t0 = Clock::now();
        ClusterShooter c;
        c.members.assign(tree.order().begin() + n.begin, tree.order().begin() + n.end);
        std::sort(c.members.begin(), c.members.end());
        dvec3 power(0.0), centre(0.0), axis(0.0);
        std::vector<dvec3> member_unshot(c.members.size());
        std::vector<double> member_power(c.members.size(), 0.0);
        for (std::size_t i = 0; i < c.members.size(); ++i) {
            const std::uint32_t m = c.members[i];
            if (hierarchy_.needs_push_pull(m)) hierarchy_.push_pull(m);
            member_unshot[i] = hierarchy_.unshot_power(m);
            member_power[i] = std::max(0.0, sum(member_unshot[i]));
        }
        rec.t_push_pull += since(t0);
        // It shoots from the area-weighted centre of its polygons: a point that does not move
        // with its light, so that what its hemicube showed once holds at the next shot.
        double area = 0;
        for (std::uint32_t m : c.members) {
            const Polygon& poly = scene_->polygons[m];
            centre += poly.area * poly.centroid();
            area += poly.area;
        }
        c.centre = centre / area;
        double r2 = 0;
        for (std::uint32_t m : c.members) {
            const Polygon& poly = scene_->polygons[m];
            for (int k = 0; k < poly.count; ++k) {
                const dvec3 d = poly.v[k] - c.centre;
                r2 = std::max(r2, glm::dot(d, d));
            }
        }
        c.radius = std::sqrt(r2);
        // What they emit: the lobes of their normals (within about 14 degrees merged),
        // weighted by their unshot power.
        double weight = 0;
        std::vector<dvec3> lobe_sum;
        std::vector<std::pair<std::size_t, std::uint32_t>> lobe_members; // (lobe, polygon)
        for (std::size_t i = 0; i < c.members.size(); ++i) {
            const std::uint32_t m = c.members[i];
            const double w = member_power[i];
            if (!(w > 0)) continue;
            const Polygon& poly = scene_->polygons[m];
            power += member_unshot[i];
            weight += w;
            axis += w * poly.normal;
            std::size_t k = 0;
            for (; k < lobe_sum.size(); ++k)
                if (glm::dot(glm::normalize(lobe_sum[k]), poly.normal) > 0.97) break;
            if (k == lobe_sum.size()) {
                if (lobe_sum.size() < 32) {
                    lobe_sum.push_back(dvec3(0.0));
                    c.weights.push_back(0);
                } else { // the closest lobe
                    double best_dot = -2;
                    for (std::size_t q = 0; q < lobe_sum.size(); ++q) {
                        const double d = glm::dot(glm::normalize(lobe_sum[q]), poly.normal);
                        if (d > best_dot) best_dot = d, k = q;
                    }
                }
            }
            lobe_sum[k] += w * poly.normal;
            c.weights[k] += w;
            lobe_members.emplace_back(k, m);
        }
        if (!(weight > 0)) { // nothing to shoot after all (cannot happen: the node has power)
            node = best;
            continue;
        }
        for (std::size_t k = 0; k < lobe_sum.size(); ++k) {
            const double len = glm::length(lobe_sum[k]);
            c.normals.push_back(len > 0 ? lobe_sum[k] / len : dvec3(0, 1, 0));
            c.weights[k] /= weight;
        }
        const double axis_len = glm::length(axis);
        c.axis = axis_len > 1e-6 * weight ? axis / axis_len : dvec3(0, 1, 0);
        // A centre inside a wall or a panel of its own polygons (both faces of a slab among
        // them), or away from where the light leaves: never shot, as an enclosed one (its
        // halves are taken instead).
        if (!measured(cluster_view_[node]) &&
            (light_off_centre(*scene_, c.members, member_power, c.centre,
                              kLightOffCentre * c.radius) ||
             in_thin_gap(*scene_, c.members, c.centre, kThinGap * c.radius) ||
             light_hidden(c, member_power))) {
            cluster_view_[node] = kViewEnclosed;
            ++rec.refined;
            node = best;
            t0 = Clock::now();
            continue;
        }
        // Each lobe's planes: its polygons' lowest corners along its normal, with their power.
        std::vector<std::vector<ClusterShooter::Plane>> lobe_planes(lobe_sum.size());
        for (const auto& [k, m] : lobe_members) {
            const Polygon& poly = scene_->polygons[m];
            ClusterShooter::Plane p;
            p.offset = 1e300;
            p.lo = dvec3(1e300);
            p.hi = dvec3(-1e300);
            for (int q = 0; q < poly.count; ++q) {
                p.offset = std::min(p.offset, glm::dot(c.normals[k], poly.v[q]));
                p.lo = glm::min(p.lo, poly.v[q]);
                p.hi = glm::max(p.hi, poly.v[q]);
            }
            p.weight = sum(hierarchy_.unshot_power(m)) / weight;
            lobe_planes[k].push_back(p);
        }
        for (std::size_t k = 0; k < lobe_planes.size(); ++k)
            c.add_lobe_planes(std::uint32_t(k), std::move(lobe_planes[k]), kLobePlaneGap * c.radius,
                              kLobePlanes);
        // A flat cluster (every polygon in one plane, facing the axis) shoots as the rectangle
        // around its polygons in that plane (ClusterShooter::rect): the area kernel is right
        // next to it, where a point's is not.
        bool flat = true;
        const double plane = glm::dot(c.axis, c.centre);
        const double tol = 1e-6 * c.radius;
        for (std::size_t k = 0; k < c.members.size() && flat; ++k) {
            const Polygon& poly = scene_->polygons[c.members[k]];
            flat = glm::dot(poly.normal, c.axis) > 0.99985; // 1 degree
            for (int q = 0; q < poly.count && flat; ++q)
                flat = std::abs(glm::dot(poly.v[q], c.axis) - plane) <= tol;
        }
        if (flat) {
            const Polygon& first = scene_->polygons[c.members.front()];
            const dvec3 e = first.v[1] - first.v[0];
            const dvec3 T = glm::normalize(e - glm::dot(e, c.axis) * c.axis);
            const dvec3 B = glm::cross(c.axis, T);
            glm::dvec2 lo(1e300), hi(-1e300);
            for (std::uint32_t m : c.members) {
                const Polygon& poly = scene_->polygons[m];
                for (int q = 0; q < poly.count; ++q) {
                    const dvec3 d = poly.v[q] - c.centre;
                    const glm::dvec2 p2(glm::dot(d, T), glm::dot(d, B));
                    lo = glm::min(lo, p2);
                    hi = glm::max(hi, p2);
                }
            }
            const dvec3 o = c.centre - glm::dot(c.centre, c.axis) * c.axis + plane * c.axis;
            c.rect.count = 4;
            c.rect.corners = {o + lo.x * T + lo.y * B, o + hi.x * T + lo.y * B,
                              o + hi.x * T + hi.y * B, o + lo.x * T + hi.y * B};
            c.rect.centre = o;
            c.rect.area = (hi.x - lo.x) * (hi.y - lo.y);
            if (!(c.rect.area > 0)) c.rect.count = 0;
        }
        c.unshot_power = weight;
        c.power_fraction = total > 0 ? std::min(1.0, weight / total) : 1.0;
        if (c.rect.count != 4) { // a point: its receivers near it judged by its sources
            c.sources = cluster_sources(*scene_, cluster_bvh(), c.members, member_power, weight,
                                        c.centre, 1e-4 * c.radius);
        }

        // A cluster not measured yet is measured on coarse hemicubes first, where the
        // provider has them: a refused one then costs a fraction of a shot.
        t0 = Clock::now();
        if (!measured(cluster_view_[node])) {
            FormFactorProvider::ClusterProbe probe;
            if (provider_->probe_cluster(c, probe)) {
                ++rec.probes;
                cluster_view_[node] = probe.backface > options_.enclosed_fraction
                                          ? kViewEnclosed
                                          : parallax_code(probe.misplaced);
                if (must_split_cluster(node)) {
                    rec.t_form_factors += since(t0);
                    ++rec.refined;
                    node = best;
                    t0 = Clock::now();
                    continue;
                }
            }
        }
        provider_->shoot_cluster(c, links_);
        rec.t_form_factors += since(t0);
        add_timings(rec);
        // Its misplaced share, once: parallax (what its point sees that its extent would see
        // otherwise) plus the light it sends within twice its radius.
        const double misplaced = provider_->last_parallax_fraction() +
                                 provider_->last_near_fraction() +
                                 provider_->last_backface_fraction();
        rec.parallax = misplaced;
        // An enclosed centre (its light mostly on the backs of polygons): never shot, measured
        // or not.
        if (provider_->last_backface_fraction() > options_.enclosed_fraction) {
            cluster_view_[node] = kViewEnclosed;
            ++rec.refined;
            ++rec.discarded;
            node = best;
            t0 = Clock::now();
            continue;
        }
        if (!measured(cluster_view_[node])) {
            cluster_view_[node] = provider_->last_backface_fraction() > options_.enclosed_fraction
                                      ? kViewEnclosed
                                      : parallax_code(misplaced);
            if (must_split_cluster(node)) {
                ++rec.refined;
                ++rec.discarded;
                node = best;
                t0 = Clock::now();
                continue;
            }
        }
        rec.cluster = long(node);
        rec.cluster_polygons = n.size();
        rec.shooter = {c.members.front(), 0, 0};
        rec.shooter_power = weight;
        rec.links = links_.size();
        // Its polygons' unshot light is cleared first: those that see each other (a corner)
        // receive some of it back.
        t0 = Clock::now();
        for (std::size_t i = 0; i < c.members.size(); ++i)
            if (member_power[i] > 0) hierarchy_.clear_unshot({c.members[i], 0, 0});
        rec.t_update += since(t0);
        attenuate_through_glazing(c.rect.count == 4 ? c.rect.centre : c.centre);
        deliver(power, 1.0, rec);
        last_polygon_ = -1;
        return true;
    }
}

void Solver::attenuate_through_glazing(const dvec3& origin) {
    if (!glazing_ || glazing_->empty()) return;
    for (Link& l : links_) {
        const dvec3 to =
            patch_geometry(scene_->polygons[l.receiver.polygon], l.receiver.level, l.receiver.index)
                .centre;
        l.ff = float(double(l.ff) * glazing_->between(origin, to));
    }
}

double Solver::deliver(const dvec3& dB, double area_s, ShotRecord& rec) {
    const auto t0 = Clock::now();
    const double row = row_of(links_, area_s);
    rec.row_sum = row;
    double scale = 1.0;
    if (options_.row_guard && row > 1.0) {
        scale = 1.0 / row;
        rec.row_guarded = true;
        ++row_guarded_;
    }
    deliver_links(hierarchy_, links_, dB, area_s, scale, absorbed_, escaped_);
    rec.t_update = since(t0);
    return scale;
}

void Solver::finish_shot(ShotRecord& rec, Clock::time_point t_start) {
    const double row = rec.row_sum;
    row_min_ = std::min(row_min_, row);
    row_max_ = std::max(row_max_, row);
    row_total_ += row;
    if (rec.luminaire < 0) {
        landed_ += std::min(row, 1.0) * rec.shooter_power;
        shot_ += rec.shooter_power;
    }
    ++shots_;
    seconds_ += since(t_start);
    rec.unshot = unshot_power();
    rec.unshot_fraction = unshot_fraction();
    rec.error_bound = error_bound();
    last_ = std::move(rec);
    round_.push_back(last_);
}

bool Solver::cut_by_plane(const PatchAddress& a) const {
    if (!plane_cuts_) return false;
    const Polygon& poly = scene_->polygons[a.polygon];
    const double share = plane_cuts_->cut_share(a.polygon, patch_geometry(poly, a.level, a.index));
    if (share <= 0) return false;
    return share * node_power(hierarchy_.node(a)) > options_.shooter_parallax * sum(emitted_);
}

bool Solver::worth_probing(std::uint64_t node) const {
    const std::uint8_t code = view_[node];
    if (code == kViewUnknown) return true;
    if (measured(code) || options_.shooter_parallax <= 0) return false;
    // A predicted share is half its parent's; measured, children read 0.8-1.3 times that
    // (room402, the Cornell box): one predicted below half the limit is shot without a probe,
    // and measured on its own hemicube (then refused only if it read twice its prediction).
    const double power = node_power(hierarchy_.nodes()[node]);
    return code_parallax(code) * power > 0.5 * options_.shooter_parallax * sum(emitted_);
}

bool Solver::must_split(std::uint64_t node) const {
    const std::uint8_t code = view_[node];
    if (code == kViewEnclosed || code == kViewOvercounted) return true;
    if (code == kViewUnknown || options_.shooter_parallax <= 0) return false;
    const double power = node_power(hierarchy_.nodes()[node]);
    return code_parallax(code) * power > options_.shooter_parallax * sum(emitted_);
}

Solver::RowSumStats Solver::row_sums() const {
    RowSumStats s;
    if (shots_ > 0) {
        s.min = row_min_;
        s.max = row_max_;
        s.mean = row_total_ / double(shots_);
    }
    s.guarded = row_guarded_;
    return s;
}

Hierarchy& Solver::solution() {
    hierarchy_.push_pull_all();
    hierarchy_.set_unshot_estimate(ambient_irradiance());
    return hierarchy_;
}

dvec3 Solver::ambient_irradiance() const {
    double area = 0;
    dvec3 rho_area(0.0);
    for (std::uint32_t i = 0; i < scene_->polygons.size(); ++i) {
        const Polygon& p = scene_->polygons[i];
        area += p.area;
        rho_area += hierarchy_.reflectance({i, 0, 0}) * p.area; // the texture's mean where textured
    }
    if (area <= 0) return dvec3(0.0);
    const dvec3 rho = rho_area / area;
    const double r = shot_ > 0 ? std::clamp(landed_ / shot_, 0.0, 1.0) : 1.0;
    return signed_unshot_power() * r / ((dvec3(1.0) - rho * r) * area);
}

Solver::Counters Solver::counters() const {
    Counters c;
    c.shots = shots_;
    c.absorbed = absorbed_;
    c.escaped = escaped_;
    c.row_min = row_min_;
    c.row_max = row_max_;
    c.row_total = row_total_;
    c.row_guarded = row_guarded_;
    c.landed = landed_;
    c.shot = shot_;
    c.last_polygon = last_polygon_;
    c.seconds = seconds_;
    return c;
}

void Solver::restore(const Counters& c) {
    shots_ = c.shots;
    absorbed_ = c.absorbed;
    escaped_ = c.escaped;
    row_min_ = c.row_min;
    row_max_ = c.row_max;
    row_total_ = c.row_total;
    row_guarded_ = c.row_guarded;
    landed_ = c.landed;
    shot_ = c.shot;
    last_polygon_ = c.last_polygon;
    seconds_ = c.seconds;
    check_stop();
}

Solver::State Solver::save_state() const {
    State st;
    st.counters = counters();
    st.nodes = hierarchy_.nodes();
    st.unshot = hierarchy_.unshot_powers();
    st.dirty = hierarchy_.dirty_flags();
    st.enclosed = view_;
    st.provider = provider_->save_state();
    st.luminaires = luminaire_unshot_;
    st.clusters = cluster_view_;
    if (layers_) st.layers = layers_->save_state();
    return st;
}

void Solver::restore_state(const State& st) {
    const std::vector<Hierarchy::Node>& nodes = hierarchy_.nodes();
    const std::vector<dvec3>& unshot = hierarchy_.unshot_powers();
    const std::vector<std::uint8_t>& dirty = hierarchy_.dirty_flags();
    const auto expect = [](const char* what, std::size_t got, std::size_t want) {
        if (got != want)
            throw InputError(std::string("saved solver state: ") + what + ": " +
                             std::to_string(got) + " saved, this solver has " +
                             std::to_string(want));
    };
    expect("hierarchy nodes", st.nodes.size(), nodes.size());
    expect("polygons (unshot power)", st.unshot.size(), unshot.size());
    expect("polygons (dirty flags)", st.dirty.size(), dirty.size());
    expect("view codes", st.enclosed.size(), view_.size());
    expect("luminaires", st.luminaires.size(), luminaire_unshot_.size());
    if (!st.clusters.empty() || !cluster_view_.empty())
        expect("cluster view codes", st.clusters.size(), cluster_view_.size());
    for (std::size_t k = 0; k < st.luminaires.size(); ++k)
        if (!finite(st.luminaires[k])) // negative after an edit (incremental.cpp)
            throw InputError("saved solver state: luminaire " + std::to_string(k) +
                             " has an invalid unshot power");
    for (std::size_t i = 0; i < st.nodes.size(); ++i) {
        const Hierarchy::Node& n = st.nodes[i];
        if (!finite(n.H) || !finite(n.dB) || !finite(n.dI))
            throw InputError("saved solver state: node " + std::to_string(i) +
                             " holds a non-finite value");
    }
    for (std::size_t p = 0; p < st.unshot.size(); ++p)
        if (!finite(st.unshot[p]) || st.dirty[p] > 1)
            throw InputError("saved solver state: polygon " + std::to_string(p) +
                             " has an invalid unshot power or dirty flag");
    const Counters& c = st.counters;
    if (c.shots < 0 || !finite(c.absorbed) || !finite(c.escaped) || !std::isfinite(c.row_min) ||
        !std::isfinite(c.row_max) || !std::isfinite(c.row_total) || c.row_guarded < 0 ||
        c.last_polygon < -1 || c.last_polygon >= std::int64_t(scene_->polygons.size()) ||
        !(c.seconds >= 0))
        throw InputError("saved solver state: invalid counters");
    if (layers_ && !st.layers.empty()) {
        expect("light layers", st.layers.size(), layers_->size());
        for (std::size_t k = 0; k < st.layers.size(); ++k) {
            const Solver::State::Layer& l = st.layers[k];
            expect("light layer nodes", l.nodes.size(), nodes.size());
            expect("light layer polygons", l.unshot.size(), unshot.size());
            expect("light layer polygons (dirty flags)", l.dirty.size(), dirty.size());
            bool ok = finite(l.absorbed) && finite(l.escaped);
            for (const Hierarchy::Node& n : l.nodes)
                ok = ok && finite(n.H) && finite(n.dB) && finite(n.dI);
            for (std::size_t p = 0; p < l.unshot.size(); ++p)
                ok = ok && finite(l.unshot[p]) && l.dirty[p] <= 1;
            if (!ok)
                throw InputError("saved solver state: light layer " + std::to_string(k) +
                                 " holds an invalid value");
        }
    }
    provider_->restore_state(st.provider);
    if (st.layers.empty())
        layers_.reset(); // the saved solution kept no layers: an edit is shot
    else if (layers_)
        layers_->restore_state(st.layers);
    hierarchy_.restore_state(st.nodes, st.unshot, st.dirty);
    view_ = st.enclosed;
    luminaire_unshot_ = st.luminaires;
    cluster_view_ = st.clusters;
    restore(c);
}

} // namespace hemirad
