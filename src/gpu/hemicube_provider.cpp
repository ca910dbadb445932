// The GPU form-factor provider (paper 002): hemicube visibility with the mipmapped patch-ID
// linking oracle, analytic form factors from the fragment shader, and the hybrid treatment
// of partially occluded patches (§3.2). Modes:
//   hemicube  classic pixel counting (Cohen & Greenberg 1985) at the mipmap linking
//   analytic  the analytic value at every visible node (binary visibility)
//   hybrid    analytic, except nodes with a fully occluded neighbour: pixel sum clamped to
//             the analytic value
#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>

#include "core/timer.h"
#include "gpu/hemicube.h"
#include "hemirad/error.h"
#include "hemirad/gl/context.h"
#include "hemirad/provider.h"

namespace hemirad {

namespace {

using Clock = SteadyClock;             // core/timer.h
constexpr auto since = &seconds_since; // [s]

enum class Mode { Hemicube, Analytic, Hybrid };

/// The polygon of a luminaire's stand-in shooter: none (the renderer skips no polygon).
constexpr std::uint32_t kNoShooterPolygon = 0xFFFFFFFFu;

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
        analytic_.assign(total, 0.f);
        seen_.assign(total, 0);
        polygon_seen_.assign(scene.polygons.size(), 0);
        below_seen_.assign(total, 0);
        area_.assign(total, -1.f);
    }

    std::string name() const override { return name_; }
    std::vector<Timing> last_timings() const override { return timings_; }
    double last_backface_fraction() const override { return backface_; }
    double last_parallax_fraction() const override {
        if (!last_layout_) return 0;
        return gpu::parallax_fraction(*scene_, last_shooter_, *last_layout_, pixels_.data());
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
        links.clear();
        timings_.clear();
        ++stamp_;
        const gpu::HemicubeLayout& layout = layout_for(shooter);
        auto t0 = Clock::now();
        const int angle = options_.atan_angle ? 2 : options_.builtin_acos ? 1 : 0;
        renderer_->render(shooter, layout, options_.lod_bias, angle);
        timings_.push_back({"cull", renderer_->cull_seconds()});
        timings_.push_back({"render", since(t0) - renderer_->cull_seconds()});
        t0 = Clock::now();
        renderer_->read_back(layout, pixels_);
        last_width_ = layout.width;
        last_height_ = layout.height;
        last_layout_ = &layout;
        last_shooter_ = shooter;
        timings_.push_back({"readback", since(t0)});
        t0 = Clock::now();
        reduce(shooter, layout, links);
        timings_.push_back({"reduce", since(t0)});
    }

