// The patch hierarchy: a quadtree of patches per polygon (paper 002 §4.1), stored level by
// level in one flat array. Per node and RGB channel it keeps the irradiance H received so
// far, the unshot radiosity dB and the unpushed irradiance dI; the radiosity is derived,
// B = Be + rho*H (storing H rather than B keeps the irradiance E that reports need, also for
// a black channel). Per polygon, the total unshot power is kept up to date as light arrives.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "hemirad/form_factors.h"
#include "hemirad/patch.h"
#include "hemirad/scene.h"
#include "hemirad/visibility.h"

namespace hemirad {

struct HierarchyOptions {
    /// Target leaf patch size (longest edge) in scene units; 0 = automatic (the scene's
    /// bounding-box diagonal / 64). Each polygon is subdivided until its patches are no larger.
    double patch_size = 0;
    int max_depth = 6; ///< cap on quadtree depth per polygon (0..kMaxDepth)
};

/// Depth of each polygon's quadtree for these options. Deterministic; shared by the solver
/// and the form-factor providers.
HEMIRAD_API Discretisation discretise(const Scene& scene, const HierarchyOptions& options);

class HEMIRAD_API Hierarchy {
  public:
    /// Per-node state, 40 bytes: float is enough for one shot's contribution, and totals that
    /// must be exact (energy balance) are kept in double by the solver.
    struct Node {
        glm::vec3 H{0.f};  ///< irradiance received and pushed [W unit^-2]
        glm::vec3 dB{0.f}; ///< unshot radiosity [W unit^-2]
        glm::vec3 dI{0.f}; ///< irradiance received here, not yet pushed to the leaves
        float area = 0.f;  ///< [unit^2]
    };

    Hierarchy(const Scene& scene, const Discretisation& disc);

    const Scene& scene() const { return *scene_; }
    const Discretisation& discretisation() const { return disc_; }
    int depth(std::uint32_t polygon) const { return disc_.depth[polygon]; }
    std::uint64_t node_count() const { return nodes_.size(); }
    std::uint64_t leaf_count() const { return leaves_; }

    std::uint64_t node_id(const PatchAddress& a) const {
        return base_[a.polygon] + level_offset(int(a.level)) + a.index;
    }
    Node& node(const PatchAddress& a) { return nodes_[node_id(a)]; }
    const Node& node(const PatchAddress& a) const { return nodes_[node_id(a)]; }

    /// Light arriving at a node: dI += irradiance (RGB); the polygon's unshot power grows by
    /// rho*irradiance*area. The polygon then needs a push-pull before it shoots.
    void receive(const PatchAddress& a, const dvec3& irradiance);
    /// Pushes dI down to the leaves (into H and dB) and pulls area-weighted averages up.
    /// Recomputes the polygon's unshot power exactly from its root afterwards.
    void push_pull(std::uint32_t polygon);
    void push_pull_all();
    bool needs_push_pull(std::uint32_t polygon) const { return dirty_[polygon] != 0; }

    /// An edit of the polygon's material (incremental re-solving, solver.h): its reflectance
    /// changed by drho (untextured polygons only) and its emitted radiosity by dBe, already in
    /// the scene. Every leaf's unshot radiosity grows by drho*H + dBe (H as pushed so far; the
    /// irradiance not yet pushed is reflected with the new reflectance when it is), then the
    /// polygon is push-pulled. Returns the irradiance power it has received, H*area [W].
    dvec3 add_unshot(std::uint32_t polygon, const dvec3& drho, const dvec3& dBe);

    /// Multiplies every node's received and unshot light (H, dB, dI) and every polygon's
    /// unshot power by s (a light layer's luminaire dimmed: Solver, light_layers.h); s = 0
    /// empties the hierarchy, emission included. Dirty flags are kept (s = 0 clears them).
    void scale(double s);
    /// Adds s times `other`'s received and unshot light, node by node, and its unshot powers;
    /// a polygon dirty in either is dirty. `other` must be a hierarchy of the same scene and
    /// discretisation (checked by size).
    void add_scaled(const Hierarchy& other, double s);

    /// Sets the unshot radiosity of the subtree under `a` to zero (it has been shot) and
    /// updates its ancestors and the polygon's unshot power. Requires a pushed polygon.
    void clear_unshot(const PatchAddress& a);

    /// Unshot power of a polygon, RGB [W] (includes light received but not yet pushed).
    const dvec3& unshot_power(std::uint32_t polygon) const { return unshot_[polygon]; }
    dvec3 total_unshot_power() const;

    /// Reflectance of a node per channel: its material's rho, or, on a textured polygon, the
    /// texture's mean over a leaf (patch_reflectance(), patch.h) and the area-weighted mean of
    /// those over a larger node. Light received at a node is reflected leaf by leaf.
    dvec3 reflectance(const PatchAddress& a) const {
        return rho_base_.empty() || rho_base_[a.polygon] == kUntextured
                   ? scene_->material_of(scene_->polygons[a.polygon]).rho
                   : dvec3(rho_[rho_base_[a.polygon] + level_offset(int(a.level)) + a.index]);
    }

    /// Radiosity B = Be + rho*H of a node (valid for pushed polygons) [W unit^-2]; on a
    /// textured polygon rho is the node's mean reflectance (exact at leaves).
    dvec3 radiosity(const PatchAddress& a) const;
    /// Irradiance of a node as read out: H, what is still unpushed above and at it, and the
    /// estimate of the light not yet shot (set_unshot_estimate).
    dvec3 irradiance(const PatchAddress& a) const { return irradiance_shot(a) + unshot_estimate_; }
    /// The same without the estimate: what the shots delivered so far.
    dvec3 irradiance_shot(const PatchAddress& a) const;
    /// The irradiance still to arrive at every surface from the power not yet shot
    /// (Solver::ambient_irradiance; 0 until a solver sets it), added by irradiance() and so to
    /// every read-out: probes, grids, images, lightmaps, reports.
    void set_unshot_estimate(const dvec3& e) { unshot_estimate_ = e; }
    const dvec3& unshot_estimate() const { return unshot_estimate_; }

    /// Bytes of node storage per leaf patch (for reports).
    double bytes_per_leaf() const;

    /// The complete state, for saving and resuming a solve bit for bit.
    const std::vector<Node>& nodes() const { return nodes_; }
    const std::vector<dvec3>& unshot_powers() const { return unshot_; }
    const std::vector<std::uint8_t>& dirty_flags() const { return dirty_; }
    /// Restores a state saved from a hierarchy of the same scene and discretisation: node
    /// values (areas are kept: they are geometry), unshot powers and dirty flags. The sizes
    /// must match (checked).
    void restore_state(const std::vector<Node>& nodes, const std::vector<dvec3>& unshot,
                       const std::vector<std::uint8_t>& dirty);

  private:
    void pull_path(const PatchAddress& a);

    static constexpr std::uint64_t kUntextured = ~std::uint64_t(0);

    const Scene* scene_;
    Discretisation disc_;
    /// Per-node reflectance of textured polygons (empty in an untextured scene): the nodes of
    /// polygon p from rho_base_[p] on, laid out like nodes_; kUntextured for the others.
    std::vector<std::uint64_t> rho_base_;
    std::vector<glm::vec3> rho_;
    std::vector<std::uint64_t> base_; ///< first node of each polygon
    std::vector<Node> nodes_;
    std::vector<dvec3> unshot_;
    std::vector<std::uint8_t> dirty_;
    std::uint64_t leaves_ = 0;
    dvec3 unshot_estimate_{0.0};
};

} // namespace hemirad
