// The shooting clusters' tree (cluster_tree.h): median splits of polygon centroids.
#include "solver/cluster_tree.h"

#include <algorithm>
#include <numeric>
#include <utility>

#include "ff/bvh.h"

namespace hemirad {

ClusterTree::ClusterTree(const Scene& scene) : scene_(&scene) {
    const std::size_t n = scene.polygons.size();
    if (n == 0) return;
    order_.resize(n);
    std::iota(order_.begin(), order_.end(), 0u);
    leaf_.assign(n, 0);
    std::vector<dvec3> centroid(n);
    for (std::size_t i = 0; i < n; ++i) centroid[i] = scene.polygons[i].centroid();
    // Orientation counts as position, so that a small cluster holds polygons facing alike
    // (both faces of a slab, or a floor and the ceiling under it, split apart early): the
    // normal scaled by an eighth of the scene's size is a further three coordinates.
    normal_scale_ = scene.bounds().diagonal() / 8;
    nodes_.reserve(2 * n - 1);
    parent_.reserve(2 * n - 1);
    build(0, std::uint32_t(n), 0, centroid);
}

std::uint32_t ClusterTree::build(std::uint32_t begin, std::uint32_t end, std::uint32_t parent,
                                 const std::vector<dvec3>& centroid) {
    const auto id = std::uint32_t(nodes_.size());
    nodes_.emplace_back();
    parent_.push_back(parent);
    Node node;
    node.begin = begin;
    node.end = end;
    dvec3 clo(1e300), chi(-1e300), nlo(1e300), nhi(-1e300);
    for (std::uint32_t k = begin; k < end; ++k) {
        const Polygon& p = scene_->polygons[order_[k]];
        for (int c = 0; c < p.count; ++c) {
            node.lo = glm::min(node.lo, p.v[c]);
            node.hi = glm::max(node.hi, p.v[c]);
        }
        node.area += p.area;
        clo = glm::min(clo, centroid[order_[k]]);
        chi = glm::max(chi, centroid[order_[k]]);
        nlo = glm::min(nlo, p.normal * normal_scale_);
        nhi = glm::max(nhi, p.normal * normal_scale_);
    }
    if (end - begin == 1) {
        leaf_[order_[begin]] = id;
        nodes_[id] = node;
        return id;
    }
    // Split at the median centroid along the longest axis of the centroids' bounds; ties
    // broken by polygon id, so the tree does not depend on the sort's implementation.
    const double e[6] = {chi.x - clo.x, chi.y - clo.y, chi.z - clo.z,
                         nhi.x - nlo.x, nhi.y - nlo.y, nhi.z - nlo.z};
    const int axis = int(std::max_element(e, e + 6) - e);
    const auto key = [&](std::uint32_t p) {
        return axis < 3 ? centroid[p][axis] : scene_->polygons[p].normal[axis - 3];
    };
    const std::uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                     [&](std::uint32_t a, std::uint32_t b) {
                         const double ca = key(a), cb = key(b);
                         return ca != cb ? ca < cb : a < b;
                     });
    node.left = build(begin, mid, id, centroid);
    node.right = build(mid, end, id, centroid);
    nodes_[id] = node;
    return id;
}

namespace {

// Whether p's foot on the plane of convex polygon `poly` lies inside it.
bool covers(const Polygon& poly, const dvec3& p) {
    for (int k = 0; k < poly.count; ++k) {
        const dvec3& a = poly.v[k];
        const dvec3& b = poly.v[(k + 1) % poly.count];
        if (glm::dot(glm::cross(b - a, p - a), poly.normal) < 0) return false;
    }
    return true;
}

} // namespace