    // A luminaire shoots from its position over the whole sphere: two hemicubes, along the
    // nadir (+aim) and against it, each from a stand-in shooter (a small square centred on the
    // luminaire, of no polygon, so that every polygon is drawn). Their patch IDs give the
    // linking and the visibility, as for a polygon shooter; the values are computed here: the
    // analytic I(d) cos(theta_j) / (683 r^2) at each node's centre, and the flux through the
    // node's pixels, sum I(u) omega / 683 (omega = the pixel's solid angle).
    void shoot_point(const Luminaire& luminaire, std::vector<Link>& links) override {
        links.clear();
        timings_.clear();
        const double power = luminaire.power();
        if (!(power > 0)) return;
        ++stamp_;
        point_ = &luminaire;
        point_power_ = power;
        const gpu::HemicubeLayout& layout =
            layout_of(options_.resolution ? options_.resolution : options_.max_resolution);
        const int angle = options_.atan_angle ? 2 : options_.builtin_acos ? 1 : 0;
        const Shooter sides[2] = {point_shooter(luminaire, -1.0), point_shooter(luminaire, 1.0)};
        std::vector<float>* buffers[2] = {&pixels_back_, &pixels_};
        touched_.clear();
        double t_render = 0, t_read = 0, t_reduce = 0;
        for (int k = 0; k < 2; ++k) {
            auto t0 = Clock::now();
            renderer_->render(sides[k], layout, options_.lod_bias, angle);
            t_render += since(t0);
            t0 = Clock::now();
            renderer_->read_back(layout, *buffers[k]);
            t_read += since(t0);
            t0 = Clock::now();
            const gpu::HemicubeFrame frame = gpu::hemicube_frame(sides[k]);
            const double d2 = 4.0 / (double(layout.res) * layout.res); // pixel area at 1
            const std::vector<float>& px = *buffers[k];
            for (int f = 0; f < 5; ++f) {
                const gpu::HemicubeLayout::Face& face = layout.faces[f];
                for (int j = 0; j < face.h; ++j)
                    for (int i = 0; i < face.w; ++i) {
                        const std::size_t at = std::size_t(face.y + j) * layout.width + face.x + i;
                        if (px[4 * at + 2] < 0.5f) continue; // nothing, or a back
                        const dvec3 u = gpu::hemicube_direction(layout, frame, f, i, j);
                        const double c = glm::dot(u, frame.dir[f]);
                        const double omega = d2 * c * c * c; // solid angle of the pixel
                        scan_pixel(
                            px.data(), at,
                            float(luminaire.intensity(u) * omega / (kLumensPerWatt * power)));
                    }
            }
            t_reduce += since(t0);
        }
        auto t0 = Clock::now();
        // The analytic value of every seen node, at its centre.
        for (const PatchAddress& a : touched_) {
            const PatchGeometry g = patch_geometry(scene_->polygons[a.polygon], a.level, a.index);
            analytic_[node_id(a.polygon, a.level, a.index)] =
                float(analytic_at(sides[0], g.centre, scene_->polygons[a.polygon].normal));
        }
        backface_ = 0;
        last_width_ = layout.width;
        last_height_ = layout.height;
        last_layout_ = &layout;
        last_shooter_ = sides[1];
        link_touched(sides[0], 1.0, links);
        if (mode_ != Mode::Hemicube)
            for (int k = 0; k < 2; ++k) link_missed_polygons(sides[k], layout, *buffers[k], links);
        t_reduce += since(t0);
        point_ = nullptr;
        timings_.push_back({"render", t_render});
        timings_.push_back({"readback", t_read});
        timings_.push_back({"reduce", t_reduce});
    }

  private:
    const gpu::HemicubeLayout& layout_for(const Shooter& shooter) {
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
        return layout_of(res);
    }

    const gpu::HemicubeLayout& layout_of(int res) {
        auto it = std::find_if(layouts_.begin(), layouts_.end(),
                               [res](const gpu::HemicubeLayout& l) { return l.res == res; });
        if (it != layouts_.end()) return *it;
        layouts_.push_back(gpu::make_hemicube_layout(res));
        return layouts_.back();
    }

    // The stand-in shooter of a luminaire's hemicube along side * aim: a square of side 1 %
    // of the scene's diagonal centred on the luminaire (its size sets only the near plane; its
    // first edge, the frame), of no polygon, with a corner count of 0 so that the fragment
    // shader computes no polygon form factor (its loop over the shooter's corners is empty).
    Shooter point_shooter(const Luminaire& l, double side) const {
        Shooter s;
        s.address = {kNoShooterPolygon, 0, 0};
        s.normal = side * l.aim;
        const double h = 0.005 * std::max(scene_->bounds().diagonal(), 1e-300);
        const dvec3 a = h * l.c0, b = h * glm::cross(s.normal, l.c0);
        s.geometry.count = 0;
        s.geometry.corners = {l.position - a - b, l.position + a - b, l.position + a + b,
                              l.position - a + b};
        s.geometry.centre = l.position;
        s.geometry.area = 4 * h * h;
        return s;
    }

    // F(dA_j -> S) of the polygon shooter, or for a point shot E_j / P (see shoot_point), at
    // a receiver centre with normal n, unoccluded.
    double analytic_at(const Shooter& s, const dvec3& centre, const dvec3& n) const {
        if (point_) return point_->irradiance(centre, n) / point_power_;
        return point_to_polygon_ff(centre, n, s.geometry.corners.data(), s.geometry.count);
    }

    std::uint64_t node_id(std::uint32_t p, std::uint32_t level, std::uint32_t index) const {
        return base_[p] + level_offset(int(level)) + index;
    }

