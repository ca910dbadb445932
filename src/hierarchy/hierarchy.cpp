// Quadtree patch hierarchy with lazy push-pull (paper 002 §4.1; Hanrahan et al. 1991).
#include "hemirad/hierarchy.h"

#include <algorithm>
#include <cmath>

#include "hemirad/error.h"

namespace hemirad {

Discretisation discretise(const Scene& scene, const HierarchyOptions& options) {
    if (options.max_depth < 0 || options.max_depth > kMaxDepth)
        throw InputError("--max-depth " + std::to_string(options.max_depth) + " must be in 0.." +
                         std::to_string(kMaxDepth));
    if (options.patch_size < 0 || !std::isfinite(options.patch_size))
        throw InputError("--patch-size " + num(options.patch_size) +
                         " must be positive (or 0 for automatic)");
    const double size =
        options.patch_size > 0 ? options.patch_size : scene.bounds().diagonal() / 64.0;
    Discretisation d;
    d.depth.reserve(scene.polygons.size());
    for (const Polygon& p : scene.polygons) {
        double longest = 0;
        for (int i = 0; i < p.count; ++i)
            longest = std::max(longest, glm::length(p.v[(i + 1) % p.count] - p.v[i]));
        int depth = 0;
        while (depth < options.max_depth && longest / double(1 << depth) > size) ++depth;
        d.depth.push_back(std::uint8_t(depth));
    }
    return d;
}

Hierarchy::Hierarchy(const Scene& scene, const Discretisation& disc) : scene_(&scene), disc_(disc) {
    HEMIRAD_CHECK_EQ(disc.depth.size(), scene.polygons.size());
    const std::size_t np = scene.polygons.size();
    base_.resize(np);
    std::uint64_t total = 0;
    for (std::size_t p = 0; p < np; ++p) {
        base_[p] = total;
        total += tree_size(disc.depth[p]);
        leaves_ += std::uint64_t(1) << (2 * disc.depth[p]);
    }
    nodes_.resize(total);
    unshot_.assign(np, dvec3(0.0));
    dirty_.assign(np, 0);
    for (std::size_t p = 0; p < np; ++p) {
        const Polygon& poly = scene.polygons[p];
        const glm::vec3 Be(scene.material_of(poly).exitance());
        for (int level = 0; level <= disc.depth[p]; ++level) {
            const std::uint32_t n = 1u << (2 * level);
            for (std::uint32_t i = 0; i < n; ++i) {
                Node& node = nodes_[base_[p] + level_offset(level) + i];
                node.area = float(patch_geometry(poly, level, i).area);
                node.dB = Be;
            }
        }
        unshot_[p] = dvec3(Be) * poly.area;
    }
    // Textured polygons: each leaf's reflectance is the texture's mean over it; nodes above
    // hold the area-weighted means of their children.
    for (std::uint32_t p = 0; p < np; ++p) {
        if (!scene.texture_of(p)) continue;
        if (rho_base_.empty()) rho_base_.assign(np, kUntextured);
        rho_base_[p] = rho_.size();
        const int depth = disc.depth[p];
        rho_.resize(rho_.size() + tree_size(depth));
        glm::vec3* rho = rho_.data() + rho_base_[p];
        const Node* tree = nodes_.data() + base_[p];
        const std::uint32_t nl = 1u << (2 * depth);
        for (std::uint32_t i = 0; i < nl; ++i)
            rho[level_offset(depth) + i] = glm::vec3(patch_reflectance(scene, p, depth, i));
        const bool tri = scene.polygons[p].is_triangle();
        for (int level = depth - 1; level >= 0; --level)
            for (std::uint32_t i = 0; i < (1u << (2 * level)); ++i) {
                glm::dvec3 sum(0.0);
                for (std::uint32_t c : patch_children(tri, level, i))
                    sum += glm::dvec3(rho[level_offset(level + 1) + c]) *
                           double(tree[level_offset(level + 1) + c].area);
                rho[level_offset(level) + i] =
                    glm::vec3(sum / double(tree[level_offset(level) + i].area));
            }
    }
}

void Hierarchy::receive(const PatchAddress& a, const dvec3& irradiance) {
    Node& n = node(a);
    n.dI += glm::vec3(irradiance);
    unshot_[a.polygon] += reflectance(a) * irradiance * double(n.area);
    dirty_[a.polygon] = 1;
}

void Hierarchy::push_pull(std::uint32_t p) {
    const int depth = disc_.depth[p];
    const bool tri = scene_->polygons[p].is_triangle();
    const glm::vec3 rho(scene_->material_of(scene_->polygons[p]).rho);
    Node* tree = nodes_.data() + base_[p];
    // Push: every node hands its dI to its four children, level by level.
    for (int level = 0; level < depth; ++level) {
        const std::uint32_t n = 1u << (2 * level);
        Node* row = tree + level_offset(level);
        Node* next = tree + level_offset(level + 1);
        for (std::uint32_t i = 0; i < n; ++i) {
            if (row[i].dI == glm::vec3(0.f)) continue;
            for (std::uint32_t c : patch_children(tri, level, i)) next[c].dI += row[i].dI;
            row[i].dI = glm::vec3(0.f);
        }
    }
    Node* leaves = tree + level_offset(depth);
    const std::uint32_t nl = 1u << (2 * depth);
    const glm::vec3* leaf_rho = rho_base_.empty() || rho_base_[p] == kUntextured
                                    ? nullptr
                                    : rho_.data() + rho_base_[p] + level_offset(depth);
    for (std::uint32_t i = 0; i < nl; ++i) {
        Node& l = leaves[i];
        l.H += l.dI;
        l.dB += (leaf_rho ? leaf_rho[i] : rho) * l.dI;
        l.dI = glm::vec3(0.f);
    }
    // Pull: area-weighted averages from the leaves up to the root.
    for (int level = depth - 1; level >= 0; --level) {
        const std::uint32_t n = 1u << (2 * level);
        Node* row = tree + level_offset(level);
        Node* next = tree + level_offset(level + 1);
        for (std::uint32_t i = 0; i < n; ++i) {
            glm::vec3 H(0.f), dB(0.f);
            for (std::uint32_t c : patch_children(tri, level, i)) {
                H += next[c].H * next[c].area;
                dB += next[c].dB * next[c].area;
            }
            row[i].H = H / row[i].area;
            row[i].dB = dB / row[i].area;
        }
    }
    unshot_[p] = dvec3(tree[0].dB) * double(tree[0].area);
    dirty_[p] = 0;
}

void Hierarchy::push_pull_all() {
    for (std::uint32_t p = 0; p < scene_->polygons.size(); ++p)
        if (dirty_[p]) push_pull(p);
}

void Hierarchy::pull_path(const PatchAddress& a) {
    const bool tri = scene_->polygons[a.polygon].is_triangle();
    PatchAddress cur = a;
    while (cur.level > 0) {
        const PatchAddress parent{cur.polygon, cur.level - 1,
                                  patch_parent(tri, cur.level, cur.index)};
        glm::vec3 dB(0.f);
        for (std::uint32_t c : patch_children(tri, parent.level, parent.index)) {
            const Node& child = node({a.polygon, cur.level, c});
            dB += child.dB * child.area;
        }
        Node& pn = node(parent);
        pn.dB = dB / pn.area;
        cur = parent;
    }
}

void Hierarchy::clear_unshot(const PatchAddress& a) {
    HEMIRAD_CHECK(!dirty_[a.polygon]);
    const bool tri = scene_->polygons[a.polygon].is_triangle();
    const int depth = disc_.depth[a.polygon];
    // The subtree at level l spans a set of indices; walk it level by level.
    std::vector<std::uint32_t> level_nodes{a.index}, next;
    for (int level = int(a.level); level <= depth; ++level) {
        for (std::uint32_t i : level_nodes) node({a.polygon, std::uint32_t(level), i}).dB = {};
        if (level == depth) break;
        next.clear();
        for (std::uint32_t i : level_nodes)
            for (std::uint32_t c : patch_children(tri, level, i)) next.push_back(c);
        level_nodes.swap(next);
    }
    pull_path(a);
    const Node& root = node({a.polygon, 0, 0});
    unshot_[a.polygon] = dvec3(root.dB) * double(root.area);
}

dvec3 Hierarchy::add_unshot(std::uint32_t p, const dvec3& drho, const dvec3& dBe) {
    HEMIRAD_CHECK(drho == dvec3(0.0) || rho_base_.empty() || rho_base_[p] == kUntextured);
    const int depth = disc_.depth[p];
    Node* leaves = nodes_.data() + base_[p] + level_offset(depth);
    const glm::vec3 d_rho(drho), d_be(dBe);
    for (std::uint32_t i = 0; i < (1u << (2 * depth)); ++i)
        leaves[i].dB += d_rho * leaves[i].H + d_be;
    push_pull(p); // pulls the leaves' dB up and recomputes the polygon's unshot power
    const Node& root = nodes_[base_[p]];
    return dvec3(root.H) * double(root.area);
}

void Hierarchy::scale(double s) {
    const float f = float(s);
    for (Node& n : nodes_) {
        n.H *= f;
        n.dB *= f;
        n.dI *= f;
    }
    for (dvec3& u : unshot_) u *= s;
    if (s == 0) std::fill(dirty_.begin(), dirty_.end(), std::uint8_t(0));
}

void Hierarchy::add_scaled(const Hierarchy& other, double s) {
    HEMIRAD_CHECK_EQ(other.nodes_.size(), nodes_.size());
    HEMIRAD_CHECK_EQ(other.unshot_.size(), unshot_.size());
    const float f = float(s);
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
        nodes_[i].H += f * other.nodes_[i].H;
        nodes_[i].dB += f * other.nodes_[i].dB;
        nodes_[i].dI += f * other.nodes_[i].dI;
    }
    for (std::size_t p = 0; p < unshot_.size(); ++p) {
        unshot_[p] += s * other.unshot_[p];
        dirty_[p] = std::uint8_t(dirty_[p] | other.dirty_[p]);
    }
}

