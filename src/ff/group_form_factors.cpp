#include "core/timer.h"
#include "hemirad/provider.h"

namespace hemirad {

GroupFormFactors group_form_factors(const Scene& scene, const Discretisation& disc,
                                    FormFactorProvider& provider, std::uint32_t group) {
    const Stopwatch timer;
    GroupFormFactors r;
    r.to.assign(scene.groups.size(), 0.0);
    double area_from = 0;
    std::vector<Link> links;
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p) {
        const Polygon& poly = scene.polygons[p];
        if (poly.group != group) continue;
        area_from += poly.area;
        const std::uint32_t level = disc.depth[p];
        for (std::uint32_t i = 0; i < (1u << (2 * level)); ++i) {
            Shooter s;
            s.address = {p, level, i};
            s.geometry = patch_geometry(poly, level, i);
            s.normal = poly.normal;
            s.unshot_power = 1;
            provider.shoot(s, links);
            ++r.shots;
            // A_s F(s -> j) = A_j F(j -> s), summed over the shooters of the group.
            for (const Link& l : links) {
                const PatchGeometry g = patch_geometry(scene.polygons[l.receiver.polygon],
                                                       l.receiver.level, l.receiver.index);
                r.to[scene.polygons[l.receiver.polygon].group] += double(l.ff) * g.area;
            }
        }
    }
    for (double& f : r.to) {
        f /= area_from;
        r.row_sum += f;
    }
    r.seconds = timer.seconds();
    return r;
}

} // namespace hemirad
