#include "solver/bright_leaves.h"

#include <algorithm>

#include "core/sampling.h"
#include "hemirad/patch.h"

namespace hemirad {

namespace {

double reflected(const Hierarchy& h, const PatchAddress& a) {
    const dvec3 B = h.reflectance(a) * h.irradiance(a);
    return B.x + B.y + B.z;
}

} // namespace

BrightLeaves::BrightLeaves(const Hierarchy& h, double factor, std::size_t max_leaves) : h_(&h) {
    if (!(factor > 0) || max_leaves == 0) return;
    const Scene& scene = h.scene();
    double power = 0, area = 0;
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p) {
        const auto level = std::uint32_t(h.depth(p));
        const std::uint32_t n = 1u << (2 * level);
        for (std::uint32_t i = 0; i < n; ++i) {
            const PatchAddress a{p, level, i};
            const double A = double(h.node(a).area);
            power += reflected(h, a) * A;
            area += A;
        }
    }
    if (!(power > 0 && area > 0)) return;
    const double threshold = factor * power / area;
    struct Candidate {
        double B;
        Leaf leaf;
    };
    std::vector<Candidate> bright;
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p) {
        const auto level = std::uint32_t(h.depth(p));
        const std::uint32_t n = 1u << (2 * level);
        for (std::uint32_t i = 0; i < n; ++i) {
            const double B = reflected(h, {p, level, i});
            if (B > threshold)
                bright.push_back({B, {p, i, patch_area(scene.polygons[p], level, i)}});
        }
    }
    if (bright.size() > max_leaves) {
        std::nth_element(bright.begin(), bright.begin() + std::ptrdiff_t(max_leaves), bright.end(),
                         [](const Candidate& a, const Candidate& b) { return a.B > b.B; });
        bright.resize(max_leaves);
    }
    double total = 0;
    for (const Candidate& c : bright)
        if (c.leaf.area > 0) total += c.B * c.leaf.area;
    if (!(total > 0)) return;
    double running = 0;
    for (const Candidate& c : bright) {
        if (!(c.leaf.area > 0)) continue;
        const double p = c.B * c.leaf.area / total;
        running += p;
        by_node_.emplace(
            h.node_id({c.leaf.polygon, std::uint32_t(h.depth(c.leaf.polygon)), c.leaf.index}),
            std::uint32_t(leaves_.size()));
        leaves_.push_back(c.leaf);
        prob_.push_back(p);
        cdf_.push_back(running);
    }
    cdf_.back() = 1.0;
}

BrightLeaves::Sample BrightLeaves::sample(double pick, double u1, double u2, double u3) const {
    const auto k = std::size_t(std::upper_bound(cdf_.begin(), cdf_.end(), pick) - cdf_.begin());
    const Leaf& leaf = leaves_[std::min(k, leaves_.size() - 1)];
    const Polygon& P = h_->scene().polygons[leaf.polygon];
    const PatchGeometry g = patch_geometry(P, std::uint32_t(h_->depth(leaf.polygon)), leaf.index);
    Sample s;
    s.point = area_point(g.corners.data(), g.count, u1, u2, u3);
    s.polygon = leaf.polygon;
    s.density = prob_[std::min(k, leaves_.size() - 1)] / leaf.area;
    return s;
}

double BrightLeaves::density(std::uint32_t polygon, double u, double v) const {
    if (leaves_.empty()) return 0;
    const auto level = std::uint32_t(h_->depth(polygon));
    const Polygon& P = h_->scene().polygons[polygon];
    const auto it = by_node_.find(h_->node_id({polygon, level, patch_at(P, level, u, v)}));
    if (it == by_node_.end()) return 0;
    return prob_[it->second] / leaves_[it->second].area;
}

} // namespace hemirad
