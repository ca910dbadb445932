// The GPU form-factor provider (paper 002): hemicube visibility with the mipmapped patch-ID
// linking oracle, analytic form factors from the fragment shader, and the hybrid treatment
// of partially occluded patches (§3.2). Modes:
//   hemicube  classic pixel counting (Cohen & Greenberg 1985) at the mipmap linking
//   analytic  the analytic value at every visible node (binary visibility)
//   hybrid    analytic, except nodes with a fully occluded neighbour: pixel sum clamped to
//             the analytic value
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <functional>
#include <initializer_list>
#include <memory>
#include <optional>
#include <unordered_map>

#include "core/parallel.h"
#include "core/timer.h"
#include "ff/bvh.h"
#include "gpu/hemicube.h"
#include "gpu/hemicube_visibility.h"
#include "gpu/pixel_runs.h"
#include "hemirad/error.h"
#include "hemirad/gl/context.h"
#include "hemirad/provider.h"

namespace hemirad {

namespace {

using Clock = SteadyClock;             // core/timer.h
constexpr auto since = &seconds_since; // [s]

enum class Mode { Hemicube, Analytic, Hybrid };

/// A node seen on at least this many pixels of a point shot's hemicubes is near the point:
/// it takes its pixels' flux, not the kernel at its centre (add_link).
constexpr std::uint32_t kNearPixels = 16;
/// touched_job() links the seen nodes in chunks of this many (fewer: one chunk).
constexpr std::size_t kChunkNodes = 2048;
/// missed_polygons_job() links the polygons no pixel shows in chunks of this many.
constexpr std::size_t kChunkPolygons = 8192;

/// The polygon of a luminaire's stand-in shooter: none (the renderer skips no polygon).
constexpr std::uint32_t kNoShooterPolygon = 0xFFFFFFFFu;

/// A point cluster whose brightest polygons see less than this share of the light its point
/// sends in front of them (share_seen) is no stand-in for them: it is reported enclosed.
constexpr double kSeenEnough = 0.05;
/// share_seen judges a receiver by ray casts to the sources that hold this share of the light
/// of those facing it.
constexpr double kJudgedShare = 0.9;

/// The point of convex polygon `p` nearest to x.
dvec3 nearest_point(const Polygon& p, const dvec3& x) {
    const dvec3 on_plane = x - glm::dot(x - p.v[0], p.normal) * p.normal;
    bool inside = true;
    double best = 1e300;
    dvec3 nearest = on_plane;
    for (int k = 0; k < p.count; ++k) {
        const dvec3 a = p.v[k], b = p.v[(k + 1) % p.count];
        if (glm::dot(glm::cross(b - a, on_plane - a), p.normal) >= 0) continue;
        inside = false;
        const dvec3 e = b - a;
        const double t =
            std::clamp(glm::dot(on_plane - a, e) / std::max(glm::dot(e, e), 1e-300), 0.0, 1.0);
        const dvec3 q = a + t * e;
        const double d = glm::dot(q - on_plane, q - on_plane);
        if (d < best) best = d, nearest = q;
    }
    return inside ? on_plane : nearest;
}

/// probe_view()'s hemicube resolution: 1/16 of the pixels of the default 256. The shot's own
/// hemicube is read at the same resolution for the same measures (stride res / 64).
constexpr int kProbeResolution = 64;

class HemicubeProvider final : public FormFactorProvider {
  public:
    HemicubeProvider(Mode mode, std::string name, const Scene& scene, const Discretisation& disc,
                     const GpuProviderOptions& options)
        : mode_(mode), name_(std::move(name)), scene_(&scene), disc_(disc), options_(options) {
        validate_gpu_options(options);
        if (!options.use_current_context) {
            gl::ContextOptions co;
            co.backend = gl::parse_backend(options.backend);
            co.device = options.device;
            context_ = gl::Context::create(co);
        }
        const int max_res = options.resolution ? options.resolution : options.max_resolution;
        renderer_ = std::make_unique<gpu::HemicubeRenderer>(scene, disc, max_res);
        base_.resize(scene.polygons.size());
        std::uint64_t total = 0;
        for (std::size_t p = 0; p < scene.polygons.size(); ++p) {
            base_[p] = total;
            total += tree_size(disc.depth[p]);
        }
        pixel_sum_.assign(total, 0.f);
        pixel_count_.assign(total, 0);
        analytic_.assign(total, 0.f);
        seen_.assign(total, 0);
        polygon_seen_.assign(scene.polygons.size(), 0);
        below_seen_.assign(total, 0);
        partial_.assign(total, 0);
        for (const Polygon& poly : scene.polygons) {
            centre_.push_back(patch_geometry(poly, 0, 0).centre);
            radius_.push_back(reach(poly.v, poly.count, centre_.back()));
            longest_.push_back(longest_edge(poly.v, poly.count));
        }
        if (mode_ != Mode::Hemicube) bvh_ = std::make_unique<Bvh>(scene); // centre_seen() etc.
        area_ = std::make_unique<std::atomic<float>[]>(total);
        for (std::size_t k = 0; k < total; ++k) area_[k].store(-1.f, std::memory_order_relaxed);
        diagonal_ = scene.bounds().diagonal();
        plane_eps_ = 1e-7 * diagonal_;
    }

    // Its GL objects go with its own context current (another solver's may be).
    ~HemicubeProvider() override {
        try {
            bind();
        } catch (const std::exception& e) {
            std::fprintf(stderr, "hemirad: GL context: %s\n", e.what());
        }
        renderer_.reset();
    }
    HemicubeProvider(const HemicubeProvider&) = delete;
    HemicubeProvider& operator=(const HemicubeProvider&) = delete;

    std::string name() const override { return name_; }
    std::vector<Timing> last_timings() const override { return timings_; }
    double last_backface_fraction() const override { return backface_; }
    double last_enclosed_fraction() const override {
        if (!last_layout_ || point_shot_) return backface_;
        // Sampled as on probe_view()'s hemicube: a share, not an image, is wanted.
        return backface_ + gpu::near_fraction(*scene_, last_shooter_, *last_layout_, pixels_.data(),
                                              0.25 * std::sqrt(last_shooter_.geometry.area),
                                              last_layout_->res / kProbeResolution);
    }
    bool last_sees_within(double distance) const override {
        if (!last_layout_ || point_shot_) return false;
        return gpu::shows_within(*scene_, last_shooter_, *last_layout_, pixels_.data(), distance);
    }
    double last_parallax_fraction() const override {
        if (!last_layout_) return 0;
        return gpu::parallax_fraction(*scene_, last_shooter_, *last_layout_, pixels_.data(),
                                      last_layout_->res / kProbeResolution);
    }
    HemicubeImage last_hemicube() const override {
        if (pixels_.size() < 4 * std::size_t(last_width_) * std::size_t(last_height_) ||
            last_width_ <= 0)
            return {};
        return {last_width_, last_height_, pixels_.data()};
    }
    /// The adaptive resolution depends on the strongest shooter so far: {max_power_}.
    std::vector<double> save_state() const override { return {max_power_}; }
    void restore_state(const std::vector<double>& state) override {
        if (state.size() != 1 || !std::isfinite(state[0]) || state[0] < 0)
            throw InputError("GPU provider state: expected 1 finite value >= 0 (max shooter "
                             "power), got " +
                             std::to_string(state.size()) + " values");
        max_power_ = state[0];
    }

    void shoot(const Shooter& shooter, std::vector<Link>& links) override {
        bind();
        links.clear();
        timings_.clear();
        if (probe_seconds_ > 0) timings_.push_back({"probe", probe_seconds_});
        probe_seconds_ = 0;
        ++stamp_;
        const gpu::HemicubeLayout& layout = layout_for(shooter);
        auto t0 = Clock::now();
        const int angle = options_.atan_angle ? 2 : options_.builtin_acos ? 1 : 0;
        renderer_->render(shooter, layout, options_.lod_bias, angle);
        timings_.push_back({"cull", renderer_->cull_seconds()});
        timings_.push_back({"render", since(t0) - renderer_->cull_seconds()});
        t0 = Clock::now();
        renderer_->read_back(layout, pixels_);
        point_shot_ = false;
        last_width_ = layout.width;
        last_height_ = layout.height;
        last_layout_ = &layout;
        last_shooter_ = shooter;
        shooter_radius_ =
            reach(shooter.geometry.corners, shooter.geometry.count, shooter.geometry.centre);
        timings_.push_back({"readback", since(t0)});
        t0 = Clock::now();
        reduce(shooter, layout, links);
        timings_.push_back({"reduce", since(t0)});
    }

    // A coarse hemicube (kProbeResolution) at the shooter's centre: the fractions that decide
    // whether it may shoot. The parallax and near-surface measures are sums of form factor
    // over silhouettes and surfaces, nearly independent of the resolution.
    bool probe_view(const Shooter& shooter, ViewProbe& probe) override {
        bind();
        if (resolution_for(shooter) <= kProbeResolution) return false;
        const gpu::HemicubeLayout& layout = layout_of(kProbeResolution);
        const auto t0 = Clock::now();
        const double backface = render_probe(shooter, layout);
        probe.enclosed =
            backface + gpu::near_fraction(*scene_, shooter, layout, probe_pixels_.data(),
                                          0.25 * std::sqrt(shooter.geometry.area));
        probe.parallax = gpu::parallax_fraction(*scene_, shooter, layout, probe_pixels_.data());
        probe_seconds_ += since(t0);
        return true;
    }

    // A luminaire shoots from its position over the whole sphere (shoot_sphere), with its
    // intensity in candela: per watt emitted, I(d) / (683 P). In hybrid, each polygon's
    // links are then scaled so that together they take the flux through its pixels
    // (match_pixel_totals).
    void shoot_point(const Luminaire& luminaire, std::vector<Link>& links) override {
        bind();
        links.clear();
        timings_.clear();
        const double power = luminaire.power();
        if (!(power > 0)) return;
        const double per_watt = 1.0 / (kLumensPerWatt * power);
        Sphere s;
        s.centre = luminaire.position;
        s.axis = luminaire.aim;
        s.first = luminaire.c0;
        s.half = 0.005 * std::max(diagonal_, 1e-300);
        s.intensity = [&](const dvec3& d) { return luminaire.intensity(d) * per_watt; };
        shoot_sphere(s, options_.resolution ? options_.resolution : options_.max_resolution, links);
        if (mode_ == Mode::Hybrid) match_pixel_totals(links);
    }