bool in_thin_gap(const Scene& scene, const std::vector<std::uint32_t>& polygons, const dvec3& p,
                 double max_gap) {
    // The polygons near p that cover it: their normals and p's signed distances.
    std::vector<std::pair<dvec3, double>> near;
    for (std::uint32_t i : polygons) {
        const Polygon& poly = scene.polygons[i];
        const double s = glm::dot(poly.normal, p - poly.v[0]);
        if (std::abs(s) >= max_gap || !(std::abs(s) > 1e-9 * max_gap) || !covers(poly, p)) continue;
        for (const auto& [n, t] : near) {
            const double c = glm::dot(n, poly.normal);
            // Parallel within about 25 degrees, and p between the two planes.
            if (std::abs(c) > 0.9 && s * t * c < 0 && std::abs(s) + std::abs(t) < max_gap)
                return true;
        }
        near.emplace_back(poly.normal, s);
    }
    return false;
}

bool light_off_centre(const Scene& scene, const std::vector<std::uint32_t>& polygons,
                      const std::vector<double>& power, const dvec3& centre, double max_offset) {
    dvec3 sum(0.0);
    double weight = 0;
    for (std::size_t k = 0; k < polygons.size() && k < power.size(); ++k) {
        if (!(power[k] > 0)) continue;
        sum += power[k] * scene.polygons[polygons[k]].centroid();
        weight += power[k];
    }
    return weight > 0 && glm::length(sum / weight - centre) > max_offset;
}

std::vector<double> light_hidden_from_centre(const Scene& scene, const Bvh& bvh,
                                             const std::vector<std::uint32_t>& polygons,
                                             const std::vector<double>& power, const dvec3& centre,
                                             double lift) {
    std::vector<double> hidden(polygons.size(), 0.0);
    std::vector<std::size_t> by_power;
    double total = 0;
    for (std::size_t k = 0; k < polygons.size() && k < power.size(); ++k)
        if (power[k] > 0) by_power.push_back(k), total += power[k];
    std::sort(by_power.begin(), by_power.end(),
              [&](std::size_t a, std::size_t b) { return power[a] > power[b]; });
    constexpr std::size_t kMaxJudged = 256;
    double judged = 0;
    for (std::size_t i = 0; i < by_power.size() && i < kMaxJudged && judged < 0.99 * total; ++i) {
        const std::size_t k = by_power[i];
        const Polygon& poly = scene.polygons[polygons[k]];
        const dvec3 c = poly.centroid();
        int blocked = 0;
        for (int q = -1; q < poly.count; ++q) {
            const dvec3 s = (q < 0 ? c : 0.5 * (c + poly.v[q])) + lift * poly.normal;
            if (bvh.occluded(s, centre, polygons[k], poly.twin)) ++blocked;
        }
        judged += power[k];
        hidden[k] = blocked / double(poly.count + 1);
    }
    return hidden;
}

std::vector<ClusterShooter::Source> cluster_sources(const Scene& scene, const Bvh& bvh,
                                                    const std::vector<std::uint32_t>& polygons,
                                                    const std::vector<double>& power, double total,
                                                    const dvec3& centre, double lift) {
    std::vector<ClusterShooter::Source> sources;
    for (std::size_t i = 0; i < polygons.size() && i < power.size(); ++i)
        if (power[i] > 0) sources.push_back({polygons[i], power[i] / total});
    const std::size_t n = std::min(sources.size(), ClusterShooter::kMaxSources);
    std::partial_sort(sources.begin(), sources.begin() + std::ptrdiff_t(n), sources.end(),
                      [](const auto& a, const auto& b) { return a.share > b.share; });
    sources.resize(n);
    // Equal weights, so that light_hidden_from_centre judges every one of them.
    std::vector<std::uint32_t> ids;
    for (const ClusterShooter::Source& s : sources) ids.push_back(s.polygon);
    const std::vector<double> hidden =
        light_hidden_from_centre(scene, bvh, ids, std::vector<double>(n, 1.0), centre, lift);
    for (std::size_t k = 0; k < n; ++k) {
        const Polygon& poly = scene.polygons[sources[k].polygon];
        sources[k].hidden_from_centre =
            hidden[k] > 0 || glm::dot(poly.normal, centre - poly.centroid()) <= 0;
    }
    return sources;
}

} // namespace hemirad
