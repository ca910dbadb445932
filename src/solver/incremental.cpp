// Incremental re-solving (issue 21; solver.h, "Incremental re-solving"): an edit of the
// scene's photometry becomes unshot power, which the usual shooting then distributes.
//
// Radiosity is linear in the emission, B = Be + rho H with H = sum_j F B_j (paper 001 eq. 1):
// a luminaire whose power changes by dP adds dP of unshot power at its position; a patch whose
// reflectance changes by drho has, for the irradiance it has received so far, a radiosity off
// by drho H, and one whose emission changes by dBe one off by dBe. Shooting these differences
// (negative where light is removed) converges to the solution of the edited scene, as the
// shooting of the original emission converged to the first.
#include <algorithm>
#include <cmath>

#include "hemirad/error.h"
#include "hemirad/scene_edit.h"
#include "hemirad/solver.h"
#include "solver/light_layers.h"
#include "solver/solver_detail.h"

namespace hemirad {

namespace {

/// s with now = s * before in every channel (a multiplier's change), or -1 when there is none:
/// `before` is dark (the luminaire was off) or the two are not proportional.
double power_ratio(const dvec3& before, const dvec3& now) {
    const double b = std::max({before.x, before.y, before.z});
    if (!(b > 0)) return -1;
    const int c = before.x == b ? 0 : before.y == b ? 1 : 2;
    const double s = now[c] / b;
    for (int i = 0; i < 3; ++i)
        if (std::abs(now[i] - s * before[i]) > 1e-12 * std::max(std::abs(now[i]), b)) return -1;
    return s;
}

} // namespace

Solver::Solver(Scene& scene, const SolverOptions& options)
    : Solver(static_cast<const Scene&>(scene), options) {
    editable_ = &scene;
}

Scene& Solver::editable_scene(const char* what) {
    if (!editable_)
        throw InputError(std::string("Solver::") + what +
                         ": the solver was built from a const Scene, which it cannot edit");
    return *editable_;
}

dvec3 Solver::signed_unshot_power() const {
    dvec3 u = hierarchy_.total_unshot_power();
    for (const dvec3& l : luminaire_unshot_) u += l;
    return u;
}

void Solver::set_luminaire_multiplier(const std::string& name, double multiplier) {
    Scene& scene = editable_scene("set_luminaire_multiplier");
    const Photometry before = photometry(scene);
    hemirad::set_luminaire_multiplier(scene, name, multiplier);
    apply_photometry(before);
}

void Solver::place_luminaire(const std::string& name, const dvec3& position, const dvec3& aim) {
    Scene& scene = editable_scene("place_luminaire");
    if (!layers_)
        throw InputError("luminaire " + name +
                         ": moving a luminaire needs light layers (--light-layers on; not with "
                         "clusters or MPI rounds)");
    // Moved in the scene (or an InputError, nothing changed) ...
    const std::size_t k = set_luminaire_placement(scene, name, position, aim);
    // ... its light so far (layer k, and what it has not shot) leaves the solution, and all
    // its power is unshot at the new place.
    rescale_layer(k, 0.0);
    luminaire_unshot_[k] = dvec3(scene.luminaires[k].power());
    check_stop();
}

void Solver::rescale_layer(std::size_t k, double s) {
    const auto [absorbed, escaped] = layers_->rescale(k, s, hierarchy_);
    absorbed_ += absorbed;
    escaped_ += escaped;
}

void Solver::set_reflectance(const std::string& group, const dvec3& rho) {
    Scene& scene = editable_scene("set_reflectance");
    const Photometry before = photometry(scene);
    set_group_reflectance(scene, group, rho);
    apply_photometry(before);
}

void Solver::set_emission(const std::string& group, const dvec3& Ke) {
    Scene& scene = editable_scene("set_emission");
    const Photometry before = photometry(scene);
    set_group_emission(scene, group, Ke);
    apply_photometry(before);
}

std::pair<std::size_t, std::size_t> Solver::apply_photometry(const Photometry& before) {
    const Photometry now = photometry(*scene_);
    const auto expect = [](const char* what, std::size_t was, std::size_t is) {
        if (was != is)
            throw InputError(std::string("photometry edit: ") + what + ": " + std::to_string(was) +
                             " before, " + std::to_string(is) + " now");
    };
    expect("polygons", before.rho.size(), now.rho.size());
    expect("polygons (emission)", before.exitance.size(), now.exitance.size());
    expect("luminaires", before.luminaires.size(), now.luminaires.size());
    for (std::uint32_t p = 0; p < now.rho.size(); ++p)
        if (now.rho[p] != before.rho[p] && scene_->texture_of(p))
            throw InputError("photometry edit: polygon " + std::to_string(p) + " (group '" +
                             scene_->groups[scene_->polygons[p].group] +
                             "') is textured: its reflectance cannot change incrementally");
    std::size_t luminaires = 0, polygons = 0;
    // A luminaire: with light layers, its share of the solution times the ratio of its powers
    // (exact, no shot); without, or from off, the difference of its power is unshot, at its
    // position.
    for (std::size_t k = 0; k < now.luminaires.size(); ++k) {
        const dvec3 d = now.luminaires[k] - before.luminaires[k];
        if (d == dvec3(0.0)) continue;
        ++luminaires;
        const double s = layers_ ? power_ratio(before.luminaires[k], now.luminaires[k]) : -1;
        if (s < 0) {
            luminaire_unshot_[k] += d;
            continue;
        }
        rescale_layer(k, s);
        luminaire_unshot_[k] *= s;
        ++rescaled_;
    }
    // A polygon: dB = drho H + dBe on its leaves. The light it absorbed so far changes by
    // -drho H A: the energy balance (emitted = absorbed + escaped + unshot) still closes.
    for (std::uint32_t p = 0; p < now.rho.size(); ++p) {
        const dvec3 drho = now.rho[p] - before.rho[p];
        const dvec3 dBe = now.exitance[p] - before.exitance[p];
        if (drho == dvec3(0.0) && dBe == dvec3(0.0)) continue;
        absorbed_ -= drho * hierarchy_.add_unshot(p, drho, dBe);
        if (layers_ && drho != dvec3(0.0)) layers_->add_unshot(p, drho);
        ++polygons;
    }
    // The emitted power before the edits and now; the sun's and the sky's are not edited.
    dvec3 before_emitted = daylight_;
    for (std::size_t p = 0; p < before.exitance.size(); ++p)
        before_emitted += before.exitance[p] * scene_->polygons[p].area;
    for (const dvec3& power : before.luminaires) before_emitted += power;
    emitted_ = scene_->emitted_power() + daylight_;
    peak_emitted_ = glm::max(peak_emitted_, glm::max(before_emitted, emitted_));
    rho_max_ = scene_->max_reflectance();
    check_stop();
    return {luminaires, polygons};
}

} // namespace hemirad
