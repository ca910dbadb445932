// "reference" provider: analytic point-to-polygon form factor at each receiving node's centre
// (the value paper 002's fragment program computes, in double precision) times a ray-cast
// visibility fraction.
#include <cmath>

#include "ff/cpu_linking.h"

namespace hemirad::cpu {

namespace {

struct Sample {
    dvec3 point;
    double weight; // area weight of the sample's cell (sums to the patch area)
};

// k*k stratified points on the shooter patch at cell centres of the unit square. Quads: the
// bilinear map, weight = Jacobian/k^2. Triangles: cells with s+t > 1 are folded onto the
// mirrored cell (s,t) -> (1-s,1-t), so each cell strictly below the diagonal is cast once with
// weight 2, each cell on it (s+t = 1 at its centre) once with weight 1.
std::vector<Sample> shooter_samples(const PatchGeometry& g, int k) {
    std::vector<Sample> out;
    const double h = 1.0 / k;
    for (int j = 0; j < k; ++j)
        for (int i = 0; i < k; ++i) {
            const double s = (i + 0.5) * h, t = (j + 0.5) * h;
            if (g.count == 4) {
                double jac;
                const dvec3 p = patch_point(g, s, t, jac);
                out.push_back({p, jac * h * h});
            } else if (i + j <= k - 1) {
                const dvec3 p = g.corners[0] + s * (g.corners[1] - g.corners[0]) +
                                t * (g.corners[2] - g.corners[0]);
                out.push_back({p, (i + j < k - 1 ? 2.0 : 1.0) * g.area * h * h});
            }
        }
    return out;
}

class ReferenceProvider final : public CpuProvider {
  public:
    using CpuProvider::CpuProvider;
    std::string name() const override { return "reference"; }

    void shoot(const Shooter& shooter, std::vector<Link>& links) override {
        const auto start = SteadyClock::now();
        begin_shot(shooter, links);
        const std::vector<Sample> samples =
            shooter_samples(shooter.geometry, options_.visibility_samples);
        for_each_polygon(
            scene_.polygons.size(), threads_,
            [&](std::uint32_t r, std::vector<Link>& out) { receive(shooter, samples, r, out); },
            links);
        timings_ = {{"form_factors", seconds_since(start)}};
    }

  private:
    void receive(const Shooter& s, const std::vector<Sample>& samples, std::uint32_t r,
                 std::vector<Link>& out) const {
        const std::vector<ReceiverNode> nodes = linked_nodes(s, r);
        const Polygon& poly = scene_.polygons[r];
        for (const ReceiverNode& node : nodes) {
            const dvec3& x = node.geometry.centre;
            const double fa =
                point_to_polygon_ff(x, poly.normal, s.geometry.corners.data(), s.geometry.count);
            if (!(fa > 0)) continue;
            // Visibility fraction weighted by the unoccluded kernel cos_j cos_S / r^2 of each
            // sample, so that samples the receiver cannot see (behind its tangent plane) or
            // that see it at grazing angles count for what they contribute to F.
            const dvec3 origin = x + poly.normal * (1e-7 * std::sqrt(node.geometry.area));
            double w_all = 0, w_visible = 0;
            for (const Sample& smp : samples) {
                const dvec3 d = smp.point - x;
                const double r2 = glm::dot(d, d);
                const double cj = glm::dot(poly.normal, d), cs = -glm::dot(s.normal, d);
                if (!(cj > 0 && cs > 0 && r2 > 0)) continue;
                const double w = smp.weight * cj * cs / (r2 * r2);
                w_all += w;
                if (!bvh_->occluded(origin, smp.point, r, s.address.polygon)) w_visible += w;
            }
            const double fraction = w_all > 0 ? w_visible / w_all : 1.0;
            const double f = fa * fraction;
            if (!(f > 0)) continue;
            Link link;
            link.receiver = node.address;
            link.ff = float(f);
            link.ff_analytic = float(fa);
            link.partial = fraction > 0 && fraction < 1;
            if (!(link.ff > 0)) continue; // underflow to 0 in float
            out.push_back(link);
        }
    }
};

} // namespace

std::unique_ptr<FormFactorProvider> make_reference_provider(const Scene& scene,
                                                            const Discretisation& disc,
                                                            const CpuProviderOptions& o,
                                                            std::shared_ptr<const Bvh> bvh) {
    return std::make_unique<ReferenceProvider>(scene, disc, o, std::move(bvh));
}

} // namespace hemirad::cpu
