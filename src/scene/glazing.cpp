// Glazing transmittance (glazing.h).
#include "hemirad/glazing.h"

#include <algorithm>
#include <cmath>

namespace hemirad {

namespace {

/// The thin pane's transmittance for internal transmissivity t along the normal, at incidence
/// cosine c1: per polarisation r = Fresnel reflectance of one surface, d = t^(1/c2) along the
/// refracted path, T = (1 - r)^2 d / (1 - r^2 d^2) (the interreflections summed).
double pane(double t, double c1) {
    c1 = std::min(1.0, std::abs(c1));
    if (!(c1 > 0)) return 0.0;
    const double n = kGlassIndex;
    const double c2 = std::sqrt(1 - (1 - c1 * c1) / (n * n));
    const double d = std::pow(t, 1 / c2);
    double rs = (c1 - n * c2) / (c1 + n * c2);
    double rp = (1 / c1 - n / c2) / (1 / c1 + n / c2);
    rs *= rs;
    rp *= rp;
    const auto one = [d](double r) { return (1 - r) * (1 - r) * d / (1 - r * r * d * d); };
    return 0.5 * (one(rs) + one(rp));
}

} // namespace

double clear_glass_transmittance() {
    return pane(1.0, 1.0);
}

double PaneTransmittance::at(double cos_incidence) const {
    if (!angular) return normal;
    return pane(transmissivity, cos_incidence);
}

PaneTransmittance make_pane_transmittance(double tau, bool angular) {
    PaneTransmittance p;
    p.normal = std::clamp(tau, 0.0, 1.0);
    p.angular = angular && p.normal <= clear_glass_transmittance() && p.normal > 0;
    if (!p.angular) return p;
    // pane(t, 1) grows monotonically with t: bisect for pane(t, 1) = tau.
    double lo = 0, hi = 1;
    for (int k = 0; k < 60; ++k) {
        const double mid = 0.5 * (lo + hi);
        (pane(mid, 1.0) < p.normal ? lo : hi) = mid;
    }
    p.transmissivity = 0.5 * (lo + hi);
    return p;
}

} // namespace hemirad
