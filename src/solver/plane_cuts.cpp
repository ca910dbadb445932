// Polygons whose plane cuts a shooter (plane_cuts.h).
#include "solver/plane_cuts.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace hemirad {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Distance from point p to the box [lo, hi] (0 inside).
double box_distance(const dvec3& p, const dvec3& lo, const dvec3& hi) {
    const dvec3 d = glm::max(glm::max(lo - p, p - hi), dvec3(0.0));
    return glm::length(d);
}

// Distance between two boxes (0 when they overlap).
double box_box_distance(const dvec3& alo, const dvec3& ahi, const dvec3& blo, const dvec3& bhi) {
    const dvec3 d = glm::max(glm::max(alo - bhi, blo - ahi), dvec3(0.0));
    return glm::length(d);
}

} // namespace

PlaneCuts::PlaneCuts(const Scene& scene, double reach)
    : scene_(&scene), reach_(reach), eps_(1e-6 * std::max(scene.bounds().diagonal(), 1e-300)) {
    const std::size_t n = scene.polygons.size();
    planes_.resize(n);
    lo_.assign(n, dvec3(1e300));
    hi_.assign(n, dvec3(-1e300));
    for (std::size_t p = 0; p < n; ++p) {
        const Polygon& poly = scene.polygons[p];
        planes_[p] = {poly.normal, glm::dot(poly.normal, poly.v[0])};
        for (int k = 0; k < poly.count; ++k) {
            lo_[p] = glm::min(lo_[p], poly.v[k]);
            hi_[p] = glm::max(hi_[p], poly.v[k]);
        }
    }
    // A uniform grid over the polygons' bounds finds the candidates near each polygon.
    const Bounds b = scene.bounds();
    const double cell = std::max(b.diagonal() / 64.0, 1e-300);
    const dvec3 top = glm::floor((b.hi - b.lo) / cell);
    const auto cell_of = [&](const dvec3& x) {
        const dvec3 c = glm::floor((x - b.lo) / cell);
        return glm::ivec3(glm::clamp(c, dvec3(0.0), top));
    };
    const auto key = [](const glm::ivec3& c) {
        return (std::uint64_t(c.x) << 42) | (std::uint64_t(c.y) << 21) | std::uint64_t(c.z);
    };
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid;
    for (std::uint32_t p = 0; p < n; ++p) {
        const glm::ivec3 a = cell_of(lo_[p]), z = cell_of(hi_[p]);
        for (int x = a.x; x <= z.x; ++x)
            for (int y = a.y; y <= z.y; ++y)
                for (int w = a.z; w <= z.z; ++w) grid[key({x, y, w})].push_back(p);
    }
    std::vector<std::uint32_t> stamp(n, 0xFFFFFFFFu);
    first_.assign(n + 1, 0);
    for (std::uint32_t p = 0; p < n; ++p) {
        first_[p] = std::uint32_t(cutters_.size());
        const Polygon& P = scene.polygons[p];
        const double r = reach_ * std::sqrt(P.area);
        const glm::ivec3 a = cell_of(lo_[p] - dvec3(r)), z = cell_of(hi_[p] + dvec3(r));
        const auto consider = [&](std::uint32_t q) {
            if (q == p || q == P.twin || stamp[q] == p) return;
            stamp[q] = p;
            if (box_box_distance(lo_[p], hi_[p], lo_[q], hi_[q]) > r) return;
            const Polygon& Q = scene.polygons[q];
            // Q partly in front of P.
            double front = -1e300;
            for (int k = 0; k < Q.count; ++k)
                front = std::max(front, glm::dot(planes_[p].n, Q.v[k]) - planes_[p].d);
            if (front <= eps_) return;
            // Q's plane separates P's corners.
            double smin = 1e300, smax = -1e300;
            for (int k = 0; k < P.count; ++k) {
                const double s = glm::dot(planes_[q].n, P.v[k]) - planes_[q].d;
                smin = std::min(smin, s), smax = std::max(smax, s);
            }
            if (smin < -eps_ && smax > eps_) cutters_.push_back(q);
        };
        const long cells = long(z.x - a.x + 1) * long(z.y - a.y + 1) * long(z.z - a.z + 1);
        if (cells > long(n)) { // a polygon about as large as the scene: look at every other
            for (std::uint32_t q = 0; q < n; ++q) consider(q);
            continue;
        }
        for (int x = a.x; x <= z.x; ++x)
            for (int y = a.y; y <= z.y; ++y)
                for (int w = a.z; w <= z.z; ++w) {
                    const auto it = grid.find(key({x, y, w}));
                    if (it == grid.end()) continue;
                    for (std::uint32_t q : it->second) consider(q);
                }
    }
    first_[n] = std::uint32_t(cutters_.size());
}

double PlaneCuts::cut_share(std::uint32_t polygon, const PatchGeometry& node) const {
    const double r = reach_ * std::sqrt(node.area);
    double share = 0;
    for (std::uint32_t k = first_[polygon]; k < first_[polygon + 1]; ++k) {
        const std::uint32_t q = cutters_[k];
        if (box_distance(node.centre, lo_[q], hi_[q]) > r) continue;
        double smin = 1e300, smax = -1e300;
        for (int c = 0; c < node.count; ++c) {
            const double s = glm::dot(planes_[q].n, node.corners[c]) - planes_[q].d;
            smin = std::min(smin, s), smax = std::max(smax, s);
        }
        if (!(smin < -eps_ && smax > eps_)) continue;
        const Polygon& Q = scene_->polygons[q];
        const dvec3 d = Q.centroid() - node.centre;
        share = std::max(share, std::min(1.0, Q.area / (kPi * std::max(glm::dot(d, d), 1e-300))));
    }
    return share;
}

std::size_t PlaneCuts::polygons_cut() const {
    std::size_t count = 0;
    for (std::size_t p = 0; p + 1 < first_.size(); ++p) count += first_[p + 1] > first_[p];
    return count;
}

} // namespace hemirad