    float area(std::uint32_t p, std::uint32_t level, std::uint32_t index) {
        float& a = area_[node_id(p, level, index)];
        if (a < 0) a = float(patch_geometry(scene_->polygons[p], level, index).area);
        return a;
    }

    // Fully occluded: in front of the shooter, yet neither it, nor an ancestor, nor a
    // descendant was seen on the hemicube.
    bool occluded(const Shooter& s, std::uint32_t p, std::uint32_t level, std::uint32_t index) {
        const std::uint64_t id = node_id(p, level, index);
        if (seen_[id] == stamp_ || below_seen_[id] == stamp_) return false;
        const bool tri = scene_->polygons[p].is_triangle();
        std::uint32_t l = level, i = index;
        while (l > 0) {
            i = patch_parent(tri, l, i);
            --l;
            if (seen_[node_id(p, l, i)] == stamp_) return false;
        }
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
        double backface = 0;
        const std::size_t n = std::size_t(layout.width) * layout.height;
        for (std::size_t i = 0; i < n; ++i) {
            const float b = pixels_[4 * i + 2];
            if (b < 0.5f) {
                if (b < -0.5f) backface += layout.delta_ff[i];
                continue;
            }
            scan_pixel(pixels_.data(), i, layout.delta_ff[i]);
        }
        backface_ = backface;
        link_touched(shooter, shooter.geometry.area, links);
        if (mode_ != Mode::Hemicube) link_missed_polygons(shooter, layout, pixels_, links);
    }

    // Pixel `i` of `rgba` shows a front (B > 0): marks its node seen (taking its analytic
    // value from alpha the first time) and adds `weight` to the node's pixel sum.
    void scan_pixel(const float* rgba, std::size_t i, float weight) {
        const float* px = &rgba[4 * i];
        const auto p = std::uint32_t(px[2]) - 1;
        polygon_seen_[p] = stamp_;
        const auto level = std::uint32_t(px[1]);
        const auto index = std::uint32_t(px[0]);
        const std::uint64_t id = node_id(p, level, index);
        if (seen_[id] != stamp_) {
            seen_[id] = stamp_;
            pixel_sum_[id] = 0;
            analytic_[id] = px[3];
            touched_.push_back({p, level, index});
        }
        pixel_sum_[id] += weight;
    }

