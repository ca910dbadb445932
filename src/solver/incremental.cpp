// Incremental re-solving (issue 21; solver.h, "Incremental re-solving"): an edit of the
// scene's photometry becomes unshot power, which the usual shooting then distributes.
//
// Radiosity is linear in the emission, B = Be + rho H with H = sum_j F B_j (paper 001 eq. 1):
// a luminaire whose power changes by dP adds dP of unshot power at its position; a patch whose
// reflectance changes by drho has, for the irradiance it has received so far, a radiosity off
// by drho H, and one whose emission changes by dBe one off by dBe. Shooting these differences
// (negative where light is removed) converges to the solution of the edited scene, as the
// shooting of the original emission converged to the first.
#include <cmath>

#include "hemirad/error.h"
#include "hemirad/scene_edit.h"
#include "hemirad/solver.h"
#include "solver/solver_detail.h"

namespace hemirad {

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
    // A luminaire: the difference of its power is unshot, at its position.
    for (std::size_t k = 0; k < now.luminaires.size(); ++k) {
        const dvec3 d = now.luminaires[k] - before.luminaires[k];
        if (d == dvec3(0.0)) continue;
        luminaire_unshot_[k] += d;
        ++luminaires;
    }
    // A polygon: dB = drho H + dBe on its leaves. The light it absorbed so far changes by
    // -drho H A: the energy balance (emitted = absorbed + escaped + unshot) still closes.
    for (std::uint32_t p = 0; p < now.rho.size(); ++p) {
        const dvec3 drho = now.rho[p] - before.rho[p];
        const dvec3 dBe = now.exitance[p] - before.exitance[p];
        if (drho == dvec3(0.0) && dBe == dvec3(0.0)) continue;
        absorbed_ -= drho * hierarchy_.add_unshot(p, drho, dBe);
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
