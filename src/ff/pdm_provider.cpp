// "pdm" provider: paper 000's Parametric Differential Method (§4): Gauss-Legendre quadrature
// of the form-factor integral (paper 000, eq. 3) over both patches, with one visibility ray per
// pair of nodes:
//   F(j->S) = 1/A_j  sum_a sum_b  W_a W_b  cos(th_j) cos(th_S) / (pi r^2)  V(x_a, y_b),
// x_a, W_a the nodes and weights (parametric Jacobian included) on the receiver node j,
// y_b, W_b those on the shooter patch S.
#include <cmath>
#include <numbers>

#include "ff/cpu_linking.h"

namespace hemirad::cpu {

namespace {

struct Node {
    dvec3 point;
    double weight; // area weight [unit^2]; the weights of a patch sum to its area
};

// order^2 product Gauss-Legendre nodes on a patch (bilinear quad, or triangle by the
// collapsed map of patch_point).
void gauss_nodes(const PatchGeometry& g, const std::vector<double>& x, const std::vector<double>& w,
                 std::vector<Node>& out) {
    out.clear();
    for (std::size_t j = 0; j < x.size(); ++j)
        for (std::size_t i = 0; i < x.size(); ++i) {
            double jac;
            const dvec3 p = patch_point(g, x[i], x[j], jac);
            out.push_back({p, w[i] * w[j] * jac});
        }
}

class PdmProvider final : public CpuProvider {
  public:
    PdmProvider(const Scene& scene, const Discretisation& disc, const CpuProviderOptions& o,
                std::shared_ptr<const Bvh> bvh)
        : CpuProvider(scene, disc, o, std::move(bvh)) {
        gauss_legendre01(o.gauss_order, x_, w_);
    }
    std::string name() const override { return "pdm"; }

    void shoot(const Shooter& shooter, std::vector<Link>& links) override {
        const auto start = SteadyClock::now();
        begin_shot(shooter, links);
        std::vector<Node> shooter_nodes;
        gauss_nodes(shooter.geometry, x_, w_, shooter_nodes);
        for_each_polygon(
            scene_.polygons.size(), threads_,
            [&](std::uint32_t r, std::vector<Link>& out) {
                receive(shooter, shooter_nodes, r, out);
            },
            links);
        timings_ = {{"form_factors", seconds_since(start)}};
    }

  private:
    void receive(const Shooter& s, const std::vector<Node>& ys, std::uint32_t r,
                 std::vector<Link>& out) const {
        const std::vector<ReceiverNode> nodes = linked_nodes(s, r);
        const Polygon& poly = scene_.polygons[r];
        std::vector<Node> xs;
        for (const ReceiverNode& node : nodes) {
            gauss_nodes(node.geometry, x_, w_, xs);
            const double offset = 1e-7 * std::sqrt(node.geometry.area);
            double sum = 0, sum_unoccluded = 0;
            for (const Node& xa : xs) {
                const dvec3 origin = xa.point + poly.normal * offset;
                for (const Node& yb : ys) {
                    const dvec3 d = yb.point - xa.point;
                    const double r2 = glm::dot(d, d);
                    const double cj = glm::dot(poly.normal, d), cs = -glm::dot(s.normal, d);
                    if (!(cj > 0 && cs > 0 && r2 > 0)) continue;
                    // cos_j cos_S / (pi r^2) = (n_j.d)(-n_S.d) / (pi r^4)
                    const double k = xa.weight * yb.weight * cj * cs / (r2 * r2);
                    sum_unoccluded += k;
                    if (!bvh_->occluded(origin, yb.point, r, s.address.polygon)) sum += k;
                }
            }
            const double scale = 1.0 / (std::numbers::pi * node.geometry.area);
            const double f = std::min(1.0, sum * scale);
            if (!(f > 0)) continue;
            Link link;
            link.receiver = node.address;
            link.ff = float(f);
            link.ff_analytic = float(point_to_polygon_ff(
                node.geometry.centre, poly.normal, s.geometry.corners.data(), s.geometry.count));
            link.partial = sum < sum_unoccluded;
            if (!(link.ff > 0)) continue;
            out.push_back(link);
        }
    }

    std::vector<double> x_, w_; // Gauss-Legendre nodes and weights on [0,1]
};

} // namespace

std::unique_ptr<FormFactorProvider> make_pdm_provider(const Scene& scene,
                                                      const Discretisation& disc,
                                                      const CpuProviderOptions& o,
                                                      std::shared_ptr<const Bvh> bvh) {
    return std::make_unique<PdmProvider>(scene, disc, o, std::move(bvh));
}

} // namespace hemirad::cpu