    // A point's light divided among polygons as its pixels divide it, and within a polygon as
    // the hybrid values do: each polygon's links are scaled so that their flux is the flux
    // through the polygon's pixels. A polygon that no pixel shows (linked by
    // missed_polygons_job) gets nothing: its direction's light is in the pixels of what is
    // shown there, and its links are dropped. The pixels divide a point's flux without bias:
    // every direction goes to what it shows; the analytic values at node centres, the
    // min(pixels, analytic) of partial nodes and the sampled visible parts do not. The
    // courtyard's three luminaire shots, against the gather's exact direct light averaged over
    // 16 points a leaf: balustrades -12.9 %, columns -4.0 %, floor +2.1 %, gallery floors
    // +24.5 % before; -2.6, +0.3, -0.4, +4.4 % after. The values keep their shape inside a
    // polygon (a plane under a point: leaves within 1.5 %, where the pixels alone give 11 %).
    void match_pixel_totals(std::vector<Link>& links) const {
        match_pixel_totals(links, 1.0, [](const PatchAddress&) { return true; });
    }

    // The same for the links and seen nodes that `matched(node)` picks (the others keep their
    // values). A polygon's pixels are its seen nodes' pixel sums (times pixel_scale, as
    // link_node takes them), not its links' ff_pixel: where GL's LOD showed a node and all its
    // children, the node's pixels have no link of their own (split() finds no filler).
    template <class Matched>
    void match_pixel_totals(std::vector<Link>& links, double pixel_scale, Matched&& matched) const {
        struct Totals {
            double linked = 0, pixels = 0;
        };
        std::unordered_map<std::uint32_t, Totals> totals;
        double all_pixels = 0, picked_pixels = 0, kept = 0; // kept: the others' links
        for (const PatchAddress& a : touched_) {
            const double pixels =
                double(pixel_sum_[node_id(a.polygon, a.level, a.index)]) * pixel_scale;
            all_pixels += pixels;
            if (!matched(a)) continue;
            totals[a.polygon].pixels += pixels;
            picked_pixels += pixels;
        }
        std::vector<char> picked(links.size());
        for (std::size_t i = 0; i < links.size(); ++i) {
            const Link& l = links[i];
            picked[i] = matched(l.receiver);
            const double a = area(l.receiver.polygon, l.receiver.level, l.receiver.index);
            (picked[i] ? totals[l.receiver.polygon].linked : kept) += double(l.ff) * a;
        }
        // The picked links take at most the light the pixels leave after the others' links,
        // so that the row is at most the pixels' (all the eye's light, but the backs'). Where
        // the others take the kernel of an extent that the eye stands for badly (a flat
        // cluster's near receivers, a long bar's), the two together took more than all the
        // light: the office glb's LED bar under a desk, 1.024 (tests/hemicube_gl_test.cpp,
        // FlatCluster).
        const double share = picked_pixels > 0 && kept + picked_pixels > all_pixels
                                 ? std::max(0.0, all_pixels - kept) / picked_pixels
                                 : 1.0;
        for (std::size_t i = 0; i < links.size(); ++i) {
            if (!picked[i]) continue;
            const Totals& t = totals[links[i].receiver.polygon];
            if (t.linked > 0)
                links[i].ff = float(double(links[i].ff) * (share * t.pixels / t.linked));
        }
        std::erase_if(links, [](const Link& l) { return !(l.ff > 0); });
    }

    // match_pixel_totals for the links and seen nodes farther than `near` from a cluster's
    // eye (their centres); nearer ones keep their values.
    void match_far_pixel_totals(std::vector<Link>& links, const dvec3& eye, double near,
                                double pixel_scale) const {
        match_pixel_totals(links, pixel_scale, [&](const PatchAddress& a) {
            const dvec3 x = patch_centre(scene_->polygons[a.polygon], a.level, a.index);
            return glm::length(x - eye) > near;
        });
    }

    bool can_shoot_clusters() const override { return true; }
    double last_near_fraction() const override { return near_fraction_; }

    // Of the light of a point cluster's brightest polygons that could reach a receiver at x
    // on `polygon` (each in front of the other), the share that a ray cast finds unblocked
    // between them: within twice its radius the point sees what its polygons do not
    // (from a centre inside a jar, the jar's inside, which its lit outside never lights).
    // 0 where none of them faces the receiver (the inside of a jar's lid). `centroids`: the
    // sources' centroids. Only with a BVH (shoot_cluster's judge_seen).
    double share_seen(const ClusterShooter& c, const std::vector<dvec3>& centroids,
                      std::uint32_t polygon, const dvec3& x, double lift) const {
        const dvec3 n = scene_->polygons[polygon].normal;
        const dvec3 from = x + lift * n;
        // The sources that face it (brightest first), then rays to them until nine tenths of
        // their light is judged (the rest is taken as seen as much); a source that sees the
        // point from in front is taken to see what the point sees, without a ray.
        std::array<std::uint8_t, ClusterShooter::kMaxSources> facing_sources;
        std::size_t count = 0;
        double facing = 0;
        for (std::size_t k = 0; k < c.sources.size() && k < facing_sources.size(); ++k) {
            const Polygon& source = scene_->polygons[c.sources[k].polygon];
            const dvec3& y = centroids[k];
            if (glm::dot(source.normal, x - y) > lift && glm::dot(n, y - x) > lift)
                facing_sources[count++] = std::uint8_t(k), facing += c.sources[k].share;
        }
        double judged = 0, seen = 0;
        for (std::size_t i = 0; i < count && judged < kJudgedShare * facing; ++i) {
            const std::size_t k = facing_sources[i];
            const ClusterShooter::Source& s = c.sources[k];
            const Polygon& source = scene_->polygons[s.polygon];
            judged += s.share;
            if (!s.hidden_from_centre) { // it sees what the point sees
                seen += s.share;
                continue;
            }
            // Across a gap (a panel millimetres in front of the source) the source's point
            // straight across, around a corner its centroid.
            const dvec3 across = nearest_point(source, x) + lift * source.normal;
            if (!bvh_->occluded(from, across, polygon, s.polygon) ||
                !bvh_->occluded(from, centroids[k] + lift * source.normal, polygon, s.polygon))
                seen += s.share;
        }
        return judged > 0 ? seen / judged : 0.0;
    }

    // A cluster shoots from its centre over the whole sphere (shoot_sphere) with the
    // intensity of its polygons' cosine lobes; its polygons are not drawn. The hemicube
    // against the axis is left out when the cluster sends less than 0.1 % of its power there
    // (a flat cluster), and that light is added to the other side's (scaled: energy is kept).
    void shoot_cluster(const ClusterShooter& c, std::vector<Link>& links) override {
        bind();
        links.clear();
        timings_.clear();
        if (c.rect.count > 0) {
            const Shooter flat = flat_shooter(c);
            renderer_->set_hidden(c.members);
            hidden_ = &c.members;
            shoot(flat, links);
            hidden_ = nullptr;
            renderer_->set_hidden({});
            // Seen from farther than twice its reach, the rectangle is nearly a point at its eye:
            // there its light is divided among polygons as the pixels divide it
            // (match_pixel_totals), which sample every direction. The analytic values at node
            // centres, each with its own visibility test, miss light on tessellated round
            // surfaces, where facets seen edge-on hide each other's centres (the courtyard's flat
            // clusters: their far links gave the columns 35 % and the balustrades 27 % less than
            // their pixels). Nearer, the rectangle's analytic values stand: one eye for the whole
            // rectangle sees the surfaces beside it unlike its polygons do (the office's flat
            // clusters: there the pixels put 4 times the analytic light).
            if (mode_ == Mode::Hybrid)
                match_far_pixel_totals(
                    links, flat.geometry.centre,
                    2 * reach(flat.geometry.corners, flat.geometry.count, flat.geometry.centre),
                    flat.geometry.area);
            // The light the backs of polygons would take (the rectangle's centre sees them where
            // the cluster's polygons would not) goes to what it sees instead: energy is kept,
            // and the solver counts the share as misplaced.
            const float per_watt = float(1.0 / (c.rect.area * std::max(1.0 - backface_, 0.05)));
            for (Link& l : links) {
                l.ff *= per_watt;
                l.ff_analytic *= per_watt;
                l.ff_pixel *= per_watt;
            }
            near_fraction_ = 0;
            return;
        }
        if (probe_seconds_ > 0) timings_.push_back({"probe", probe_seconds_});
        probe_seconds_ = 0;
        const int res = resolution_for(stand_in(c));
        const Sphere s = cluster_sphere(c);
        renderer_->set_hidden(c.members, true);
        hidden_ = &c.members;
        shoot_sphere(s, res, links);
        hidden_ = nullptr;
        renderer_->set_hidden({});
        // Each polygon takes the light its pixels show, near the point as well as far: the
        // pixels integrate the point's kernel (most finely where a receiver is nearest), while
        // the analytic values are the kernel at node centres, each with its own visibility
        // test, and a polygon that no pixel shows is linked by its kernel when its depth
        // matches what is drawn there. Within twice the radius these were kept (as a flat
        // cluster's are, above): near a board modelled twice (coincident faces) the board took
        // its light twice, and the office glb's clusters of 4-17 polygons summed to 1.009-1.037
        // (a desk part 20 cm from the point that no pixel showed took 0.074 of the light).
        if (mode_ == Mode::Hybrid) match_pixel_totals(links);
        // The light the backs of polygons would take goes to what the point sees instead (see
        // the flat case).
        const float keep = float(1.0 / std::max(1.0 - backface_, 0.05));
        for (Link& l : links) {
            l.ff *= keep;
            l.ff_analytic *= keep;
            l.ff_pixel *= keep;
        }
        // How wrong a point is as a stand-in for the cluster: the light received, weighted by
        // (R / r)^2 (the relative error of a point's kernel at distance r from a cluster of
        // radius R, capped at 1), over the light received.
        // Each of a lobe's planes lights only what lies in front of it and faces some of its
        // polygons: a receiver behind it is inside the object the cluster wraps, or behind the
        // wall it covers (the twin of a lit wall, facing into the slab), which the point sees
        // and the plane's polygons do not. A link keeps the share of the intensity towards it
        // of the planes that pass it (ClusterShooter::share_in_front).
        double near = 0, total = 0, seen = 0, in_front = 0;
        const double R2 = c.radius * c.radius;
        const double eps = 1e-6 * std::max(c.radius, 1e-300);
        // Each link's receiver and share on threads (in chunks), the sums after, in order.
        // Receivers near the point are judged by what its sources see (share_seen) where
        // some of them do not see the point from in front (on the courtyard: 1.3 million
        // receivers judged with 3.4 million rays in 1.4 s, where judging every near receiver
        // of every point cluster by rays took 32 million rays, 6 s, and fixed the plant pots'
        // leaks in the office lit by point sources as well).
        const bool judge_seen =
            bvh_ && std::any_of(c.sources.begin(), c.sources.end(),
                                [](const auto& s) { return s.hidden_from_centre; });
        std::vector<dvec3> centroids;
        if (judge_seen)
            for (const ClusterShooter::Source& s : c.sources)
                centroids.push_back(scene_->polygons[s.polygon].centroid());
        receivers_.resize(links.size());
        for_chunks(links.size(), chunk_count(links.size(), kChunkNodes, 0), 0,
                   [&](std::size_t, std::size_t begin, std::size_t end) {
                       for (std::size_t i = begin; i < end; ++i) {
                           const PatchAddress& a = links[i].receiver;
                           const Polygon& poly = scene_->polygons[a.polygon];
                           const PatchGeometry g = patch_geometry(poly, a.level, a.index);
                           const double share = c.share_in_front(g.centre, poly.normal, eps);
                           const dvec3 d = g.centre - c.centre;
                           const double seen_share =
                               judge_seen && share > 0 && glm::dot(d, d) < 4 * R2
                                   ? share_seen(c, centroids, a.polygon, g.centre, 1e-4 * c.radius)
                                   : 1.0;
                           receivers_[i] = {g.centre, g.area, float(share), float(seen_share)};
                       }
                   });
        std::size_t kept = 0;
        for (std::size_t i = 0; i < links.size(); ++i) {
            Link l = links[i];
            const Receiver& g = receivers_[i];
            seen += double(l.ff) * g.area;
            if (!(g.share > 0)) continue;
            in_front += double(l.ff) * g.share * g.area;
            const float share = g.share * g.seen;
            if (!(share > 0)) continue;
            l.ff *= share;
            l.ff_analytic *= share;
            l.ff_pixel *= share;
            links[kept++] = l;
            const double w = double(l.ff) * g.area;
            total += w;
            const dvec3 d = g.centre - c.centre;
            near += w * std::min(1.0, R2 / std::max(glm::dot(d, d), 1e-300));
        }
        links.resize(kept);
        near_fraction_ = total > 0 ? near / total : 0;
        // The light the point sent where its polygons could not goes, like the backs', to
        // what they can light; the solver counts it as misplaced with the backs' share (a
        // cluster that sends most of its light there is refused as an enclosed one).
        // So does the light it would send a receiver near the point that its brightest
        // polygons do not see (share_seen); that is not counted (the point's view is mended
        // there), unless they see almost none of what lies in front of them: a point in a jar,
        // which sees only the jar's inside, is no stand-in for the jar (all is counted with the
        // backs, and the solver refuses it as an enclosed one; its halves shoot). Counted from
        // half on, the office glb took 2062 shots, not 1714 (as many leaks).
        const double behind = seen > 0 ? std::clamp(1.0 - in_front / seen, 0.0, 1.0) : 0.0;
        const double unseen = seen > 0 ? std::clamp(1.0 - total / seen, 0.0, 1.0) : 0.0;
        const float lit = float(1.0 / std::max(1.0 - unseen, 0.05));
        for (Link& l : links) {
            l.ff *= lit;
            l.ff_analytic *= lit;
            l.ff_pixel *= lit;
        }
        backface_ += (1.0 - backface_) * (total < kSeenEnough * in_front ? unseen : behind);
    }

