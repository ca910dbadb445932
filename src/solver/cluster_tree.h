// Clusters of polygons for shooting (Smits, Arvo & Greenberg 1994, "A clustering algorithm
// for radiosity in complex environments"; Sillion 1995, "A unified hierarchical algorithm for
// global illumination with scattering volumes and object clusters"): a binary tree over the
// scene's polygons, built by splitting them at the median of their centroids along the
// longest axis, so that every node holds a compact group of nearby polygons. The solver keeps
// each node's unshot power (the sum of its polygons') and shoots a whole node at once when
// its power is spread over many small polygons, as one point source at the node's centre
// whose intensity is the sum of its polygons' cosine lobes (FormFactorProvider::
// shoot_cluster). Internal header.
#pragma once

#include <cstdint>
#include <vector>

#include "hemirad/form_factors.h"
#include "hemirad/scene.h"

namespace hemirad {

class Bvh;

class ClusterTree {
  public:
    struct Node {
        dvec3 lo{1e300}, hi{-1e300}; ///< bounds of the polygons' corners [unit]
        std::uint32_t begin = 0;     ///< first polygon in order()
        std::uint32_t end = 0;       ///< one past the last
        std::uint32_t left = 0;      ///< children (0: a leaf, holding one polygon)
        std::uint32_t right = 0;
        double area = 0; ///< of its polygons [unit^2]
        bool leaf() const { return left == 0; }
        std::uint32_t size() const { return end - begin; }
        dvec3 centre() const { return 0.5 * (lo + hi); }
        double radius() const { return 0.5 * glm::length(hi - lo); }
    };

    /// The tree of every polygon of `scene` (none for an empty scene). Node 0 is the root;
    /// children follow their parent, so a pass from the last node to the first visits
    /// children before parents. Deterministic.
    explicit ClusterTree(const Scene& scene);

    const std::vector<Node>& nodes() const { return nodes_; }
    const Node& node(std::uint32_t i) const { return nodes_[i]; }
    /// Polygon ids, each node's polygons contiguous: order()[begin .. end).
    const std::vector<std::uint32_t>& order() const { return order_; }
    /// The leaf node of each polygon.
    std::uint32_t leaf_of(std::uint32_t polygon) const { return leaf_[polygon]; }
    /// The parent of each node (the root's is itself).
    std::uint32_t parent(std::uint32_t node) const { return parent_[node]; }

  private:
    std::uint32_t build(std::uint32_t begin, std::uint32_t end, std::uint32_t parent,
                        const std::vector<dvec3>& centroid);

    const Scene* scene_;
    double normal_scale_ = 0; ///< [unit]: normals count as positions this far apart
    std::vector<Node> nodes_;
    std::vector<std::uint32_t> order_, leaf_, parent_;
};

/// Whether point p lies in a gap narrower than max_gap between two of `polygons` (roughly
/// parallel, on either side of p, each covering p's foot on its plane): inside a wall slab or
/// a thin panel whose two faces are both among them. A cluster's centre there sees the inner
/// faces of the slab, which none of its polygons can light.
bool in_thin_gap(const Scene& scene, const std::vector<std::uint32_t>& polygons, const dvec3& p,
                 double max_gap);

/// Whether the light of `polygons` leaves from away from `centre`: the centroid of their
/// centroids, weighted by `power` (one value each, >= 0), lies farther than `max_offset` from
/// it. A cluster shooting from `centre` would send that light from where it does not leave.
/// False when every power is 0.
bool light_off_centre(const Scene& scene, const std::vector<std::uint32_t>& polygons,
                      const std::vector<double>& power, const dvec3& centre, double max_offset);

/// For each of `polygons`, the share of its points that do not see `centre`: of its centroid
/// and the points halfway from it to each corner, lifted by `lift` off its front, those whose
/// segment to the centre `bvh` finds blocked. A cluster shooting from there would send that
/// polygon's light where it sends none (from inside a wall slab, through the side of a shelf).
/// (A centre behind a polygon's plane counts as seen: a box's centre is behind all its faces,
/// and refusing those clusters as well tripled the office's shots.) Judges the polygons of most
/// `power` (one value each, >= 0), up to 256 of them or 99 % of the power; the rest (and those
/// without power) get 0.
std::vector<double> light_hidden_from_centre(const Scene& scene, const Bvh& bvh,
                                             const std::vector<std::uint32_t>& polygons,
                                             const std::vector<double>& power, const dvec3& centre,
                                             double lift);

/// A point cluster's sources (ClusterShooter::sources): of `polygons`, the kMaxSources of most
/// `power` (one value each, >= 0; those without power are left out), brightest first, each
/// with its share of `total`, and marked hidden_from_centre where `centre` lies behind its
/// plane (in it included) or a segment from one of its points (as light_hidden_from_centre
/// takes them, lifted by `lift`) to the centre is blocked. Every source is judged.
std::vector<ClusterShooter::Source> cluster_sources(const Scene& scene, const Bvh& bvh,
                                                    const std::vector<std::uint32_t>& polygons,
                                                    const std::vector<double>& power, double total,
                                                    const dvec3& centre, double lift);

} // namespace hemirad