    // Links every node seen in this shot. pixel_scale turns a node's pixel sum into the
    // pixel value's numerator: A_S for a polygon shooter (A_S F(S->j)), 1 for a point shot.
    void link_touched(const Shooter& shooter, double pixel_scale, std::vector<Link>& links) {
        // Mark the ancestors of every seen node: "something below was seen".
        for (const PatchAddress& a : touched_) {
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
        links.reserve(touched_.size());
        for (const PatchAddress& a : touched_) {
            const std::uint64_t id = node_id(a.polygon, a.level, a.index);
            if (below_seen_[id] == stamp_) {
                // The oracle picks a level per fragment, so where GL's LOD crosses a level a
                // node and some of its descendants are both seen. Linking both would deliver
                // light twice to the descendants' area; the finer links win, and the rest of
                // this node is linked by "filler" children that were not seen themselves.
                split(shooter, a, double(pixel_sum_[id]) * pixel_scale, links);
                continue;
            }
            add_link(shooter, a, analytic_[id], double(pixel_sum_[id]) * pixel_scale, links);
        }
    }

    // A polygon smaller than a pixel can fall between pixel centres and get no pixel at all
    // (the oracle can coarsen within a polygon, not below one): its light would be lost,
    // and the rows of closed scenes of many small polygons would sum under 1. For every
    // polygon in front of the shooter that no pixel shows, look at the pixel its centre
    // falls in: if the surface there is farther away (or there is none), the polygon is
    // visible and is linked whole, with its analytic value computed here.
    // (A point shot calls this once per hemicube, each with its own pixels: a polygon's centre
    // lies on one side of the luminaire.)
    void link_missed_polygons(const Shooter& shooter, const gpu::HemicubeLayout& layout,
                              const std::vector<float>& pixels, std::vector<Link>& links) {
        const gpu::HemicubeFrame frame = gpu::hemicube_frame(shooter);
        const dvec3& eye = shooter.geometry.centre;
        for (std::uint32_t p = 0; p < scene_->polygons.size(); ++p) {
            if (polygon_seen_[p] == stamp_ || p == shooter.address.polygon) continue;
            const Polygon& poly = scene_->polygons[p];
            const dvec3 centre = patch_geometry(poly, 0, 0).centre;
            const dvec3 d = centre - eye;
            if (glm::dot(poly.normal, d) >= 0) continue; // faces away from the shooter
            const long pixel = gpu::hemicube_pixel(layout, frame, d);
            if (pixel < 0) continue; // below the shooter's plane
            const float id = pixels[4 * std::size_t(pixel) + 2];
            if (id > 0.5f || id < -0.5f) {
                const Polygon& q = scene_->polygons[std::uint32_t(std::abs(id)) - 1];
                const double along = glm::dot(d, q.normal);
                if (along != 0) {
                    const double t = glm::dot(q.v[0] - eye, q.normal) / along; // in units of d
                    if (t < 1 - 1e-6) continue; // something nearer covers it: occluded
                }
            }
            const double f = analytic_at(shooter, centre, poly.normal);
            if (f <= 0) continue;
            Link l;
            l.receiver = {p, 0, 0};
            l.ff = l.ff_analytic = float(f);
            links.push_back(l);
        }
    }

    // Adds the link of node a: analytic F(j->S), and the pixel sum as A_S F(S->j).
    void add_link(const Shooter& shooter, const PatchAddress& a, float analytic, double pixel_power,
                  std::vector<Link>& links) {
        const double area_j = area(a.polygon, a.level, a.index);
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
               std::vector<Link>& links) {
        fillers_.clear();
        collect_fillers(a);
        if (fillers_.empty()) return;
        const Polygon& poly = scene_->polygons[a.polygon];
        filler_values_.clear();
        double total = 0;
        for (const PatchAddress& c : fillers_) {
            const PatchGeometry g = patch_geometry(poly, c.level, c.index);
            const double f = analytic_at(shooter, g.centre, poly.normal);
            filler_values_.push_back(f);
            total += f * g.area;
        }
        for (std::size_t k = 0; k < fillers_.size(); ++k) {
            const PatchAddress& c = fillers_[k];
            const double share =
                total > 0 ? filler_values_[k] * area(c.polygon, c.level, c.index) / total : 0;
            add_link(shooter, c, float(filler_values_[k]), pixel_power * share, links);
        }
    }

    void collect_fillers(const PatchAddress& a) {
        const bool tri = scene_->polygons[a.polygon].is_triangle();
        for (std::uint32_t c : patch_children(tri, a.level, a.index)) {
            const PatchAddress ca{a.polygon, a.level + 1, c};
            const std::uint64_t id = node_id(ca.polygon, ca.level, ca.index);
            if (seen_[id] == stamp_) continue; // linked on its own
            if (below_seen_[id] == stamp_)
                collect_fillers(ca); // partly linked below
            else
                fillers_.push_back(ca);
        }
    }

    Mode mode_;
    std::string name_;
    const Scene* scene_;
    Discretisation disc_;
    GpuProviderOptions options_;
    std::unique_ptr<gl::Context> context_;
    std::unique_ptr<gpu::HemicubeRenderer> renderer_;
    std::deque<gpu::HemicubeLayout> layouts_; // deque: references stay valid as it grows
    std::vector<std::uint64_t> base_;
    std::vector<float> pixels_, pixel_sum_, analytic_, area_;
    std::vector<float> pixels_back_;   ///< a point shot's hemicube against the aim
    const Luminaire* point_ = nullptr; ///< during shoot_point(): the luminaire
    double point_power_ = 0;           ///< its power per channel [W]
    std::vector<std::uint32_t> seen_, below_seen_, polygon_seen_;
    std::vector<PatchAddress> touched_, fillers_;
    std::vector<double> filler_values_;
    std::vector<Timing> timings_;
    std::uint32_t stamp_ = 0;
    double max_power_ = 0;
    double backface_ = 0;
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
