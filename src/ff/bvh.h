// Bounding-volume hierarchy over a scene's polygons for the CPU form-factor providers:
// segment visibility (reference, pdm) and nearest-hit ray casting (sr). Internal header.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "hemirad/scene.h"

namespace hemirad {

constexpr std::uint32_t kNoPolygon = std::numeric_limits<std::uint32_t>::max();

/// A ray's nearest hit.
struct Hit {
    std::uint32_t polygon = kNoPolygon;
    double t = 0;        ///< ray parameter: point = origin + t*dir
    double u = 0, v = 0; ///< parameters of the hit point in the polygon (patch.h), in [0,1]
    bool front = false;  ///< the ray arrived on the polygon's front (normal) side
};

/// Binned-SAH BVH (12 bins per axis, leaves of at most 4 polygons) in double precision.
/// Polygons are hit from both sides, but for the two polygons of a two-sided surface
/// (Polygon::twin), each hit from its front only: the other is hit there instead. Read-only after
/// construction: safe to share between threads.
class Bvh {
  public:
    explicit Bvh(const Scene& scene);

    /// Is the open segment from -> to blocked by a polygon other than ignore_a, ignore_b?
    /// The first and last 1e-7 of the segment's length are not tested, so that polygons
    /// touching its end points (neighbours sharing an edge) do not count.
    bool occluded(const dvec3& from, const dvec3& to, std::uint32_t ignore_a,
                  std::uint32_t ignore_b) const;

    /// Nearest hit with t in (1e-9 |dir|-relative, tmax), skipping polygon `ignore` (the
    /// polygon the ray starts on). `dir` need not be normalised.
    bool intersect(const dvec3& origin, const dvec3& dir, double tmax, Hit& hit,
                   std::uint32_t ignore = kNoPolygon) const;

    std::size_t node_count() const { return nodes_.size(); }

  private:
    struct Node {
        dvec3 lo, hi;
        std::uint32_t first = 0; ///< leaf: first primitive in order_; inner: right child
        std::uint32_t count = 0; ///< primitives in a leaf; 0 for an inner node (left = this+1)
    };
    struct Prim {
        dvec3 v0, e1, e2, e3; ///< v0 and edges v1-v0, v2-v0, v3-v0 (e3 unused for triangles)
        dvec3 normal;
        int count = 3;
        bool twinned = false; ///< one side of a two-sided surface (Polygon::twin)
    };

    std::uint32_t build(std::uint32_t begin, std::uint32_t end, std::vector<dvec3>& lo,
                        std::vector<dvec3>& hi, std::vector<dvec3>& centroid);
    // Ray/polygon: returns t in (tmin, tmax) or a negative value; (u,v) of the hit.
    bool hit_prim(const Prim& p, const dvec3& o, const dvec3& d, double tmin, double tmax,
                  double& t, double& u, double& v) const;
    template <class Visit>
    void traverse(const dvec3& o, const dvec3& d, double tmin, double& tmax, Visit visit) const;

    std::vector<Node> nodes_;
    std::vector<Prim> prims_;
    std::vector<std::uint32_t> order_; ///< leaf ranges index into this: polygon ids
};

/// The same without the clamp: outside the quad, the root nearest to it (for point location).
void inverse_bilinear_unclamped(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& d,
                                const dvec3& normal, const dvec3& p, double& u, double& v);

/// Inverse of the bilinear map of a planar quad, P(u,v) = (1-u)(1-v)a + u(1-v)b + uv c +
/// (1-u)v d: the (u,v) of point `p` (assumed in the quad's plane), clamped to [0,1]^2.
void inverse_bilinear(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& d,
                      const dvec3& normal, const dvec3& p, double& u, double& v);

} // namespace hemirad