    // The shares shoot_cluster() leaves for the solver, on 64² hemicubes of polygon IDs: a
    // flat cluster's as probe_view() takes a patch's (its backs and parallax); a point
    // cluster's from each pixel's flux (the lobes' intensity times the pixel's solid angle),
    // with the point its ray meets on the polygon it shows standing for the links' receivers
    // (share_in_front, the near weight (R / r)^2).
    bool probe_cluster(const ClusterShooter& c, ClusterProbe& probe) override {
        bind();
        const auto t0 = Clock::now();
        const gpu::HemicubeLayout& layout = layout_of(kProbeResolution);
        if (c.rect.count > 0) {
            const Shooter flat = flat_shooter(c);
            if (resolution_for(flat) <= kProbeResolution) return false;
            renderer_->set_hidden(c.members);
            const double back = render_probe(flat, layout);
            renderer_->set_hidden({});
            probe.backface = back;
            probe.misplaced =
                gpu::parallax_fraction(*scene_, flat, layout, probe_pixels_.data()) + back;
            probe_seconds_ += since(t0);
            return true;
        }
        if (resolution_for(stand_in(c)) <= kProbeResolution) return false;
        const Sphere s = cluster_sphere(c);
        const double R2 = c.radius * c.radius;
        const double eps = 1e-6 * std::max(c.radius, 1e-300);
        double back = 0, seen = 0, total = 0, near = 0, parallax = 0;
        renderer_->set_hidden(c.members, true);
        for (int k = s.front_only ? 1 : 0; k < 2; ++k) {
            const Shooter side = point_shooter(s, k == 0 ? -1.0 : 1.0);
            renderer_->render_polygon_ids(side, layout);
            renderer_->read_back(layout, probe_pixels_);
            const gpu::HemicubeFrame frame = gpu::hemicube_frame(side);
            for (int f = 0; f < 5; ++f) {
                const gpu::HemicubeLayout::Face& face = layout.faces[std::size_t(f)];
                for (int j = 0; j < face.h; ++j)
                    for (int i = 0; i < face.w; ++i) {
                        const std::size_t at =
                            std::size_t(face.y + j) * layout.width + std::size_t(face.x + i);
                        const float id = probe_pixels_[4 * at + 2];
                        if (id > -0.5f && id < 0.5f) continue; // nothing
                        const dvec3 u = gpu::hemicube_direction(layout, frame, f, i, j);
                        const double flux = pixel_flux(s, layout, frame, f, u);
                        if (id < 0) {
                            back += flux;
                            continue;
                        }
                        const Polygon& q = scene_->polygons[std::size_t(id) - 1];
                        const double along = glm::dot(u, q.normal);
                        if (along == 0) continue;
                        const double t = glm::dot(q.v[0] - s.centre, q.normal) / along;
                        if (!(t > 0)) continue;
                        seen += flux;
                        const double share = c.share_in_front(s.centre + t * u, q.normal, eps);
                        total += flux * share;
                        near += flux * share * std::min(1.0, R2 / (t * t));
                    }
            }
            // (The shot's parallax is read on its hemicube along the axis: side 1, last.)
            if (k == 1)
                parallax = gpu::parallax_fraction(*scene_, side, layout, probe_pixels_.data());
        }
        renderer_->set_hidden({});
        const double behind = seen > 0 ? std::clamp(1.0 - total / seen, 0.0, 1.0) : 0.0;
        probe.backface = back + (1.0 - back) * behind;
        probe.misplaced = parallax + (total > 0 ? near / total : 0) + probe.backface;
        probe_seconds_ += since(t0);
        return true;
    }

  private:
    // Renders a probe's hemicube of polygon IDs (the measures read nothing else) into
    // probe_pixels_ and returns the share of it that the backs of polygons take.
    double render_probe(const Shooter& shooter, const gpu::HemicubeLayout& layout) {
        renderer_->render_polygon_ids(shooter, layout);
        renderer_->read_back(layout, probe_pixels_);
        double backface = 0;
        const std::size_t n = std::size_t(layout.width) * layout.height;
        for (std::size_t i = 0; i < n; ++i)
            if (probe_pixels_[4 * i + 2] < -0.5f) backface += layout.delta_ff[i];
        return backface;
    }

    // A flat cluster's stand-in: the rectangle around its polygons (ClusterShooter::rect).
    static Shooter flat_shooter(const ClusterShooter& c) {
        Shooter flat;
        flat.address = {kNoShooterPolygon, 0, 0};
        flat.geometry = c.rect;
        flat.normal = c.axis;
        flat.unshot_power = c.unshot_power;
        flat.power_fraction = c.power_fraction;
        return flat;
    }

    // A point cluster's power, for resolution_for().
    static Shooter stand_in(const ClusterShooter& c) {
        Shooter s;
        s.unshot_power = c.unshot_power;
        s.power_fraction = c.power_fraction;
        return s;
    }

    // A shot from a point over the whole sphere (a luminaire, a cluster).
    struct Sphere {
        dvec3 centre{0.0}, axis{0.0, -1.0, 0.0}, first{1.0, 0.0, 0.0}; ///< first: along the
                                                                       ///< hemicubes' first edge
        double half = 0;         ///< half the side of the stand-in square [unit]
        bool front_only = false; ///< only the hemicube along +axis
        std::function<double(const dvec3&)> intensity; ///< [sr^-1 per watt emitted]
    };

    static dvec3 perpendicular(const dvec3& a) {
        const dvec3 t = std::abs(a.x) < 0.9 ? dvec3(1, 0, 0) : dvec3(0, 1, 0);
        return glm::normalize(t - glm::dot(t, a) * a);
    }

    // A point cluster's sphere: its lobes' intensity about its centre; the hemicube against
    // the axis is left out where it would take under 0.1 % of the power, and that light
    // added to the other's (scaled: energy is kept). Refers to c.
    Sphere cluster_sphere(const ClusterShooter& c) const {
        Sphere s;
        s.centre = c.centre;
        s.axis = c.axis;
        s.first = perpendicular(c.axis);
        s.half = std::max(c.radius, 1e-9 * diagonal_);
        const double back = c.back_share();
        s.front_only = back < 1e-3;
        const double scale = s.front_only ? 1.0 / std::max(1.0 - back, 1e-12) : 1.0;
        s.intensity = [&c, scale](const dvec3& d) { return c.intensity(d) * scale; };
        return s;
    }

    // The flux per watt emitted that point shot s sends through the pixel of face f whose
    // (unit) direction is u: I(u) times the pixel's solid angle, its area at unit distance
    // along the face's axis times cos^3 of u off that axis.
    static double pixel_flux(const Sphere& s, const gpu::HemicubeLayout& layout,
                             const gpu::HemicubeFrame& frame, int f, const dvec3& u) {
        const double d2 = 4.0 / (double(layout.res) * layout.res);
        const double c = glm::dot(u, frame.dir[std::size_t(f)]);
        const double omega = d2 * c * c * c; // the pixel's solid angle
        return s.intensity(u) * omega;
    }

