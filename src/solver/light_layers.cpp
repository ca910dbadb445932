// Light layers: each luminaire's share of the solution (light_layers.h).
#include "solver/light_layers.h"

#include "hemirad/error.h"
#include "solver/solver_detail.h"

namespace hemirad {

LightLayers::LightLayers(const Hierarchy& primary) {
    const std::size_t n = primary.scene().luminaires.size();
    layers_.reserve(n);
    for (std::size_t k = 0; k < n; ++k) {
        layers_.push_back({Hierarchy(primary.scene(), primary.discretisation())});
        layers_.back().light.scale(0.0); // no emission: that is the rest's, not a luminaire's
    }
}

bool LightLayers::wanted(const std::string& mode, const Hierarchy& primary, bool clusters) {
    const std::size_t n = primary.scene().luminaires.size();
    if (mode == "off" || n == 0 || clusters) return false;
    if (mode == "on") return true;
    const double bytes = double(n) * double(primary.node_count()) * sizeof(Hierarchy::Node);
    return n <= kLayerLuminaires && bytes <= kLayerBytes;
}

void LightLayers::push_pull(std::uint32_t polygon) {
    for (Layer& l : layers_)
        if (l.light.needs_push_pull(polygon)) l.light.push_pull(polygon);
}

void LightLayers::deliver_patch(const PatchAddress& sa, double area_s,
                                const std::vector<Link>& links, double scale) {
    for (Layer& l : layers_) {
        const dvec3 dB(l.light.node(sa).dB);
        if (dB == dvec3(0.0)) continue; // none of this luminaire's light is in the shooter
        solver_detail::deliver_links(l.light, links, dB, area_s, scale, l.absorbed, l.escaped);
        l.light.clear_unshot(sa);
    }
}

void LightLayers::deliver_luminaire(std::size_t k, const dvec3& power,
                                    const std::vector<Link>& links, double scale) {
    Layer& l = layers_[k];
    solver_detail::deliver_links(l.light, links, power, 1.0, scale, l.absorbed, l.escaped);
}

void LightLayers::add_unshot(std::uint32_t polygon, const dvec3& drho) {
    for (Layer& l : layers_) l.absorbed -= drho * l.light.add_unshot(polygon, drho, dvec3(0.0));
}

std::pair<dvec3, dvec3> LightLayers::rescale(std::size_t k, double s, Hierarchy& primary) {
    Layer& l = layers_[k];
    primary.add_scaled(l.light, s - 1.0);
    l.light.scale(s);
    const std::pair<dvec3, dvec3> change{(s - 1.0) * l.absorbed, (s - 1.0) * l.escaped};
    l.absorbed *= s;
    l.escaped *= s;
    return change;
}

std::vector<LightLayers::State> LightLayers::save_state() const {
    std::vector<State> out;
    out.reserve(layers_.size());
    for (const Layer& l : layers_)
        out.push_back({l.light.nodes(), l.light.unshot_powers(), l.light.dirty_flags(), l.absorbed,
                       l.escaped});
    return out;
}

void LightLayers::restore_state(const std::vector<State>& layers) {
    HEMIRAD_CHECK_EQ(layers.size(), layers_.size());
    for (std::size_t k = 0; k < layers.size(); ++k) {
        layers_[k].light.restore_state(layers[k].nodes, layers[k].unshot, layers[k].dirty);
        layers_[k].absorbed = layers[k].absorbed;
        layers_[k].escaped = layers[k].escaped;
    }
}

} // namespace hemirad