dvec3 Hierarchy::total_unshot_power() const {
    dvec3 u(0.0);
    for (const dvec3& p : unshot_) u += p;
    return u;
}

dvec3 Hierarchy::radiosity(const PatchAddress& a) const {
    const Material& m = scene_->material_of(scene_->polygons[a.polygon]);
    return m.exitance() + reflectance(a) * irradiance(a);
}

dvec3 Hierarchy::irradiance_shot(const PatchAddress& a) const {
    const bool tri = scene_->polygons[a.polygon].is_triangle();
    dvec3 h = dvec3(node(a).H) + dvec3(node(a).dI);
    PatchAddress cur = a;
    while (cur.level > 0) {
        cur = {cur.polygon, cur.level - 1, patch_parent(tri, cur.level, cur.index)};
        h += dvec3(node(cur).dI);
    }
    return h;
}

void Hierarchy::restore_state(const std::vector<Node>& nodes, const std::vector<dvec3>& unshot,
                              const std::vector<std::uint8_t>& dirty) {
    HEMIRAD_CHECK_EQ(nodes.size(), nodes_.size());
    HEMIRAD_CHECK_EQ(unshot.size(), unshot_.size());
    HEMIRAD_CHECK_EQ(dirty.size(), dirty_.size());
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        nodes_[i].H = nodes[i].H;
        nodes_[i].dB = nodes[i].dB;
        nodes_[i].dI = nodes[i].dI;
    }
    unshot_ = unshot;
    dirty_ = dirty;
}

double Hierarchy::bytes_per_leaf() const {
    return leaves_ ? double(nodes_.size() * sizeof(Node) + rho_.size() * sizeof(glm::vec3)) /
                         double(leaves_)
                   : 0.0;
}

} // namespace hemirad