    // Two hemicubes, along +axis and against it, each from a stand-in shooter (a small square
    // centred on the point, of no polygon, so that every polygon but the hidden ones is
    // drawn). Their patch IDs give the linking and the visibility, as for a polygon shooter;
    // the values are computed here: the analytic I(d) cos(theta_j) / r^2 at each node's
    // centre, and the flux through the node's pixels, sum I(u) omega (omega = the pixel's
    // solid angle).
    void shoot_sphere(const Sphere& s, int res, std::vector<Link>& links) {
        ++stamp_;
        point_ = &s;
        const gpu::HemicubeLayout& layout = layout_of(res);
        const int angle = options_.atan_angle ? 2 : options_.builtin_acos ? 1 : 0;
        const Shooter sides[2] = {point_shooter(s, -1.0), point_shooter(s, 1.0)};
        std::vector<float>* buffers[2] = {&pixels_back_, &pixels_};
        touched_.clear();
        double t_render = 0, t_read = 0, t_reduce = 0;
        double back = 0; // the light that the backs of polygons take
        for (int k = s.front_only ? 1 : 0; k < 2; ++k) {
            auto t0 = Clock::now();
            renderer_->render(sides[k], layout, options_.lod_bias, angle);
            t_render += since(t0);
            t0 = Clock::now();
            renderer_->read_back(layout, *buffers[k]);
            t_read += since(t0);
            t0 = Clock::now();
            const gpu::HemicubeFrame frame = gpu::hemicube_frame(sides[k]);
            gpu::fill_cracks(*scene_, layout, frame, buffers[k]->data(), s.centre, sphere_ids_[k]);
            const std::vector<float>& px = *buffers[k];
            // Each pixel's flux on the faces' threads (-1: no front there), then the nodes'
            // sums in order.
            flux_.resize(std::size_t(layout.width) * layout.height);
            std::array<double, 5> face_back{};
            parallel_for(5, gpu::face_threads(layout), [&](std::size_t f) {
                const gpu::HemicubeLayout::Face& face = layout.faces[f];
                for (int j = 0; j < face.h; ++j)
                    for (int i = 0; i < face.w; ++i) {
                        const std::size_t at = std::size_t(face.y + j) * layout.width + face.x + i;
                        const float id = px[4 * at + 2];
                        flux_[at] = -1.f;
                        if (id > -0.5f && id < 0.5f) continue; // nothing
                        const dvec3 u = gpu::hemicube_direction(layout, frame, int(f), i, j);
                        const double flux = pixel_flux(s, layout, frame, int(f), u);
                        if (id < 0)
                            face_back[f] += flux;
                        else
                            flux_[at] = float(flux);
                    }
            });
            for (int f = 0; f < 5; ++f) back += face_back[std::size_t(f)];
            const auto add_run = [&](std::size_t first, std::size_t count) {
                if (px[4 * first + 2] < 0.5f) return; // nothing, or the back of a polygon
                scan_pixels(px.data(), first, run_sum(flux_, first, count), std::uint32_t(count));
            };
            gpu::for_each_pixel_run(px.data(), flux_.size(), add_run);
            t_reduce += since(t0);
        }
        auto t0 = Clock::now();
        // The analytic value of every seen node, at its centre.
        for (const PatchAddress& a : touched_) {
            const PatchGeometry g = patch_geometry(scene_->polygons[a.polygon], a.level, a.index);
            analytic_[node_id(a.polygon, a.level, a.index)] =
                float(analytic_at(sides[0], g.centre, scene_->polygons[a.polygon].normal));
        }
        backface_ = back;
        point_shot_ = true;
        last_width_ = layout.width;
        last_height_ = layout.height;
        last_layout_ = &layout;
        last_shooter_ = sides[1];
        std::optional<gpu::HemicubeVisibility> vis[2];
        for (int k = s.front_only ? 1 : 0; k < 2; ++k) {
            vis[k].emplace(*scene_, layout, gpu::hemicube_frame(sides[k]), buffers[k]->data(),
                           s.centre, sphere_ids_[k].data());
            vis_[k] = &*vis[k];
            if (mode_ == Mode::Hybrid)
                mark_partial(*vis[k], buffers[k]->data(), gpu::face_threads(layout), [] {});
        }
        sphere_centre_ = s.centre;
        sphere_axis_ = s.axis;
        link_in_chunks(links, {touched_job(sides[0], 1.0, gpu::face_threads(layout))});
        for (int k = s.front_only ? 1 : 0; k < 2; ++k)
            link_in_chunks(links, {missed_polygons_job(sides[k], *vis[k])});
        vis_[0] = vis_[1] = nullptr;
        sphere_axis_ = dvec3(0.0);
        t_reduce += since(t0);
        point_ = nullptr;
        timings_.push_back({"render", t_render});
        timings_.push_back({"readback", t_read});
        timings_.push_back({"reduce", t_reduce});
    }

    int resolution_for(const Shooter& shooter) {
        int res = options_.resolution;
        if (res == 0) {
            // Less unshot power, coarser cube (paper 002 §2): resolution scales with the square
            // root of the shooter's power relative to the strongest shooter so far.
            max_power_ = std::max(max_power_, shooter.unshot_power);
            const double rel = max_power_ > 0 ? shooter.unshot_power / max_power_ : 1.0;
            res = int(std::lround(options_.max_resolution * std::sqrt(rel) / 8.0)) * 8;
            res = std::clamp(res, options_.min_resolution, options_.max_resolution);
            res += res % 2;
        }
        return res;
    }

    const gpu::HemicubeLayout& layout_for(const Shooter& shooter) {
        return layout_of(resolution_for(shooter));
    }

    const gpu::HemicubeLayout& layout_of(int res) {
        auto it = std::find_if(layouts_.begin(), layouts_.end(),
                               [res](const gpu::HemicubeLayout& l) { return l.res == res; });
        if (it != layouts_.end()) return *it;
        layouts_.push_back(gpu::make_hemicube_layout(res));
        return layouts_.back();
    }

    // The stand-in shooter of a point shot's hemicube along side * axis: a square of side
    // 2 half centred on the point (its size sets only the near plane; its first edge, the
    // frame), of no polygon, with a corner count of 0 so that the fragment shader computes no
    // polygon form factor (its loop over the shooter's corners is empty).
    Shooter point_shooter(const Sphere& p, double side) const {
        Shooter s;
        s.address = {kNoShooterPolygon, 0, 0};
        s.normal = side * p.axis;
        const dvec3 a = p.half * p.first, b = p.half * glm::cross(s.normal, p.first);
        s.geometry.count = 0;
        s.geometry.corners = {p.centre - a - b, p.centre + a - b, p.centre + a + b,
                              p.centre - a + b};
        s.geometry.centre = p.centre;
        s.geometry.area = 4 * p.half * p.half;
        return s;
    }

    // Is x in front of a patch shooter's plane (not behind it, nor in it)?
    bool before_shooter(const Shooter& s, const dvec3& x) const {
        return glm::dot(x - s.geometry.centre, s.normal) > plane_eps_;
    }

    // F(dA_j -> S) of the polygon shooter, or for a point shot E_j per watt emitted (see
    // shoot_sphere), at a receiver centre with normal n, unoccluded.
    double analytic_at(const Shooter& s, const dvec3& centre, const dvec3& n) const {
        if (point_) {
            const dvec3 d = centre - point_->centre;
            const double r2 = glm::dot(d, d);
            if (!(r2 > 0)) return 0;
            const dvec3 w = d / std::sqrt(r2);
            const double cos_theta = -glm::dot(n, w);
            if (!(cos_theta > 0)) return 0;
            return point_->intensity(w) * cos_theta / r2;
        }
        // A patch emits from its front only: a point behind it (or in its plane) gets nothing
        // (the kernel below would integrate over the shooter's back).
        if (!before_shooter(s, centre)) return 0;
        return point_to_polygon_ff(centre, n, s.geometry.corners.data(), s.geometry.count);
    }

    // analytic_at for a receiver near a patch shooter. Where the shooter's unshot radiosity
    // is uneven (Shooter::emission) and the receiver faces it (a board or a shelf's back
    // across a gap from a wall: the part of the wall in front of it fills its view), the
    // kernels of the shooter's parts weighted by their radiosity over its mean, a part split
    // while it is larger than its distance from x. The back of the office glb's whiteboard,
    // 1.3 cm from a wall half in its shadow, read 3x the light with the wall's mean. Receivers
    // across the shooter's edges (the next wall in a corner) keep the even kernel: weighting
    // them too tripled the Cornell box's solve time, for 0.1 % at its points, and raised its
    // row sums to 1.05 (only near receivers are weighted; the far ones keep the mean).
    static constexpr double kFacing = -0.7; ///< n . shooter normal at most this: facing it
    static bool faces(const Shooter& s, const dvec3& n) { return glm::dot(n, s.normal) <= kFacing; }
    bool weighs_emission(const Shooter& s, const dvec3& n) const {
        return !s.emission.empty() && !point_ && faces(s, n);
    }
    // (weigh false: the even kernel, as if the shooter's emission were even.)
    double near_kernel(const Shooter& s, const dvec3& x, const dvec3& n, bool weigh) const {
        if (!weigh || !weighs_emission(s, n)) return analytic_at(s, x, n);
        if (!before_shooter(s, x)) return 0;
        const Polygon& poly = scene_->polygons[s.address.polygon];
        std::size_t at = 0;
        return emitter_parts(s, poly, x, n, s.address.level, s.address.index, s.emission_levels,
                             at);
    }

    // The weighted kernels of the children of a shooter's node (level, index), `levels` deep
    // in Shooter::emission from `at` (advanced past them).
    double emitter_parts(const Shooter& s, const Polygon& poly, const dvec3& x, const dvec3& n,
                         std::uint32_t level, std::uint32_t index, int levels,
                         std::size_t& at) const {
        double f = 0;
        for (std::uint32_t c : patch_children(poly.is_triangle(), level, index)) {
            const float w = s.emission[at++];
            const PatchGeometry g = patch_geometry(poly, level + 1, c);
            if (levels > 1 && g.area > glm::dot(x - g.centre, x - g.centre)) {
                f += emitter_parts(s, poly, x, n, level + 1, c, levels - 1, at);
                continue;
            }
            // Its descendants, not read: 4 + 16 + ... for levels - 1 levels.
            at += std::size_t((std::uint64_t(1) << (2 * levels)) - 4) / 3;
            if (w > 0) f += w * point_to_polygon_ff(x, n, g.corners.data(), g.count);
        }
        return f;
    }

