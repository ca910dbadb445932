// Polygons whose plane cuts a shooter (the solver's shooter refinement, next to the parallax
// measure of gpu/hemicube.h): a polygon Q in front of a patch S whose plane passes through S
// shows its front to one part of S and its back (or nothing) to the other, yet from S's
// centre, in that plane, it is seen edge-on and gets nothing from a shot of S's centre. A
// plate floating beside a wall, a shelf board beside the wall it is fixed to, a partition
// standing on a floor that runs on beneath it: the parallax measure (silhouettes in the
// hemicube) cannot see what the hemicube does not show. Internal header.
#pragma once

#include <cstdint>
#include <vector>

#include "hemirad/patch.h"
#include "hemirad/scene.h"

namespace hemirad {

class PlaneCuts {
  public:
    /// For every polygon, the polygons within `reach` times its size (sqrt of its area) that
    /// lie partly in front of it and whose plane separates its corners (strictly).
    PlaneCuts(const Scene& scene, double reach);

    /// The largest share of the hemisphere (A_Q / (pi d^2), capped at 1; d from the patch's
    /// centre to Q's centre) among the polygons whose plane cuts the patch `node` of polygon
    /// `polygon` and that lie within `reach` times the patch's size of its centre; 0 if none.
    double cut_share(std::uint32_t polygon, const PatchGeometry& node) const;

    /// Polygons with at least one candidate (for reports and tests).
    std::size_t polygons_cut() const;

  private:
    struct Plane {
        dvec3 n{0.0};
        double d = 0;
    };
    const Scene* scene_;
    double reach_;
    double eps_;                         ///< plane tolerance [unit]
    std::vector<Plane> planes_;          ///< per polygon
    std::vector<dvec3> lo_, hi_;         ///< per polygon, its bounds
    std::vector<std::uint32_t> first_;   ///< per polygon + 1: into cutters_
    std::vector<std::uint32_t> cutters_; ///< candidates, by polygon
};

} // namespace hemirad
