// Shared machinery of the CPU form-factor providers (reference, pdm, sr): choosing the
// receiving nodes, culling, a deterministic two-thread loop over polygons, sampling helpers.
// Internal header.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "core/timer.h"
#include "ff/bvh.h"
#include "hemirad/form_factors.h"

namespace hemirad::cpu {

/// A receiving node and its geometry.
struct ReceiverNode {
    PatchAddress address;
    PatchGeometry geometry;
};

/// False when polygon `r` cannot receive from the shooter: it lies entirely behind the
/// shooter's plane, or the whole shooter lies behind r's plane (r faces away).
bool may_receive(const Polygon& r, const Shooter& shooter);

/// The receiving nodes of polygon `polygon`:
///  - leaves: every patch of level `depth`;
///  - adaptive: from the root, refine a node while sqrt(area) / |centre - shooter centre|
///    > link_angle and its level < depth (paper 002's "about one hemicube pixel per patch").
void receiver_nodes(const Polygon& p, std::uint32_t polygon, int depth, bool leaves,
                    double link_angle, const Shooter& shooter, std::vector<ReceiverNode>& out);

/// Calls fn(polygon, links_of_that_polygon) for every polygon on up to `threads` threads and
/// appends the per-polygon results to `links` in polygon order: the output does not depend on
/// the number of threads.
void for_each_polygon(std::size_t count, int threads,
                      const std::function<void(std::uint32_t, std::vector<Link>&)>& fn,
                      std::vector<Link>& links);

/// Gauss-Legendre nodes and weights on [0,1] (weights sum to 1), order 1..32.
void gauss_legendre01(int order, std::vector<double>& nodes, std::vector<double>& weights);

/// A point of a patch from unit-square coordinates (s,t) and the Jacobian |dP/ds x dP/dt|
/// (area element): bilinear for quads; for triangles the collapsed (Duffy) map
/// (s,t) -> corner0 + s (c1-c0) + (1-s) t (c2-c0), Jacobian 2A(1-s).
dvec3 patch_point(const PatchGeometry& g, double s, double t, double& jacobian);

/// Deterministic hash mixing (splitmix64 finaliser).
std::uint64_t mix64(std::uint64_t x);

/// Base of the CPU providers: scene, discretisation, options, a BVH shared by all, timings.
class CpuProvider : public FormFactorProvider {
  public:
    CpuProvider(const Scene& scene, const Discretisation& disc, const CpuProviderOptions& o,
                std::shared_ptr<const Bvh> bvh);
    std::vector<Timing> last_timings() const override { return timings_; }
    /// A point shot, the same for every CPU provider: adaptive (or leaf) linking as for a
    /// shooter at the luminaire's position, over every polygon whose front faces it; per node
    /// the analytic E_j / P at its centre (form_factors.h) if one ray from the centre to the
    /// luminaire arrives, else nothing.
    void shoot_point(const Luminaire& luminaire, std::vector<Link>& links) override;

  protected:
    /// Checks the shooter, clears `links`; throws InputError for a bad address.
    void begin_shot(const Shooter& shooter, std::vector<Link>& links) const;
    int depth_of(std::uint32_t polygon) const { return disc_.depth[polygon]; }
    /// The receiving nodes of polygon r for this shot (leaves or adaptive linking); empty
    /// when r is the shooter's polygon or cannot receive from it.
    std::vector<ReceiverNode> linked_nodes(const Shooter& s, std::uint32_t r) const {
        std::vector<ReceiverNode> nodes;
        const Polygon& poly = scene_.polygons[r];
        if (r == s.address.polygon || !may_receive(poly, s)) return nodes;
        receiver_nodes(poly, r, depth_of(r), link_at_leaves_, options_.link_angle, s, nodes);
        return nodes;
    }

    const Scene& scene_;
    Discretisation disc_;
    CpuProviderOptions options_;
    std::shared_ptr<const Bvh> bvh_;
    int threads_ = 1;
    std::vector<Timing> timings_;
};

std::unique_ptr<FormFactorProvider> make_reference_provider(const Scene&, const Discretisation&,
                                                            const CpuProviderOptions&,
                                                            std::shared_ptr<const Bvh>);
std::unique_ptr<FormFactorProvider> make_pdm_provider(const Scene&, const Discretisation&,
                                                      const CpuProviderOptions&,
                                                      std::shared_ptr<const Bvh>);
std::unique_ptr<FormFactorProvider> make_sr_provider(const Scene&, const Discretisation&,
                                                     const CpuProviderOptions&,
                                                     std::shared_ptr<const Bvh>);

} // namespace hemirad::cpu