    // A patch shooter's F(j->S) over receiving node a, given its value at a's centre: where
    // the kernel varies across a (a node as large as its distance from the shooter: a lamp's
    // housing a centimetre from the lamp) the centre alone reads it far off, a row of such
    // nodes summing to 2 and more; there it is the mean over a's quadtree parts. A part is
    // split while it is larger than an eighth of its centre's distance to the shooter's
    // polygon, for three levels; below them, only while it is larger than that distance (it
    // touches the shooter's edge, where the kernel peaks logarithmically), to six levels below
    // a. On paper 000's cube at 4x4 polygons the faces' factors are within 0.06 % of the closed
    // forms, where the centres alone are 1 % off. A lamp 3 mm wide against a wall that meets
    // its edge (the office glb's LED bars against the PC's case) reads 2.8 % low; it read 47 %
    // low with at most three levels of parts by the distance to the shooter's centre and the
    // wall's polygons on no pixel at their centre values (tests/hemicube_gl_test.cpp,
    // NearReceivers). Parts wider than the shooter (its area over its longest edge) are split
    // on past the sixth level, to the twelfth: a node 8 cm x 25 cm across a gap of 0.8 mm
    // from a part of an LED bar 0.8 mm wide (the office glb's bar, split into quarters) took
    // the kernel at the centres of parts 2 mm long where it falls from 0.5 to 0.1 within
    // 2 mm, and read 5.6 % high (-0.8 % at the twelfth level; rows up to 1.0075 -> 1.001).
    // A receiver that faces the shooter across a gap (a bookshelf's plinth 1.6 cm from the
    // wall behind it) takes its light in a bump as wide as the gap, which parts as large as
    // their distance read high at their centres: such parts are split down to 0.35 of it. A
    // part of the plinth 47 cm x 1.4 cm put 0.8062 of its light on the wall, where the exact
    // integral is 0.8044 (0.8041 now; 0.8062 with 0.5, 0.8045 with 0.25), its row 1.0017
    // (office glb: up to 1.0044; tests/hemicube_gl_test.cpp, NearReceivers.APlinthAcross...).
    // The office lit by point sources: rows rescaled by the guard 235 -> 70, the solve's time
    // per shot 17.0 -> 17.4 ms (18.6 ms with 0.25).
    static constexpr double kMeanRatio = 0.125;        ///< split while size > this x distance, ...
    static constexpr std::uint32_t kMeanLevels = 3;    ///< ... for this many levels below a;
    static constexpr double kEdgeRatio = 1.0;          ///< then while size > this x distance
    static constexpr double kFacingRatio = 0.35;       ///< (this x, for a receiver facing it),
    static constexpr std::uint32_t kEdgeLevels = 6;    ///< to this many levels below a,
    static constexpr std::uint32_t kSliverLevels = 12; ///< or this many for parts wider than
                                                       ///< the shooter
    float area_mean_analytic(const Shooter& s, const PatchAddress& a, const PatchGeometry& g,
                             float at_centre, bool weigh = true) const {
        if (point_) return at_centre;
        const Polygon& poly = scene_->polygons[a.polygon];
        // (A patch index of level 15 still fits 32 bits.)
        const std::uint32_t deepest = std::min<std::uint32_t>(a.level + kSliverLevels, 15);
        const double width = s.geometry.area / longest_edge(s.geometry.corners, s.geometry.count);
        return float(part_mean(s, poly, a.level, a.index, g.centre,
                               part_size(g.area, longest_edge(g.corners, g.count)),
                               deepest - a.level, 0, at_centre, weigh, width));
    }

    // The mean of the kernel over part `index` of `level` of poly (its centre; size: the
    // square root of its area), `depth` levels below the node, split as area_mean_analytic()
    // says for at most `levels` levels (past kEdgeLevels only while wider than `width`, the
    // shooter's); `value` is the kernel at its centre if known (else negative).
    double part_mean(const Shooter& s, const Polygon& poly, std::uint32_t level,
                     std::uint32_t index, const dvec3& centre, double size, std::uint32_t levels,
                     std::uint32_t depth, double value, bool weigh, double width) const {
        const double ratio = depth < kMeanLevels     ? kMeanRatio
                             : faces(s, poly.normal) ? kFacingRatio
                                                     : kEdgeRatio;
        if (depth >= levels || (depth >= kEdgeLevels && size <= width) ||
            small_for_distance(s, centre, size, ratio))
            return value >= 0 && !(weigh && weighs_emission(s, poly.normal))
                       ? value
                       : near_kernel(s, centre, poly.normal, weigh);
        // The parts' means weighted by their areas: a quad that is no parallelogram has parts
        // of unequal area (the office glb's wall beside an LED bar, a trapezoid whose short
        // side meets the bar: its nodes read 6.5 % high with equal weights, the bar's rows
        // up to 1.05; tests/hemicube_gl_test.cpp, NearReceivers).
        double total = 0, weights = 0;
        for (std::uint32_t c : patch_children(poly.is_triangle(), level, index)) {
            const double w = patch_area(poly, level + 1, c);
            total += w * part_mean(s, poly, level + 1, c, patch_centre(poly, level + 1, c),
                                   0.5 * size, levels, depth + 1, -1.0, weigh, width);
            weights += w;
        }
        return weights > 0 ? total / weights : 0.0;
    }

    // The distance from x to a patch shooter's polygon [unit] (its corners: convex, either
    // way round).
    static double distance_to_shooter(const Shooter& s, const dvec3& x) {
        const PatchGeometry& g = s.geometry;
        int left = 0, right = 0; // edges that x projects to the left and right of
        double nearest = 1e300;  // squared, to the nearest edge
        for (int k = 0; k < g.count; ++k) {
            const dvec3& a = g.corners[std::size_t(k)];
            const dvec3 e = g.corners[std::size_t((k + 1) % g.count)] - a;
            const dvec3 ax = x - a;
            const double side = glm::dot(glm::cross(e, ax), s.normal);
            left += side > 0;
            right += side < 0;
            const double ee = glm::dot(e, e);
            const double t = ee > 0 ? std::clamp(glm::dot(ax, e) / ee, 0.0, 1.0) : 0.0;
            const dvec3 d = ax - t * e;
            nearest = std::min(nearest, glm::dot(d, d));
        }
        if (left == 0 || right == 0) return std::abs(glm::dot(x - g.centre, s.normal)); // over it
        return std::sqrt(nearest);
    }

    // The size of a part of a receiver for the tests that split it: the square root of its
    // area, or half its longest edge where that is longer (a sliver: the office glb's LED bar
    // faces, 1.4 cm x 86 cm, 3.3 mm across a gap from a strip of the PC case; their parts were
    // split while the square root of their area exceeded the gap, so that parts 27 mm long
    // stood for the strip's kernel at their centres, 2-14 % high: 84 rows over 1.001, up to
    // 1.044; tests/hemicube_gl_test.cpp, NearReceivers). The same for squares and right or
    // equilateral triangles.
    static double part_size(double area, double longest) {
        return std::max(std::sqrt(area), 0.5 * longest);
    }
    template <class Corners> static double longest_edge(const Corners& v, int count) {
        double longest = 0;
        for (int k = 0; k < count; ++k)
            longest =
                std::max(longest, glm::length(v[std::size_t((k + 1) % count)] - v[std::size_t(k)]));
        return longest;
    }

    // The farthest of `count` corners from `centre`.
    static double reach(const std::array<dvec3, 4>& corners, int count, const dvec3& centre) {
        double r = 0;
        for (int k = 0; k < count; ++k) r = std::max(r, glm::length(corners[k] - centre));
        return r;
    }

    // Whether node a of area area_j may be near enough to a patch shooter for
    // area_mean_analytic() to split it: the same test, first with the nearest that any point
    // of its polygon can be (no node geometry for the many far ones), then with its centre.
    // (1 + 2e-6): area_j is the node's area in float.
    bool may_be_near(const Shooter& s, const PatchAddress& a, double area_j) const {
        if (point_) return false;
        const std::uint32_t p = a.polygon;
        const double size =
            part_size(area_j * (1 + 2e-6), longest_[p] / double(std::uint64_t(1) << a.level));
        const double r = glm::length(centre_[p] - s.geometry.centre) - radius_[p] - shooter_radius_;
        if (size <= kMeanRatio * r) return false;
        const dvec3 c = patch_centre(scene_->polygons[p], a.level, a.index);
        return !small_for_distance(s, c, size, kMeanRatio);
    }

    // Is size <= ratio times x's distance to a patch shooter's polygon? Tested first against
    // the distance to its centre less its reach (every point of it lies within the reach of
    // the centre: a lower bound that takes one square root), where most receivers are far.
    bool small_for_distance(const Shooter& s, const dvec3& x, double size, double ratio) const {
        const double at_least = glm::length(x - s.geometry.centre) - shooter_radius_;
        if (size <= ratio * at_least * (1 - 1e-12)) return true;
        return size <= ratio * distance_to_shooter(s, x);
    }

    // In hybrid, node a's analytic value (`at_centre`: the kernel at its centre; area_j: its
    // area) as area_mean_analytic() takes it where a may be near the shooter; else at_centre.
    float near_mean(const Shooter& s, const PatchAddress& a, double area_j, float at_centre) const {
        if (mode_ != Mode::Hybrid || !may_be_near(s, a, area_j)) return at_centre;
        return area_mean_analytic(
            s, a, patch_geometry(scene_->polygons[a.polygon], a.level, a.index), at_centre);
    }

    // Does polygon p reach in front of a patch shooter's plane? One wholly behind it, or in it
    // (a neighbour in the same plane), gets nothing from it, whatever pixels at the horizon
    // show: float rounding rasterises an edge-on polygon there.
    bool in_front_of(const Shooter& s, std::uint32_t p) const {
        const Polygon& q = scene_->polygons[p];
        for (int k = 0; k < q.count; ++k)
            if (before_shooter(s, q.v[k])) return true;
        return false;
    }

    std::uint64_t node_id(std::uint32_t p, std::uint32_t level, std::uint32_t index) const {
        return base_[p] + level_offset(int(level)) + index;
    }

    // Cached on first use; link_in_chunks's threads may both fill an entry, with one value.
    float area(std::uint32_t p, std::uint32_t level, std::uint32_t index) const {
        std::atomic<float>& cached = area_[node_id(p, level, index)];
        float a = cached.load(std::memory_order_relaxed);
        if (a < 0) {
            a = float(patch_geometry(scene_->polygons[p], level, index).area);
            cached.store(a, std::memory_order_relaxed);
        }
        return a;
    }

    // Was an ancestor of node (p, level, index) seen in this shot?
    bool ancestor_seen(std::uint32_t p, std::uint32_t level, std::uint32_t index) const {
        const bool tri = scene_->polygons[p].is_triangle();
        while (level > 0) {
            index = patch_parent(tri, level, index);
            --level;
            if (seen_[node_id(p, level, index)] == stamp_) return true;
        }
        return false;
    }

    // Fully occluded: in front of the shooter, yet neither it, nor an ancestor, nor a
    // descendant was seen on the hemicube.
    bool occluded(const Shooter& s, std::uint32_t p, std::uint32_t level,
                  std::uint32_t index) const {
        const std::uint64_t id = node_id(p, level, index);
        if (seen_[id] == stamp_ || below_seen_[id] == stamp_ || ancestor_seen(p, level, index))
            return false;
        const PatchGeometry g = patch_geometry(scene_->polygons[p], level, index);
        // (A point shot sees the whole sphere: nothing is behind it.)
        if (!point_ && glm::dot(g.centre - s.geometry.centre, s.normal) <= 0) return false;
        const dvec3 to_shooter = s.geometry.centre - g.centre;
        if (glm::dot(scene_->polygons[p].normal, to_shooter) <= 0) return false;
        return true;
    }

