// Glazing (SCENE.json "glazing"): surface groups that are window panes rather than surfaces.
// A pane is taken out of the radiosity geometry (it has no patches, does not shoot and is not
// drawn in a hemicube) and lets light through in the direction it came (a thin clear pane):
// every light path that crosses it, from the sky, the sun, a luminaire or another surface, is
// multiplied by its transmittance. Light a pane reflects (about 8 % for clear glass) is left
// out: what falls on a pane from either side passes it or is lost.
#pragma once

#include <string>

#include "hemirad/visibility.h"

namespace hemirad {

/// Refractive index of the panes' glass (soda-lime; Radiance's glass uses the same).
inline constexpr double kGlassIndex = 1.52;
/// The largest normal-incidence transmittance a clear pane of kGlassIndex can have (no
/// absorption: its two surfaces reflect 8.2 % together).
HEMIRAD_API double clear_glass_transmittance();

/// The transmittance of a pane at normal incidence, and how it falls off at grazing angles.
struct HEMIRAD_API PaneTransmittance {
    double normal = 1;   ///< tau at normal incidence, in [0, 1]
    bool angular = true; ///< Fresnel fall-off (see at()); false: tau at every angle
    /// The per-pass transmissivity t of the glass inside the pane at normal incidence, solved
    /// from `normal` (set by make_pane_transmittance).
    double transmissivity = 1;

    /// The transmittance for light arriving at |cos_incidence| to the pane's normal: a thin
    /// pane of index kGlassIndex with internal transmissivity t^(1/cos_r) along the refracted
    /// path, both surfaces' Fresnel reflection per polarisation and their interreflections,
    /// averaged over the two polarisations (the model of Radiance's `glass`); `normal` at every
    /// angle when not angular. 0 at grazing incidence.
    double at(double cos_incidence) const;
};

/// A pane for the normal-incidence transmittance tau in [0, 1]. The Fresnel fall-off applies
/// when `angular` and tau <= clear_glass_transmittance(); above that no glass reaches tau and
/// `angular` is turned off (the caller warns).
HEMIRAD_API PaneTransmittance make_pane_transmittance(double tau, bool angular = true);

} // namespace hemirad
