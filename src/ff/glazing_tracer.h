// What the scene's window panes (Scene::glazing, glazing.h) let through along a ray or a
// segment: the product of the transmittances of the panes it crosses, each at the angle it
// crosses. Every light path that may cross a pane asks it: the sky's and the sun's rays, the
// solver's links, the final gather. Internal header.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "hemirad/scene.h"

namespace hemirad {

class Bvh;

class GlazingTracer {
  public:
    explicit GlazingTracer(const Scene& scene);
    ~GlazingTracer();
    GlazingTracer(const GlazingTracer&) = delete;
    GlazingTracer& operator=(const GlazingTracer&) = delete;

    /// No panes: everything passes (transmittance 1, no work).
    bool empty() const { return panes_.empty(); }
    /// Along origin + t dir for t in (0, tmax) (`dir` need not be normalised; tmax may be
    /// infinite): the product of the crossed panes' transmittances, in [0, 1].
    double along(const dvec3& origin, const dvec3& dir, double tmax) const;
    /// Between two points, the first and last 1e-7 of the segment left out (as Bvh::occluded):
    /// a pane the segment only touches at an end does not count.
    double between(const dvec3& from, const dvec3& to) const;

  private:
    std::vector<GlazingPane> panes_;
    std::unique_ptr<Bvh> bvh_; ///< over the panes' polygons
};

} // namespace hemirad