    void reduce(const Shooter& shooter, const gpu::HemicubeLayout& layout,
                std::vector<Link>& links) {
        touched_.clear();
        const gpu::HemicubeFrame frame = gpu::hemicube_frame(shooter);
        gpu::fill_cracks(*scene_, layout, frame, pixels_.data(), shooter.geometry.centre, ids_);
        const float* rgba = pixels_.data();
        const std::size_t n = std::size_t(layout.width) * layout.height;
        // Neighbouring pixels mostly show the same node: a run of them is added to it at once.
        double backface = 0;
        const auto add_runs = [&] {
            gpu::for_each_pixel_run(rgba, n, [&](std::size_t first, std::size_t count) {
                const float b = rgba[4 * first + 2];
                if (b > -0.5f && b < 0.5f) return; // nothing
                if (b < 0) {                       // the back of a polygon
                    for (std::size_t i = first; i < first + count; ++i)
                        backface += layout.delta_ff[i];
                    return;
                }
                scan_pixels(rgba, first, run_sum(layout.delta_ff, first, count),
                            std::uint32_t(count));
            });
        };
        const gpu::HemicubeVisibility vis(*scene_, layout, frame, pixels_.data(),
                                          shooter.geometry.centre, ids_.data());
        vis_[0] = vis_[1] = &vis;
        sphere_axis_ = dvec3(0.0);
        if (mode_ == Mode::Hybrid)
            mark_partial(vis, pixels_.data(), gpu::face_threads(layout), add_runs);
        else
            add_runs();
        backface_ = backface;
        // The seen nodes and the polygons no pixel shows, linked in one loop.
        link_in_chunks(links,
                       {touched_job(shooter, shooter.geometry.area, gpu::face_threads(layout)),
                        missed_polygons_job(shooter, vis)});
        vis_[0] = vis_[1] = nullptr;
        if (mode_ == Mode::Hybrid) {
            share_the_rest(shooter, links);
            see_from_parts(shooter, links);
        }
    }

    // A patch shooter's links stand on what its centre sees: a node seen whole from there
    // takes the whole shooter's kernel, though parts of the shooter may not see it. Where the
    // links sum to more than 1 % over all the shooter's light (receivers that hide one another
    // from parts of the shooter, both seen from its centre, as a desk and a chair under a
    // shelf's underside: office glb rows up to 1.099), each link takes the share of the
    // shooter's kernel that reaches it unblocked from the centres of the shooter's 64 parts
    // three levels down, a ray cast from each: a node seen whole from the centre, to its centre;
    // one that a silhouette crosses there, to its centre and its children's, at most that share
    // of its analytic value (tests/hemicube_gl_test.cpp, ShooterParts). While the row stays
    // over 1.001, the same from 256 parts four levels down, then 1024 five levels down: where
    // the blockers are low walls along the shooter's sides (the PC face between the office's
    // two LED bars, 3.3 mm high), what they hide lies within a few millimetres of them: 16
    // parts found a 0.052 share of the light hidden, 64 find 0.071, 256 about 0.08, the exact
    // share (row 1.026 -> 1.006 -> 0.9995). The light that parts send to what the centre
    // does not see has no link and is lost: the other error of the centre's view, which on
    // average cancels the first. So rows under 1.01 keep the centre's view: the seventeenth
    // session cast these rays for every row, and the Cornell box read low (mean -1.40 ->
    // -3.21 % without the final gather); past 1.001 (twenty-fifth session), room402's shots
    // (rows 1.001-1.006) took 4.7 bare hemicubes, and where only the links that pass a
    // polygon near the shooter were judged, 1.6, the office's rows that such polygons caused
    // going from 1.003-1.01 to 0.89-0.99.
    static constexpr double kRowSlack = 0.01, kRowBar = 0.001;
    static constexpr std::uint32_t kFirstPartDepth = 3, kLastPartDepth = 5;
    void see_from_parts(const Shooter& s, std::vector<Link>& links) const {
        if (point_ || hidden_ || s.address.polygon >= scene_->polygons.size()) return;
        const double row = row_sum(links) / s.geometry.area;
        if (!(row > 1 + kRowSlack)) return;
        std::vector<float> centre_ff(links.size());
        for (std::size_t i = 0; i < links.size(); ++i) centre_ff[i] = links[i].ff;
        // Deeper only while the rays find something hidden: a row they leave as it was (its
        // excess not the centre's view: the office's whiteboard back, 1.04) would cost 1344
        // rays a link for nothing.
        for (std::uint32_t depth = kFirstPartDepth; depth <= kLastPartDepth; ++depth) {
            for (std::size_t i = 0; i < links.size(); ++i) links[i].ff = centre_ff[i];
            scale_by_parts(s, shooter_parts(s, depth), links);
            const double judged = row_sum(links) / s.geometry.area;
            if (!(judged > 1 + kRowBar) || !(judged < row - kRowBar)) break;
        }
        std::erase_if(links, [](const Link& l) { return !(l.ff > 0); });
    }

    // The links' share of the shooter's light, times its area.
    double row_sum(const std::vector<Link>& links) const {
        double row = 0;
        for (const Link& l : links)
            row += double(l.ff) * area(l.receiver.polygon, l.receiver.level, l.receiver.index);
        return row;
    }

    // The centres and areas of the shooter's parts `depth` levels down.
    std::vector<std::pair<dvec3, double>> shooter_parts(const Shooter& s,
                                                        std::uint32_t depth) const {
        const Polygon& shooter = scene_->polygons[s.address.polygon];
        const bool tri = shooter.is_triangle();
        std::vector<std::uint32_t> nodes{s.address.index}, below;
        for (std::uint32_t level = s.address.level; level < s.address.level + depth; ++level) {
            below.clear();
            for (std::uint32_t n : nodes)
                for (std::uint32_t c : patch_children(tri, level, n)) below.push_back(c);
            nodes.swap(below);
        }
        std::vector<std::pair<dvec3, double>> parts;
        parts.reserve(nodes.size());
        for (std::uint32_t n : nodes) {
            const PatchGeometry g = patch_geometry(shooter, s.address.level + depth, n);
            parts.emplace_back(g.centre, g.area);
        }
        return parts;
    }

    // Each link scaled by the share of the shooter's kernel that reaches it unblocked from
    // `parts` (see_from_parts).
    void scale_by_parts(const Shooter& s, const std::vector<std::pair<dvec3, double>>& parts,
                        std::vector<Link>& links) const {
        for_chunks(
            links.size(), std::min<std::size_t>(links.size(), 64), 0,
            [&](std::size_t, std::size_t begin, std::size_t end) {
                std::array<dvec3, 5> at;
                for (std::size_t i = begin; i < end; ++i) {
                    Link& l = links[i];
                    const PatchAddress& r = l.receiver;
                    const Polygon& q = scene_->polygons[r.polygon];
                    at[0] = patch_centre(q, r.level, r.index);
                    std::size_t points = 1;
                    if (l.partial) // its children's centres too (link_visible_parts)
                        for (std::uint32_t c : patch_children(q.is_triangle(), r.level, r.index))
                            at[points++] = patch_centre(q, r.level + 1, c);
                    double all = 0, seen = 0;
                    for (std::size_t k = 0; k < points; ++k)
                        for (const auto& [y, a] : parts) {
                            const dvec3 d = at[k] - y;
                            const double r2 = glm::dot(d, d);
                            const double w = a * std::max(0.0, glm::dot(s.normal, d)) *
                                             std::max(0.0, -glm::dot(q.normal, d)) / (r2 * r2);
                            if (!(w > 0)) continue;
                            all += w;
                            if (!bvh_->occluded(y, at[k], s.address.polygon, r.polygon)) seen += w;
                        }
                    if (!(all > 0)) continue;
                    // A node seen whole from the centre: the parts' share of it. One
                    // that a silhouette crosses there (its value the share the centre
                    // sees): at most the parts' share.
                    l.ff = l.partial ? std::min(l.ff, float(l.ff_analytic * (seen / all)))
                                     : float(double(l.ff) * (seen / all));
                }
            });
    }

    // Where a shooter's unshot light is uneven, the near receivers that face it take its
    // parts' kernels weighted by their radiosity (near_kernel), more of its light than its
    // mean gives them where its bright parts face them; the rest of the scene took the mean's
    // shares. Each part sends all its light once, so what those receivers take more (or less)
    // the others lose (or gain), in proportion: they are scaled by (1 - weighted) / (1 - even),
    // the weighted receivers' share of the row with the parts' kernels and with the mean's.
    // In the office glb, a desk's side panel whose lit part faces a PC case 34 cm away gave the
    // case 0.137 of its row where the mean gives 0.065, and its row summed to 1.15
    // (tests/hemicube_gl_test.cpp, NearReceivers).
    void share_the_rest(const Shooter& s, std::vector<Link>& links) const {
        if (s.emission.empty() || point_) return;
        double weighted = 0, even = 0;
        std::vector<char> was_weighted(links.size());
        for (std::size_t i = 0; i < links.size(); ++i) {
            const Link& l = links[i];
            const Polygon& poly = scene_->polygons[l.receiver.polygon];
            const double area_j = area(l.receiver.polygon, l.receiver.level, l.receiver.index);
            if (!weighs_emission(s, poly.normal) || !may_be_near(s, l.receiver, area_j)) continue;
            const double parts = l.ff_analytic; // its weighted mean (near_mean)
            if (!(parts > 0)) continue;
            was_weighted[i] = 1;
            const double flux = double(l.ff) * area_j;
            weighted += flux;
            const PatchGeometry g = patch_geometry(poly, l.receiver.level, l.receiver.index);
            even += flux * area_mean_analytic(s, l.receiver, g, -1.f, false) / parts;
        }
        weighted /= s.geometry.area;
        even /= s.geometry.area;
        if (weighted == even || !(even < 1)) return;
        const double scale = std::max(0.0, 1 - weighted) / (1 - even);
        for (std::size_t i = 0; i < links.size(); ++i)
            if (!was_weighted[i]) links[i].ff = float(double(links[i].ff) * scale);
        std::erase_if(links, [](const Link& l) { return !(l.ff > 0); });
    }

    // Nodes that a silhouette crosses (gpu::HemicubeVisibility::occlusion_edges): the
    // pixels where their polygon goes on behind something nearer border theirs.
    // The faces are searched on threads of their own, the marks set after. `alongside`, work
    // that neither reads nor sets the marks, runs first as one more item of the same loop
    // (the reduction's pixel runs: one thread adds them while the other searches faces).
    template <class Work>
    void mark_partial(const gpu::HemicubeVisibility& vis, const float* rgba, int threads,
                      Work&& alongside) {
        for (auto& m : edge_pixels_) m.clear();
        parallel_for(6, threads, [&](std::size_t k) {
            if (k == 0) return alongside();
            const std::size_t f = k - 1;
            vis.occlusion_edges(int(f), [&](std::size_t i) { edge_pixels_[f].push_back(i); });
        });
        for (const auto& m : edge_pixels_)
            for (std::size_t i : m) {
                const float* px = &rgba[4 * i];
                partial_[node_id(std::uint32_t(px[2]) - 1, std::uint32_t(px[1]),
                                 std::uint32_t(px[0]))] = stamp_;
            }
    }

    // Is x (on polygon p) seen by the shooter, in the hemicube of its side (a point shot has
    // two: along and against its axis)?
    bool visible(const dvec3& x, std::uint32_t p) const {
        const bool front = glm::dot(sphere_axis_, sphere_axis_) == 0 ||
                           glm::dot(x - sphere_centre_, sphere_axis_) >= 0;
        const gpu::HemicubeVisibility* v = vis_[front ? 1 : 0];
        return v && v->visible(x, p);
    }

