#include "solver/matrix_solver.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "hemirad/error.h"

namespace hemirad {

MatrixSolution solve_matrix(const Scene& scene, const Discretisation& disc,
                            FormFactorProvider& provider, double tolerance, int max_iterations) {
    MatrixSolution s;
    std::vector<std::uint64_t> base(scene.polygons.size());
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p) {
        base[p] = s.leaves.size();
        const std::uint32_t level = disc.depth[p];
        for (std::uint32_t i = 0; i < (1u << (2 * level)); ++i) s.leaves.push_back({p, level, i});
    }
    const std::size_t n = s.leaves.size();
    const auto index_of = [&](const PatchAddress& a) {
        HEMIRAD_CHECK_EQ(a.level, std::uint32_t(disc.depth[a.polygon]));
        return base[a.polygon] + a.index;
    };
    // Rows: gather[j] = list of (i, F(j -> i)). Column i comes from shooting leaf i.
    std::vector<std::vector<std::pair<std::uint32_t, double>>> gather(n);
    provider.set_link_at_leaves(true);
    std::vector<Link> links;
    for (std::size_t i = 0; i < n; ++i) {
        const PatchAddress& a = s.leaves[i];
        const Polygon& poly = scene.polygons[a.polygon];
        Shooter sh;
        sh.address = a;
        sh.geometry = patch_geometry(poly, a.level, a.index);
        sh.normal = poly.normal;
        sh.unshot_power = 1;
        provider.shoot(sh, links);
        for (const Link& l : links)
            gather[index_of(l.receiver)].push_back({std::uint32_t(i), l.ff});
    }
    std::vector<dvec3> E(n), rho(n);
    for (std::size_t j = 0; j < n; ++j) {
        const Material& m = scene.material_of(scene.polygons[s.leaves[j].polygon]);
        E[j] = m.exitance();
        rho[j] = patch_reflectance(scene, s.leaves[j].polygon, s.leaves[j].level,
                                   s.leaves[j].index); // rho, times the texture's leaf mean
    }
    s.B = E;
    s.H.assign(n, dvec3(0.0));
    // Gauss-Seidel: converges since rho < 1 and every row sum of F is <= 1 (up to the
    // provider's error; paper 000 discusses what breaks when it is not).
    for (s.iterations = 1; s.iterations <= max_iterations; ++s.iterations) {
        double change = 0, scale = 0;
        for (std::size_t j = 0; j < n; ++j) {
            dvec3 h(0.0);
            for (const auto& [i, f] : gather[j]) h += f * s.B[i];
            const dvec3 b = E[j] + rho[j] * h;
            const dvec3 d = glm::abs(b - s.B[j]);
            change = std::max({change, d.x, d.y, d.z});
            scale = std::max({scale, b.x, b.y, b.z});
            s.B[j] = b;
            s.H[j] = h;
        }
        s.residual = scale > 0 ? change / scale : 0;
        if (s.residual <= tolerance) break;
    }
    provider.set_link_at_leaves(false);
    return s;
}

} // namespace hemirad
