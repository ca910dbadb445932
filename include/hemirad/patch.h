// Patch addressing and patch geometry within one polygon's quadtree (paper 002 §2, §4.3).
//
// Level d of a polygon holds n*n patches, n = 2^d, indexed index = y*n + x on a grid of
// cells over the polygon's parameter domain (u along v0->v1, v along v0->v3 for quads,
// v0->v2 for triangles). This is the addressing the GPU patch-ID texture encodes.
//  - Quad: bilinear map P(u,v); patch (x,y) covers [x/n,(x+1)/n] x [y/n,(y+1)/n].
//  - Triangle: P(u,v) = v0 + u(v1-v0) + v(v2-v0), u,v >= 0, u+v <= 1. Cell (i,j) with
//    i+j <= n-1 holds the "upright" sub-triangle (lower-left half of the cell) at index
//    j*n+i; the "inverted" sub-triangle in the upper-right half of cell (i,j), i+j <= n-2,
//    is stored at the mirrored cell (n-1-i, n-1-j), whose i+j >= n. This is exactly
//    midpoint subdivision: every patch has four children at the next level.
#pragma once

#include <array>
#include <cstdint>

#include "hemirad/scene.h"
#include "hemirad/visibility.h"

namespace hemirad {

constexpr int kMaxDepth = 11; ///< deepest quadtree level (4^11 = 4.2M leaves per polygon)

struct PatchAddress {
    std::uint32_t polygon = 0;
    std::uint32_t level = 0;
    std::uint32_t index = 0; ///< within the level, y*n + x (see above)
    bool operator==(const PatchAddress& o) const {
        return polygon == o.polygon && level == o.level && index == o.index;
    }
};

/// Number of nodes in levels 0..level-1 of one quadtree: (4^level - 1)/3.
constexpr std::uint64_t level_offset(int level) {
    return ((std::uint64_t(1) << (2 * level)) - 1) / 3;
}
/// Nodes in a quadtree of depth `depth` (levels 0..depth).
constexpr std::uint64_t tree_size(int depth) {
    return level_offset(depth + 1);
}

/// The geometry of one patch (a sub-quad or sub-triangle of a polygon).
struct PatchGeometry {
    std::array<dvec3, 4> corners{}; ///< counter-clockwise like the polygon
    int count = 0;                  ///< 3 or 4
    dvec3 centre{0.0};              ///< parametric centre (quad) or centroid (triangle)
    double area = 0.0;              ///< exact area of the patch [unit^2]
};

/// Parametric coordinates of a patch's corners and centre (see header comment).
HEMIRAD_API PatchGeometry patch_geometry(const Polygon& polygon, std::uint32_t level,
                                         std::uint32_t index);

/// The centre alone of patch_geometry() (the same value, at a fifth of the cost).
HEMIRAD_API dvec3 patch_centre(const Polygon& polygon, std::uint32_t level, std::uint32_t index);

/// Maps parameter (u,v) to a point on the polygon (bilinear for quads, affine for triangles).
HEMIRAD_API dvec3 polygon_point(const Polygon& polygon, double u, double v);

/// The area of patch `index` of `level` (patch_geometry()'s, without its corners): a quad's
/// patches differ in area where the quad is no parallelogram; a triangle's are equal.
HEMIRAD_API double patch_area(const Polygon& polygon, std::uint32_t level, std::uint32_t index);

/// Index of the patch of `level` that contains parameter point (u,v) (clamped into range).
HEMIRAD_API std::uint32_t patch_at(const Polygon& polygon, std::uint32_t level, double u, double v);

/// Children of a patch at level+1 (always four), and its parent at level-1.
HEMIRAD_API std::array<std::uint32_t, 4> patch_children(bool triangle, std::uint32_t level,
                                                        std::uint32_t index);
HEMIRAD_API std::uint32_t patch_parent(bool triangle, std::uint32_t level, std::uint32_t index);

/// Patches of the same level sharing an edge with this one (up to 4; unused = UINT32_MAX).
HEMIRAD_API std::array<std::uint32_t, 4> patch_neighbours(bool triangle, std::uint32_t level,
                                                          std::uint32_t index);

/// Texture coordinates of parameter point (u, v) of polygon `polygon` (the same bilinear or
/// affine map as polygon_point()); the scene must have texcoords.
HEMIRAD_API glm::dvec2 polygon_texcoord(const Scene& scene, std::uint32_t polygon, double u,
                                        double v);

/// The reflectance of a patch, per channel: its material's rho, times, for a textured polygon,
/// the texture's mean over the patch (patch_reflectance.cpp): the patch is split into 8 x 8
/// equal-area parts (a quad's parameter cells, a triangle's midpoint sub-triangles), each
/// sampled at its centre from the mip level whose texels are about 1/8 of the patch's footprint
/// wide (the footprint's side: the square root of its area in level-0 texels), so a leaf
/// averages the box-filtered texture over its own footprint.
HEMIRAD_API dvec3 patch_reflectance(const Scene& scene, std::uint32_t polygon, std::uint32_t level,
                                    std::uint32_t index);
/// The reflectance at parameter point (u, v): rho times the level-0 texel there.
HEMIRAD_API dvec3 reflectance_at(const Scene& scene, std::uint32_t polygon, double u, double v);

/// Is `index` a valid patch of `level` (for triangles, every cell index is valid).
inline bool patch_valid(std::uint32_t level, std::uint32_t index) {
    return index < (std::uint32_t(1) << (2 * level));
}

} // namespace hemirad