    // Links the parts of node a that the shooter sees (a silhouette crosses a): a is sampled
    // at its centre and its four children's centres; all seen, it is linked whole (analytic
    // value at its centre), or by the share its own pixels show (pixel_seen_share: a strip
    // thinner than the samples' spacing may be hidden); some seen, its children are taken one
    // by one, down to the leaves, where the share of samples seen scales the value; none
    // seen, nothing (a sliver between the samples: its pixels, at most the analytic value,
    // when a was seen itself).
    void link_visible_parts(const Shooter& shooter, const PatchAddress& a, float analytic,
                            double pixel_power, bool has_pixels, std::vector<Link>& links) const {
        const Polygon& poly = scene_->polygons[a.polygon];
        const bool tri = poly.is_triangle();
        const PatchGeometry g = patch_geometry(poly, a.level, a.index);
        int seen = visible(g.centre, a.polygon) ? 1 : 0;
        const std::array<std::uint32_t, 4> children = patch_children(tri, a.level, a.index);
        for (std::uint32_t c : children)
            seen += visible(patch_centre(poly, a.level + 1, c), a.polygon) ? 1 : 0;
        const double area_j = area(a.polygon, a.level, a.index);
        if (analytic < 0) analytic = float(analytic_at(shooter, g.centre, poly.normal));
        analytic = near_mean(shooter, a, area_j, analytic);
        Link l;
        l.receiver = a;
        l.ff_analytic = analytic;
        l.ff_pixel = float(pixel_power / area_j);
        l.partial = seen < 5;
        if (point_ && has_pixels && pixels_seen(a) >= kNearPixels) {
            l.ff = l.ff_pixel; // near a point shot (add_link)
        } else if (seen == 5) {
            const double share = has_pixels ? pixel_seen_share(shooter, a, g, pixel_power) : 1;
            l.ff = analytic * float(std::clamp(share, 0.0, 1.0));
            l.partial = share < 1;
        } else if (seen == 0) {
            l.ff = has_pixels ? std::min(l.ff_pixel, analytic) : 0.f;
        } else if (int(a.level) < disc_.depth[a.polygon]) {
            for (std::uint32_t c : children)
                link_visible_parts(shooter, {a.polygon, a.level + 1, c}, -1.f, 0.0, false, links);
            return;
        } else if (has_pixels) { // a leaf seen itself: its pixels measure the part seen
            l.ff = std::min(l.ff_pixel, analytic);
        } else {
            l.ff = analytic * float(seen) / 5.f;
        }
        if (l.ff > 0) links.push_back(l);
    }

    // The share of node a (geometry g) that a patch shooter's centre sees, as its pixels
    // measure it: their form factor over the exact one from the centre to all of a. Where a
    // silhouette borders a's pixels but all five samples of link_visible_parts see it, what
    // is hidden is thinner than the samples' spacing: in the office glb, an LED bar 3.3 mm
    // proud of a PC case's side hides a 5 mm strip along a node's near edge, 30 % of its
    // light (the case's inner face's row 1.0027 -> 1.0003; 2,000,000 cosine rays: the node's
    // polygon 0.00934 of the light, 0.01128 before, 0.00933 now); in room402 the legs of
    // chairs on floor nodes of 17 pixels (a ceiling light's row 1.0032 -> 0.9984; the floor's
    // share 0.5213 -> 0.5188, 0.5195 by rays). 1 (no measure) where pixels are not all a's
    // own (a seen ancestor or descendant took some) or a reaches behind the shooter's plane
    // (seen at the horizon, where pixels are coarse).
    double pixel_seen_share(const Shooter& s, const PatchAddress& a, const PatchGeometry& g,
                            double pixel_power) const {
        if (point_ || below_seen_[node_id(a.polygon, a.level, a.index)] == stamp_ ||
            ancestor_seen(a.polygon, a.level, a.index))
            return 1;
        for (int k = 0; k < g.count; ++k)
            if (!before_shooter(s, g.corners[k])) return 1;
        const double whole =
            point_to_polygon_ff(s.geometry.centre, s.normal, g.corners.data(), g.count) *
            s.geometry.area;
        return whole > 0 ? pixel_power / whole : 1;
    }

    // The sum of a run's per-pixel weights, `count` from pixel `first`, in float (the order of
    // the sums the pixel-by-pixel scan had).
    static float run_sum(const std::vector<float>& weights, std::size_t first, std::size_t count) {
        float sum = 0;
        for (std::size_t i = first; i < first + count; ++i) sum += weights[i];
        return sum;
    }

    // The pixels that showed node a in this shot (0 for a node no pixel showed: its count is
    // an earlier shot's).
    std::uint32_t pixels_seen(const PatchAddress& a) const {
        const std::uint64_t id = node_id(a.polygon, a.level, a.index);
        return seen_[id] == stamp_ ? pixel_count_[id] : 0;
    }

    // `count` pixels from pixel `i` of `rgba` show the front (B > 0) of one node: marks it seen
    // (taking its analytic value from alpha the first time) and adds `weight` (their summed
    // weight) to its pixel sum and `count` to its pixels.
    void scan_pixels(const float* rgba, std::size_t i, float weight, std::uint32_t count) {
        const float* px = &rgba[4 * i];
        const auto p = std::uint32_t(px[2]) - 1;
        polygon_seen_[p] = stamp_;
        const auto level = std::uint32_t(px[1]);
        const auto index = std::uint32_t(px[0]);
        const std::uint64_t id = node_id(p, level, index);
        if (seen_[id] != stamp_) {
            seen_[id] = stamp_;
            pixel_sum_[id] = 0;
            pixel_count_[id] = 0;
            analytic_[id] = px[3];
            touched_.push_back({p, level, index});
            mark_ancestors(touched_.back());
        }
        pixel_sum_[id] += weight;
        pixel_count_[id] += count;
    }

    // Marks the ancestors of seen node a: "something below was seen" (link_node, occluded).
    void mark_ancestors(const PatchAddress& a) {
        const bool tri = scene_->polygons[a.polygon].is_triangle();
        std::uint32_t l = a.level, i = a.index;
        while (l > 0) {
            i = patch_parent(tri, l, i);
            --l;
            std::uint32_t& b = below_seen_[node_id(a.polygon, l, i)];
            if (b == stamp_) break;
            b = stamp_;
        }
    }

    // A list of items to link in chunks (link_in_chunks): link(begin, end, out) links items
    // [begin, end) into out.
    struct LinkJob {
        std::size_t n = 0;      ///< items
        std::size_t chunks = 1; ///< chunk_count()
        std::function<void(std::size_t, std::size_t, std::vector<Link>&)> link;
    };

    // Links every node seen in this shot (scan_pixels has marked their ancestors).
    // pixel_scale turns a node's pixel sum into the pixel value's numerator: A_S for a
    // polygon shooter (A_S F(S->j)), 1 for a point shot.
    LinkJob touched_job(const Shooter& shooter, double pixel_scale, int threads) const {
        return {touched_.size(), chunk_count(touched_.size(), kChunkNodes, threads),
                [this, &shooter, pixel_scale](std::size_t begin, std::size_t end,
                                              std::vector<Link>& out) {
                    for (std::size_t k = begin; k < end; ++k)
                        link_node(shooter, touched_[k], pixel_scale, out);
                }};
    }

    // How many chunks of about `chunk` items n items are cut into: one where n is under a
    // chunk or one thread runs them.
    static std::size_t chunk_count(std::size_t n, std::size_t chunk, int threads) {
        return threads == 1 || n < chunk ? 1 : n / chunk;
    }

    // Calls body(c, begin, end) for each of `chunks` equal chunks [begin, end) of [0, n), on
    // `threads` (the chunks, and so any sums kept per chunk, do not depend on the threads).
    template <class Body>
    static void for_chunks(std::size_t n, std::size_t chunks, int threads, Body&& body) {
        parallel_for(chunks, threads,
                     [&](std::size_t c) { body(c, c * n / chunks, (c + 1) * n / chunks); });
    }

    // Links the items of each job (in chunks), all chunks in one loop: on all cores where
    // there is more than one chunk. Each chunk goes into its own list, the lists appended to
    // `links` in order: the links come in the order one thread would give them, job by job.
    void link_in_chunks(std::vector<Link>& links, std::initializer_list<LinkJob> jobs) {
        std::size_t chunks = 0;
        for (const LinkJob& job : jobs) chunks += job.chunks;
        chunk_links_.resize(std::max(chunk_links_.size(), chunks));
        parallel_for(chunks, chunks > 1 ? 0 : 1, [&](std::size_t c) {
            // Filled on this thread's stack (chunk_links_'s vectors share cache lines: each
            // push_back would move the line between the cores), its memory kept for later.
            std::vector<Link> out = std::move(chunk_links_[c]);
            out.clear();
            std::size_t k = c; // the chunk's number within its job
            for (const LinkJob& job : jobs) {
                if (k < job.chunks) {
                    job.link(k * job.n / job.chunks, (k + 1) * job.n / job.chunks, out);
                    break;
                }
                k -= job.chunks;
            }
            chunk_links_[c] = std::move(out);
        });
        std::size_t total = links.size();
        for (std::size_t c = 0; c < chunks; ++c) total += chunk_links_[c].size();
        links.reserve(total);
        for (std::size_t c = 0; c < chunks; ++c)
            links.insert(links.end(), chunk_links_[c].begin(), chunk_links_[c].end());
    }

    // Links seen node a (touched_job): split where seen descendants are linked too, by its
    // visible parts where a silhouette crosses it, else whole.
    void link_node(const Shooter& shooter, const PatchAddress& a, double pixel_scale,
                   std::vector<Link>& links) const {
        if (!point_ && !in_front_of(shooter, a.polygon)) return;
        const std::uint64_t id = node_id(a.polygon, a.level, a.index);
        if (below_seen_[id] == stamp_) {
            // The oracle picks a level per fragment, so where GL's LOD crosses a level a
            // node and some of its descendants are both seen. Linking both would deliver
            // light twice to the descendants' area; the finer links win, and the rest of
            // this node is linked by "filler" children that were not seen themselves.
            split(shooter, a, double(pixel_sum_[id]) * pixel_scale, links);
            return;
        }
        if (mode_ == Mode::Hybrid && partial_[id] == stamp_)
            link_visible_parts(shooter, a, analytic_[id], double(pixel_sum_[id]) * pixel_scale,
                               true, links);
        else
            add_link(shooter, a, analytic_[id], double(pixel_sum_[id]) * pixel_scale, links);
    }

