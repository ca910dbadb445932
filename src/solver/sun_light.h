// The sun's direct light on surfaces (Scene::sun, sun.h): delivered to every leaf patch before
// the first shot, like a luminaire's first shot, and gathered exactly at read-out points.
// Internal header.
#pragma once

#include <cstdint>

#include "hemirad/hierarchy.h"
#include "hemirad/scene.h"
#include "solver/leaf_light.h"

namespace hemirad {

class Bvh;
class GlazingTracer;

/// What deliver_sunlight() delivered (leaf_light.h).
using SunDelivery = LeafDelivery;

/// Delivers the sun's direct irradiance E = E_n/683 max(0, n.s) V to every leaf patch
/// (Hierarchy::receive), V the fraction of the leaf that sees the sun: shadow rays along s
/// from the centres of a 4 x 4 grid of equal cells over the leaf, and of an 8 x 8 grid where
/// some of those 16 are shadowed and some not (a shadow's edge crosses the leaf); a ray through
/// window panes counts their transmittance (glazing.h) instead of 1. Nothing for
/// a scene without a sun, or with one at or below the horizon. `bvh` and `glazing` are the
/// scene's (built once for the sun and the sky). threads: 0 = one per core.
SunDelivery deliver_sunlight(const Scene& scene, const Bvh& bvh, const GlazingTracer& glazing,
                             Hierarchy& hierarchy, int threads = 0);

/// The sun's direct irradiance at point x with unit normal n on polygon `self` (kNoPolygon off
/// the surfaces), one shadow ray along s from x + offset n: E_n/683 max(0, n.s) or 0 in
/// shadow [W unit^-2], equal RGB, times the transmittance of the panes the ray crosses
/// (`glazing`; null: no panes). 0 without a sun.
dvec3 sun_irradiance(const Scene& scene, const Bvh& bvh, const dvec3& x, const dvec3& n,
                     std::uint32_t self, double offset, const GlazingTracer* glazing = nullptr);

} // namespace hemirad
