// The sky's direct light on surfaces and at points (Scene::sky, sky.h): delivered to every leaf
// patch before the first shot, like the sun's (sun_light.h), and gathered at read-out points.
// Internal header.
#pragma once

#include <cstdint>

#include "hemirad/hierarchy.h"
#include "hemirad/scene.h"
#include "solver/leaf_light.h"

namespace hemirad {

class Bvh;
class GlazingTracer;
class Rng;

/// What deliver_skylight() delivered (leaf_light.h).
using SkyDelivery = LeafDelivery;

/// Rays per leaf in deliver_skylight(): kSkyLeafRays^2 (stratified).
inline constexpr int kSkyLeafRays = 16;

/// Delivers the sky's (and the ground's) direct irradiance to every leaf patch
/// (Hierarchy::receive): E = pi/N sum_k L(w_k)/683 over N = 16 x 16 cosine-distributed
/// directions w_k stratified over the unit square (core/sampling.h cosine_direction), each from
/// its own point jittered over the leaf's area, L(w) the sky's luminance (sky.h) for a ray that
/// leaves the scene, 0 for one that meets a polygon (pdf cos/pi: E = pi E[L] per sample), times
/// the transmittance of the window panes it crosses (glazing.h).
/// Nothing for a scene without a sky. `bvh` and `glazing` are the scene's (built once for the
/// sun and the sky). threads: 0 = one per core.
SkyDelivery deliver_skylight(const Scene& scene, const Bvh& bvh, const GlazingTracer& glazing,
                             Hierarchy& hierarchy, int threads = 0);

/// The sky's direct irradiance at x with unit normal n on polygon `self` (kNoPolygon off the
/// surfaces) in a scene of bounds `bounds` [W unit^-2], equal RGB. Stratified cosine rays from
/// x + offset n over coarse x coarse cells of the unit square (core/sampling.h
/// cosine_direction): pilot rays through the centres of a grid twice as fine decide which cells
/// lie on the edge of an opening or the horizon (two neighbouring pilots see different things:
/// a polygon, the sky, the ground) or in the clear sky's circumsolar region (sky changing by
/// more than 25 % across a cell); those are sampled by fine x fine jittered rays, the others by one
/// jittered ray. The pilots only choose, so the estimate is unbiased; the edges of openings
/// are resolved as by (coarse * fine)^2 stratified rays at the cost of the cells along them.
/// `rays` counts the rays cast (pilots too). A ray through window panes brings the sky times
/// their transmittance (`glazing`; null: no panes).
dvec3 sky_irradiance(const Sky& sky, const Bounds& bounds, const Bvh& bvh, const dvec3& x,
                     const dvec3& n, std::uint32_t self, double offset, Rng& rng, int coarse = 32,
                     int fine = 8, std::uint64_t* rays = nullptr,
                     const GlazingTracer* glazing = nullptr);

/// Does the ray from `origin` along unit `w` leave the scene of bounds `b` (meet no polygon but
/// `self`)?
bool sky_escapes(const Bounds& b, const Bvh& bvh, const dvec3& origin, const dvec3& w,
                 std::uint32_t self);

} // namespace hemirad