    // A polygon smaller than a pixel can fall between pixel centres and get no pixel at all
    // (the oracle can coarsen within a polygon, not below one): its light would be lost,
    // and the rows of closed scenes of many small polygons would sum under 1. Every polygon
    // in front of the shooter that no pixel shows is linked whole, with its analytic value
    // computed here (its mean, near the shooter: near_mean), if its centre is seen
    // (centre_seen).
    LinkJob missed_polygons_job(const Shooter& shooter, const gpu::HemicubeVisibility& vis) const {
        const std::size_t n = mode_ == Mode::Hemicube ? 0 : scene_->polygons.size();
        return {n, chunk_count(n, kChunkPolygons, 0),
                [this, &shooter, &vis](std::size_t begin, std::size_t end, std::vector<Link>& out) {
                    for (std::size_t k = begin; k < end; ++k)
                        link_missed_polygon(shooter, vis, std::uint32_t(k), out);
                }};
    }

    void link_missed_polygon(const Shooter& shooter, const gpu::HemicubeVisibility& vis,
                             std::uint32_t p, std::vector<Link>& links) const {
        if (polygon_seen_[p] == stamp_ || p == shooter.address.polygon) return;
        if (hidden_ && std::binary_search(hidden_->begin(), hidden_->end(), p)) return;
        const Polygon& poly = scene_->polygons[p];
        const dvec3& centre = centre_[p];
        if (glm::dot(poly.normal, centre - shooter.geometry.centre) >= 0)
            return; // faces away from the shooter
        if (!centre_seen(shooter, vis, p)) return;
        const double f = near_mean(shooter, {p, 0, 0}, poly.area,
                                   float(analytic_at(shooter, centre, poly.normal)));
        if (f <= 0) return;
        Link l;
        l.receiver = {p, 0, 0};
        l.ff = l.ff_analytic = float(f);
        links.push_back(l);
    }

    // Is the centre of polygon p, which no pixel shows, seen from the shooter's eye? Not if
    // the hemicube taken as a depth map hides it (HemicubeVisibility::visible_in_depth_map),
    // nor if the segment to it crosses a polygon (a ray cast). The depth map alone passed a
    // centre whose pixel shows nothing, or its own twin, while things smaller than a pixel
    // hide it: in the office glb, the LED bars' first shots linked faces inside a closed tea
    // container on a shelf 6 m away (reflectance 0.985), which then lit its inside. A point
    // cluster's eye stands among its polygons, which its hemicubes leave out (hidden_), and
    // which a ray from it would cross: the depth map alone decides there. (A flat cluster's
    // eye lies in the plane of its polygons, which a ray into its front does not cross.)
    bool centre_seen(const Shooter& shooter, const gpu::HemicubeVisibility& vis,
                     std::uint32_t p) const {
        if (!vis.visible_in_depth_map(centre_[p], p)) return false;
        if (hidden_ && point_) return true;
        return !bvh_->occluded(shooter.geometry.centre, centre_[p], shooter.address.polygon, p);
    }

    // Adds the link of node a: analytic F(j->S), and the pixel sum as A_S F(S->j).
    void add_link(const Shooter& shooter, const PatchAddress& a, float analytic, double pixel_power,
                  std::vector<Link>& links) const {
        const double area_j = area(a.polygon, a.level, a.index);
        // A node seen across a patch shooter's plane, its centre behind it (a wall that meets
        // the end of a gap the shooter faces): the shader's kernel there integrates over the
        // shooter's back, where its pixels show the part in front.
        if (!point_ &&
            !before_shooter(shooter, patch_centre(scene_->polygons[a.polygon], a.level, a.index)))
            analytic = float(pixel_power / area_j);
        analytic = near_mean(shooter, a, area_j, analytic);
        Link l;
        l.receiver = a;
        l.ff_analytic = analytic;
        // Reciprocity: F(j->S) = F(S->j) A_S / A_j.
        l.ff_pixel = float(pixel_power / area_j);
        switch (mode_) {
        case Mode::Hemicube:
            l.ff = l.ff_pixel;
            break;
        case Mode::Analytic:
            l.ff = l.ff_analytic;
            break;
        case Mode::Hybrid: {
            const bool tri = scene_->polygons[a.polygon].is_triangle();
            for (std::uint32_t nb : patch_neighbours(tri, a.level, a.index)) {
                if (nb == UINT32_MAX) continue;
                if (occluded(shooter, a.polygon, a.level, nb)) {
                    l.partial = true;
                    break;
                }
            }
            l.ff = l.partial ? std::min(l.ff_pixel, l.ff_analytic) : l.ff_analytic;
            // A point shot's kernel I cos / r^2 at the centre of a node near the point (one
            // that covers many pixels) says nothing of the node's average, and grows without
            // bound as r shrinks: there the flux through its pixels is the measure.
            if (point_ && pixels_seen(a) >= kNearPixels) l.ff = l.ff_pixel;
            break;
        }
        }
        if (l.ff > 0) links.push_back(l);
    }

    // Links the parts of seen node a that no seen descendant covers, at the level of a's
    // children: their analytic value is computed here (double precision, same formula as the
    // shader), visibility taken from a; a's pixels are shared among them in proportion to
    // their analytic A_j F(j->S).
    void split(const Shooter& shooter, const PatchAddress& a, double pixel_power,
               std::vector<Link>& links) const {
        std::vector<PatchAddress> fillers;
        collect_fillers(a, fillers);
        if (fillers.empty()) return;
        const Polygon& poly = scene_->polygons[a.polygon];
        std::vector<double> values;
        values.reserve(fillers.size());
        double total = 0;
        for (const PatchAddress& c : fillers) {
            const PatchGeometry g = patch_geometry(poly, c.level, c.index);
            const double f = analytic_at(shooter, g.centre, poly.normal);
            values.push_back(f);
            total += f * g.area;
        }
        for (std::size_t k = 0; k < fillers.size(); ++k) {
            const PatchAddress& c = fillers[k];
            const double share =
                total > 0 ? values[k] * area(c.polygon, c.level, c.index) / total : 0;
            if (mode_ == Mode::Hybrid)
                link_visible_parts(shooter, c, float(values[k]), pixel_power * share, true, links);
            else
                add_link(shooter, c, float(values[k]), pixel_power * share, links);
        }
    }

    void collect_fillers(const PatchAddress& a, std::vector<PatchAddress>& fillers) const {
        const bool tri = scene_->polygons[a.polygon].is_triangle();
        for (std::uint32_t c : patch_children(tri, a.level, a.index)) {
            const PatchAddress ca{a.polygon, a.level + 1, c};
            const std::uint64_t id = node_id(ca.polygon, ca.level, ca.index);
            if (seen_[id] == stamp_) continue; // linked on its own
            if (below_seen_[id] == stamp_)
                collect_fillers(ca, fillers); // partly linked below
            else
                fillers.push_back(ca);
        }
    }

    Mode mode_;
    std::string name_;
    const Scene* scene_;
    Discretisation disc_;
    GpuProviderOptions options_;
    /// A provider that owns its context makes it current before it draws: several solvers,
    /// each with its own, may step in turn on one thread (the Python module's).
    void bind() {
        if (context_) context_->make_current();
    }

    std::unique_ptr<gl::Context> context_;
    std::unique_ptr<Bvh> bvh_; ///< the scene's polygons: centre_seen(), share_seen()
    std::unique_ptr<gpu::HemicubeRenderer> renderer_;
    std::deque<gpu::HemicubeLayout> layouts_; // deque: references stay valid as it grows
    std::vector<std::uint64_t> base_;
    std::vector<float> pixels_, pixel_sum_, analytic_;
    std::unique_ptr<std::atomic<float>[]> area_; ///< per node, its area (area()), -1 until used
    std::vector<std::uint32_t> pixel_count_;     ///< per node seen, its pixels in this shot
    std::vector<float> probe_pixels_;            ///< probe_view()'s coarse hemicube
    double probe_seconds_ = 0;                   ///< probe_view()s since the last shot's timings
    std::vector<float> pixels_back_;             ///< a point shot's hemicube against the aim
    const Sphere* point_ = nullptr;              ///< during shoot_sphere(): the point shot
    /// During a shot's linking: the visibility of its hemicubes (against and along the axis;
    /// a patch shot has one, in both) and a point shot's centre and axis (0: a patch shot).
    const gpu::HemicubeVisibility* vis_[2] = {nullptr, nullptr};
    dvec3 sphere_centre_{0.0}, sphere_axis_{0.0};
    std::vector<std::uint32_t> partial_; ///< per node, stamp_: a silhouette crosses it
    std::array<std::vector<std::size_t>, 5> edge_pixels_; ///< mark_partial: per face
    std::vector<float> ids_;                              ///< pixels_'s IDs (fill_cracks)
    struct Receiver {
        dvec3 centre{0.0};
        double area = 0;
        float share = 0; ///< of the cluster's intensity (ClusterShooter::share_in_front)
        float seen = 1;  ///< of that, what its brightest polygons see of it (share_seen)
    };
    std::vector<Receiver> receivers_; ///< shoot_cluster(): per link
    std::vector<float> flux_;         ///< shoot_sphere(): per pixel, its flux (-1: no front)
    std::array<std::vector<float>, 2> sphere_ids_; ///< the same for a point's two sides
    std::vector<dvec3> centre_;                    ///< per polygon, its level-0 centre
    std::vector<double> radius_;  ///< per polygon, its farthest corner from centre_ [unit]
    std::vector<double> longest_; ///< per polygon, its longest edge [unit]
    const std::vector<std::uint32_t>* hidden_ = nullptr; ///< during shoot_cluster(): members
    double near_fraction_ = 0;
    bool point_shot_ = false; ///< the last shot was shoot_sphere()'s
    std::vector<std::uint32_t> seen_, below_seen_, polygon_seen_;
    std::vector<PatchAddress> touched_;
    std::vector<std::vector<Link>> chunk_links_; ///< link_in_chunks(): per chunk
    std::vector<Timing> timings_;
    std::uint32_t stamp_ = 0;
    double max_power_ = 0;
    double backface_ = 0;
    double shooter_radius_ = 0; ///< a patch shot's: its farthest corner from its centre [unit]
    double plane_eps_ = 0;      ///< in a plane: within this distance of it [scene units]
    double diagonal_ = 0;       ///< the scene's bounding box diagonal [scene units]
    const gpu::HemicubeLayout* last_layout_ = nullptr; ///< of the last shoot() (in layouts_)
    Shooter last_shooter_;
    int last_width_ = 0, last_height_ = 0; ///< layout of pixels_ (last_hemicube())
};

} // namespace

std::unique_ptr<FormFactorProvider> make_hemicube_provider(const std::string& mode,
                                                           const Scene& scene,
                                                           const Discretisation& disc,
                                                           const GpuProviderOptions& options) {
    const Mode m = mode == "hemicube"   ? Mode::Hemicube
                   : mode == "analytic" ? Mode::Analytic
                                        : Mode::Hybrid;
    return std::make_unique<HemicubeProvider>(m, mode, scene, disc, options);
}

} // namespace hemirad
