// Per-patch reflectance of textured polygons: the texture's mean over a patch's footprint,
// through the texture's box-filtered mipmap (patch.h).
#include <cmath>

#include "hemirad/patch.h"

namespace hemirad {

namespace {

constexpr int kSamples = 8; ///< samples per side of a patch (kSamples^2 in all)

} // namespace

glm::dvec2 polygon_texcoord(const Scene& s, std::uint32_t polygon, double u, double v) {
    const TexCoords& t = s.texcoords[polygon];
    const glm::dvec2 t0(t[0]), t1(t[1]), t2(t[2]), t3(t[3]);
    if (s.polygons[polygon].is_triangle()) return t0 + u * (t1 - t0) + v * (t2 - t0);
    return (1 - u) * (1 - v) * t0 + u * (1 - v) * t1 + u * v * t2 + (1 - u) * v * t3;
}

dvec3 patch_reflectance(const Scene& s, std::uint32_t polygon, std::uint32_t level,
                        std::uint32_t index) {
    const Polygon& p = s.polygons[polygon];
    const dvec3& rho = s.material_of(p).rho;
    const Texture* tex = s.texture_of(polygon);
    if (!tex) return rho;
    const std::uint32_t n = 1u << level;
    const double h = 1.0 / n;
    const std::uint32_t x = index % n, y = index / n;
    // The patch's parameter corners: origin o and edge vectors a, b (a triangle's inverted
    // patch has negative edges), as patch_geometry() lays them out.
    glm::dvec2 o, a(h, 0.0), b(0.0, h);
    if (p.is_triangle() && x + y > n - 1) {
        o = glm::dvec2((n - x) * h, (n - y) * h); // cell (n-1-x, n-1-y), upper-right corner
        a = -a, b = -b;
    } else {
        o = glm::dvec2(x * h, y * h);
    }
    // Footprint in level-0 texels: |det| of the texture map's Jacobian times the parameter
    // area (a triangle's patch is half its cell).
    const auto st = [&](glm::dvec2 q) { return polygon_texcoord(s, polygon, q.x, q.y); };
    const glm::dvec2 c = o + 0.5 * (a + b);
    const glm::dvec2 ds = (st(c + 0.5 * a) - st(c - 0.5 * a)) * double(tex->width());
    const glm::dvec2 dt = (st(c + 0.5 * b) - st(c - 0.5 * b)) * double(tex->height());
    const double area = std::abs(ds.x * dt.y - ds.y * dt.x) * (p.is_triangle() ? 0.5 : 1.0);
    const int mip = tex->level_for(std::sqrt(area) / kSamples);
    glm::dvec3 sum(0.0);
    constexpr double k = 1.0 / kSamples;
    if (!p.is_triangle()) {
        // Quad: cell centres (equal parameter areas; equal areas for a parallelogram).
        for (int j = 0; j < kSamples; ++j)
            for (int i = 0; i < kSamples; ++i)
                sum += glm::dvec3(tex->fetch(mip, st(o + (i + 0.5) * k * a + (j + 0.5) * k * b)));
    } else {
        // Triangle: centroids of its kSamples^2 equal sub-triangles (midpoint subdivision):
        // upright (i + 1/3, j + 1/3), i + j <= S-1, and inverted (i + 2/3, j + 2/3), i + j <= S-2.
        for (int j = 0; j < kSamples; ++j)
            for (int i = 0; i + j < kSamples; ++i) {
                sum += glm::dvec3(
                    tex->fetch(mip, st(o + (i + 1.0 / 3) * k * a + (j + 1.0 / 3) * k * b)));
                if (i + j <= kSamples - 2)
                    sum += glm::dvec3(
                        tex->fetch(mip, st(o + (i + 2.0 / 3) * k * a + (j + 2.0 / 3) * k * b)));
            }
    }
    return rho * sum / double(kSamples * kSamples);
}

dvec3 reflectance_at(const Scene& s, std::uint32_t polygon, double u, double v) {
    const dvec3& rho = s.material_of(s.polygons[polygon]).rho;
    const Texture* tex = s.texture_of(polygon);
    if (!tex) return rho;
    return rho * glm::dvec3(tex->fetch(0, polygon_texcoord(s, polygon, u, v)));
}

} // namespace hemirad
