// Leaves that straddle a discontinuity of the direct light, and the detail inside them
// (render.h, resolve_discontinuities; the lightmaps of export.h). Internal header.
//
// A leaf whose irradiance differs from a neighbour's (one leaf-width away in u or v, on the
// same polygon) by more than 20 % of the larger, and by more than 1 % of the scene's
// 95th-percentile leaf, is flagged: a shadow edge, a contact line, a light's footprint. For
// the flagged leaves and their eight neighbours the leaf's mean direct light D_leaf (what its
// H holds) is the final gather's direct light at the centres of its 4 children. The detail
// at a point x of a flagged leaf is D(x) - D~(x): the direct light at the point (emitter
// cells, deterministic, every fine cell summed: smooth from point to point) less the same
// field as the leaves hold it, reconstructed like the renderer does (nodal averages, linear
// over each quad leaf's two triangles; a triangle leaf's own value) or, for piecewise
// constant texels, the leaf's own D_leaf.
#pragma once

#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include "hemirad/gather.h"
#include "hemirad/hierarchy.h"

namespace hemirad {

class DiscontinuityField {
  public:
    /// `h` push-pulled, outliving this object. Costs a few direct-light evaluations per
    /// flagged leaf and neighbour.
    explicit DiscontinuityField(const Hierarchy& h);

    std::size_t flagged_count() const { return flagged_.size(); }
    bool flagged(std::uint32_t polygon, std::uint32_t leaf) const {
        return flagged_.count(key(polygon, leaf)) != 0;
    }

    enum class Reconstruction { Smooth, Leaf };
    /// The detail D(x) - D~(x) at point x (parameters u, v) on polygon `polygon`, or false if
    /// the leaf there is not flagged. `index` makes the evaluation's stream (any number).
    bool detail(std::uint32_t polygon, double u, double v, const dvec3& x, std::uint64_t index,
                Reconstruction r, dvec3& out) const;

  private:
    static std::uint64_t key(std::uint32_t p, std::uint32_t leaf) {
        return (std::uint64_t(p) << 32) | leaf;
    }
    const Hierarchy* h_;
    std::unordered_map<std::uint64_t, char> flagged_;
    std::unordered_map<std::uint64_t, dvec3> mean_direct_; ///< flagged leaves and neighbours
    std::unique_ptr<FinalGather> point_;                   ///< D(x): every fine cell, centres
};

} // namespace hemirad
