// hemirad-view's pick: the surface under a window pixel and the illuminance there, by the final
// gather that `hemirad solve --probes` uses (report.h evaluate_probes, gather.h), so that the two
// agree at the same point.
#pragma once

#include <memory>
#include <string>

#include "ff/bvh.h"
#include "hemirad/hierarchy.h"
#include "hemirad/scene.h"

namespace hemirad {
class FinalGather;
}

namespace hemirad::view {

struct PickResult {
    bool hit = false;                 ///< the ray met the front of a polygon
    dvec3 position{0.0}, normal{0.0}; ///< the point [scene units] and its polygon's normal
    std::string group;                ///< surface group of the polygon
    dvec3 E{0.0};                     ///< irradiance, RGB [W unit^-2]
    double luminance() const;         ///< Rec. 709 luminance of E [W unit^-2]
    double lux() const;               ///< 683 lm/W times luminance() (scene in metres)
};

class Picker {
  public:
    explicit Picker(const Scene& scene);
    ~Picker();
    Picker(const Picker&) = delete;
    Picker& operator=(const Picker&) = delete;
    /// The camera ray through the centre of pixel (x, y) of a width x height window (origin
    /// top left; the renderer's perspective), its nearest hit, and the final gather there.
    /// `h` must be push-pulled (Solver::solution()).
    PickResult pick(const Hierarchy& h, const Camera& camera, int width, int height, int x,
                    int y) const;

  private:
    Bvh bvh_;
    /// The final gather of the last hierarchy picked on (it reads the hierarchy live, and its
    /// BVH and emitter list are the scene's): built on the first pick, again for another one.
    mutable std::unique_ptr<FinalGather> gather_;
    mutable const Hierarchy* gathered_ = nullptr;
};

/// The script's output line: "pick X Y: x y z nx ny nz GROUP E lx" (lux) or "... E W/unit^2";
/// "pick X Y: none" where the ray meets no surface's front.
std::string pick_line(int x, int y, const PickResult& r, bool lux);

} // namespace hemirad::view
