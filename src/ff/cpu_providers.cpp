// CPU form-factor providers: the factory and the linking code they share (cpu_linking.h).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "core/parallel.h"
#include "ff/cpu_linking.h"
#include "hemirad/error.h"
#include "hemirad/solver.h"
#include "hemirad/solver_options.h"

namespace hemirad {

namespace cpu {

bool may_receive(const Polygon& r, const Shooter& s) {
    // Tolerance relative to the sizes involved [scene units].
    const double scale = std::sqrt(r.area) + std::sqrt(s.geometry.area);
    const double eps = 1e-12 * scale;
    const dvec3& sc = s.geometry.centre;
    bool in_front_of_shooter = false;
    for (int k = 0; k < r.count; ++k)
        if (glm::dot(s.normal, r.v[k] - sc) > eps) in_front_of_shooter = true;
    if (!in_front_of_shooter) return false;
    for (int k = 0; k < s.geometry.count; ++k)
        if (glm::dot(r.normal, s.geometry.corners[k] - r.v[0]) > eps) return true;
    return false;
}

void receiver_nodes(const Polygon& p, std::uint32_t polygon, int depth, bool leaves,
                    double link_angle, const Shooter& shooter, std::vector<ReceiverNode>& out) {
    out.clear();
    if (leaves) {
        const std::uint32_t n = std::uint32_t(1) << (2 * depth);
        out.reserve(n);
        for (std::uint32_t i = 0; i < n; ++i)
            out.push_back(
                {{polygon, std::uint32_t(depth), i}, patch_geometry(p, std::uint32_t(depth), i)});
        return;
    }
    // Depth-first, children in patch_children order: deterministic.
    struct Item {
        std::uint32_t level, index;
    };
    std::vector<Item> stack{{0, 0}};
    while (!stack.empty()) {
        const Item it = stack.back();
        stack.pop_back();
        const PatchGeometry g = patch_geometry(p, it.level, it.index);
        const double dist = glm::length(g.centre - shooter.geometry.centre);
        const double size = std::sqrt(g.area);
        if (int(it.level) < depth && !(size <= link_angle * dist)) {
            const auto ch = patch_children(p.is_triangle(), it.level, it.index);
            for (int k = 3; k >= 0; --k) stack.push_back({it.level + 1, ch[k]});
            continue;
        }
        out.push_back({{polygon, it.level, it.index}, g});
    }
}

void for_each_polygon(std::size_t count, int threads,
                      const std::function<void(std::uint32_t, std::vector<Link>&)>& fn,
                      std::vector<Link>& links) {
    std::vector<std::vector<Link>> per(count);
    parallel_for(count, threads, [&](std::size_t i) { fn(std::uint32_t(i), per[i]); });
    std::size_t total = 0;
    for (const auto& v : per) total += v.size();
    links.reserve(links.size() + total);
    for (const auto& v : per) links.insert(links.end(), v.begin(), v.end());
}

void gauss_legendre01(int order, std::vector<double>& nodes, std::vector<double>& weights) {
    HEMIRAD_CHECK(order >= 1 && order <= 32);
    nodes.assign(order, 0.0);
    weights.assign(order, 0.0);
    // Roots of P_n by Newton from the Chebyshev-like guess; weights 2/((1-x^2) P_n'(x)^2) on
    // [-1,1], mapped to [0,1] (x -> (x+1)/2, w -> w/2).
    const int n = order;
    for (int i = 0; i < n; ++i) {
        double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
        double dp = 1;
        for (int it = 0; it < 100; ++it) {
            double p0 = 1, p1 = x;
            for (int k = 2; k <= n; ++k) {
                const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (x * p1 - p0) / (x * x - 1);
            const double dx = p1 / dp;
            x -= dx;
            if (std::abs(dx) < 1e-16) break;
        }
        {
            double p0 = 1, p1 = x;
            for (int k = 2; k <= n; ++k) {
                const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (x * p1 - p0) / (x * x - 1);
        }
        nodes[n - 1 - i] = 0.5 * (x + 1);
        weights[n - 1 - i] = 1.0 / ((1 - x * x) * dp * dp);
    }
}

dvec3 patch_point(const PatchGeometry& g, double s, double t, double& jacobian) {
    const auto& c = g.corners;
    if (g.count == 3) {
        const dvec3 e1 = c[1] - c[0], e2 = c[2] - c[0];
        jacobian = glm::length(glm::cross(e1, e2)) * (1 - s);
        return c[0] + s * e1 + (1 - s) * t * e2;
    }
    const dvec3 du = (1 - t) * (c[1] - c[0]) + t * (c[2] - c[3]);
    const dvec3 dv = (1 - s) * (c[3] - c[0]) + s * (c[2] - c[1]);
    jacobian = glm::length(glm::cross(du, dv));
    return (1 - s) * (1 - t) * c[0] + s * (1 - t) * c[1] + s * t * c[2] + (1 - s) * t * c[3];
}

std::uint64_t mix64(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

CpuProvider::CpuProvider(const Scene& scene, const Discretisation& disc,
                         const CpuProviderOptions& o, std::shared_ptr<const Bvh> bvh)
    : scene_(scene), disc_(disc), options_(o), bvh_(std::move(bvh)) {
    if (disc_.depth.size() != scene.polygons.size()) {
        std::ostringstream m;
        m << "discretisation has " << disc_.depth.size() << " depths for " << scene.polygons.size()
          << " polygons";
        throw InputError(m.str());
    }
    for (std::uint8_t& d : disc_.depth) d = std::min<std::uint8_t>(d, kMaxDepth);
    threads_ = int(std::min(thread_count(0), 2u)); // at most 2: the CPU providers' own limit
}

void CpuProvider::begin_shot(const Shooter& s, std::vector<Link>& links) const {
    links.clear();
    if (s.address.polygon >= scene_.polygons.size() || s.address.level > kMaxDepth ||
        !patch_valid(s.address.level, s.address.index)) {
        std::ostringstream m;
        m << "shooter address (" << s.address.polygon << ", " << s.address.level << ", "
          << s.address.index << ") is not a patch of the scene";
        throw InputError(m.str());
    }
}

void CpuProvider::shoot_point(const Luminaire& l, std::vector<Link>& links) {
    const auto start = SteadyClock::now();
    links.clear();
    const double power = l.power();
    if (!(power > 0)) return;
    Shooter at; // only its centre is used by the linking
    at.geometry.centre = l.position;
    for_each_polygon(
        scene_.polygons.size(), threads_,
        [&](std::uint32_t r, std::vector<Link>& out) {
            const Polygon& poly = scene_.polygons[r];
            if (!(glm::dot(poly.normal, l.position - poly.v[0]) > 0)) return; // faces away
            std::vector<ReceiverNode> nodes;
            receiver_nodes(poly, r, depth_of(r), link_at_leaves_, options_.link_angle, at, nodes);
            for (const ReceiverNode& node : nodes) {
                const dvec3& x = node.geometry.centre;
                const double e = l.irradiance(x, poly.normal) / power;
                if (!(e > 0)) continue;
                const dvec3 origin = x + poly.normal * (1e-7 * std::sqrt(node.geometry.area));
                if (bvh_->occluded(origin, l.position, r, kNoPolygon)) continue;
                Link link;
                link.receiver = node.address;
                link.ff = link.ff_analytic = float(e);
                if (link.ff > 0) out.push_back(link);
            }
        },
        links);
    timings_ = {{"form_factors", seconds_since(start)}};
}

} // namespace cpu

std::unique_ptr<FormFactorProvider> make_cpu_provider(const std::string& name, const Scene& scene,
                                                      const Discretisation& disc,
                                                      const CpuProviderOptions& o) {
    SolverOptions ranges; // the ranges are the options table's (solver_options.h)
    ranges.provider.cpu = o;
    validate_solver_options(ranges, SolverOption::Check::Cpu);
    if (name != "reference" && name != "pdm" && name != "sr")
        throw InputError("unknown form-factor method '" + name +
                         "' (expected reference, pdm or sr)");
    auto bvh = std::make_shared<const Bvh>(scene);
    if (name == "reference") return cpu::make_reference_provider(scene, disc, o, bvh);
    if (name == "pdm") return cpu::make_pdm_provider(scene, disc, o, bvh);
    return cpu::make_sr_provider(scene, disc, o, bvh);
}

} // namespace hemirad
