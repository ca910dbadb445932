// Light layers (issue 21): each luminaire's share of the solution, kept apart, so that dimming
// or switching off a luminaire rescales its share instead of shooting the difference.
//
// Radiosity is linear in the emission: the solution is the sum of what each luminaire's light
// became (direct and every bounce) and what the rest (emitting surfaces, the sun, the sky)
// became. A layer is a Hierarchy that receives, for every shot, only its luminaire's part of
// the shooter's unshot radiosity (the layer's own dB at the shooter's node): the luminaire's
// own shot, then each patch shot's share of that luminaire's light. The solver's hierarchy
// stays the solution (every read-out reads it); the layers only shadow it. A multiplier
// f0 -> f1 (f0 > 0) then adds (f1/f0 - 1) times the layer to the solution and scales the
// layer: the solution of the edited scene, with no shot (Solver::set_luminaire_multiplier).
//
// Cost: a hierarchy per luminaire (memory) and each patch shot delivered once more for every
// luminaire whose light is in the shooter. Used where that is small: see LightLayers::wanted.
// Cluster shots (which read the polygons' unshot powers, not nodes) and parallel rounds do not
// keep layers; there an edit is shot as unshot power (incremental.cpp).
// Internal header.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "hemirad/form_factors.h"
#include "hemirad/hierarchy.h"
#include "hemirad/scene.h"
#include "hemirad/solver.h"

namespace hemirad {

/// At most this many luminaires get layers ("auto").
inline constexpr std::size_t kLayerLuminaires = 16;
/// ... and only while the layers' node storage stays under this [bytes] ("auto").
inline constexpr double kLayerBytes = 256.0 * 1024 * 1024;

class LightLayers {
  public:
    /// One layer per luminaire of the primary's scene, empty (no light, no emission).
    explicit LightLayers(const Hierarchy& primary);

    /// Does SolverOptions::light_layers ask for layers in this scene? "on": whenever there are
    /// luminaires; "auto": 1..kLayerLuminaires luminaires whose layers fit in kLayerBytes;
    /// never with clusters (their shots read polygons' unshot powers, not nodes).
    static bool wanted(const std::string& mode, const Hierarchy& primary, bool clusters);

    std::size_t size() const { return layers_.size(); }
    const Hierarchy& layer(std::size_t k) const { return layers_[k].light; }

    /// Push-pulls the polygon in every layer that needs it (before its nodes are read).
    void push_pull(std::uint32_t polygon);
    /// A patch shot from node `sa` of area area_s: each layer's share of the shooter's unshot
    /// radiosity goes along the links (their form factors times `scale`, the row guard's), and
    /// the shooter's unshot radiosity is cleared in every layer.
    void deliver_patch(const PatchAddress& sa, double area_s, const std::vector<Link>& links,
                       double scale);
    /// Luminaire k's shot of `power` (its unshot power) along the links, into its own layer.
    void deliver_luminaire(std::size_t k, const dvec3& power, const std::vector<Link>& links,
                           double scale);
    /// A reflectance edit of polygon p by drho (Hierarchy::add_unshot, without emission, which
    /// is no luminaire's), in every layer.
    void add_unshot(std::uint32_t polygon, const dvec3& drho);
    /// Luminaire k's share times s: `primary` gains (s - 1) times the layer, the layer is
    /// scaled, and its absorbed and escaped power too; returns the change of the absorbed and
    /// of the escaped power (for the solver's energy balance).
    std::pair<dvec3, dvec3> rescale(std::size_t k, double s, Hierarchy& primary);

    /// Saving and resuming (Solver::State::layers).
    using State = Solver::State::Layer;
    std::vector<State> save_state() const;
    /// Restores layers saved for the same scene (sizes checked by the caller).
    void restore_state(const std::vector<State>& layers);

  private:
    struct Layer {
        Hierarchy light;
        dvec3 absorbed{0.0}, escaped{0.0}; ///< of this luminaire's light [W]
    };
    std::vector<Layer> layers_;
};

} // namespace hemirad
