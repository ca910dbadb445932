// Exports of a solution for other tools: a mesh with per-vertex radiosity (PLY) and
// lightmaps (EXR atlases + OBJ meshes with UVs). Both read a push-pulled hierarchy
// (Solver::solution()); every file is written atomically.
//
// PLY (`--export-ply FILE`): binary little-endian PLY 1.0, the scene subdivided at leaf level.
//   element vertex: float x, y, z; float red, green, blue = radiosity B [W unit^-2], linear RGB
//   element face:   list uchar int vertex_indices (triangles)
// Vertices are shared within a polygon's leaf grid (not between polygons, so that a crease
// or a colour edge stays sharp); a vertex's value is the area-weighted average of B over the
// leaves that touch it. Each quad leaf is two triangles (corners 0-1-2, 0-2-3). Faces are
// counter-clockwise seen from the front, like the scene's polygons.
//
// Lightmaps (`--export-lightmaps DIR`): per surface group G,
//   DIR/G.exr  32-bit float RGB atlas of leaf radiosity B [W unit^-2], linear;
//   DIR/G.obj  the group's polygons (one `v`/`vt`/`vn` per corner) with UVs into the atlas,
//              `mtllib G.mtl`; DIR/G.mtl names G.exr as map_Kd.
// (G is the group name with characters other than A-Z a-z 0-9 _ - . replaced by '_'.)
// Layout: every polygon is a chart of n x n texels, n = 2^depth, one texel per leaf: texel
// (x0 + i, y0 + j) holds the leaf at parameter cell (i, j) (patch.h), so texel centres sit at
// the leaf centres (u, v) = ((i + 0.5)/n, (j + 0.5)/n). A triangle's cell (i, j), i + j <= n-1,
// holds the average of the (one or two) leaves in that cell; its texels with i + j >= n lie
// outside the triangle and are filled from the nearest texel on the diagonal. Around each
// chart is a border of kLightmapPadding (2) texels filled by clamp-to-edge dilation (copies of
// the chart's edge texels), so that bilinear filtering at a polygon's edge never reads black;
// texels outside every chart's border are 0. Charts (with borders) are packed in rows
// ("shelves"), largest first (ties in polygon order), into an atlas about as wide as the
// square root of their total area. A polygon corner at parameter (pu, pv) gets the texture
// coordinate s = (x0 + pu n)/W, t = 1 - (y0 + pv n)/H (W x H atlas; image row 0 is the top,
// OBJ's t = 0 is the bottom).
// Detail at discontinuities (default; render/discontinuity_field.h): a quad whose leaves
// straddle a shadow edge gets a chart of 4n x 4n texels, 4 x 4 per leaf; a texel of a flagged
// leaf holds B_leaf + rho (D(x) - D_leaf), the leaf's radiosity plus the direct light's
// detail at the texel centre x (D_leaf the leaf's mean direct light), so that the texels of a
// leaf still average about its B and the shadow edge is drawn at a quarter of a leaf.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "hemirad/hierarchy.h"
#include "hemirad/image.h"
#include "hemirad/visibility.h"

namespace hemirad {

/// The scene at leaf level, with per-vertex radiosity (what the PLY holds).
struct LeafMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> radiosity; ///< B per vertex, area-weighted over adjacent leaves
    std::vector<std::array<std::uint32_t, 3>> triangles;
};
HEMIRAD_API LeafMesh leaf_mesh(const Hierarchy& h);

/// The bytes of the PLY file for a leaf mesh.
HEMIRAD_API std::string ply_bytes(const LeafMesh& mesh);
/// Writes the PLY of the hierarchy's leaf mesh atomically. Throws RuntimeError naming `path`.
HEMIRAD_API void export_ply(const std::string& path, const Hierarchy& h);

inline constexpr int kLightmapPadding = 2; ///< border texels around each chart

struct LightmapChart {
    std::uint32_t polygon = 0;
    int x0 = 0, y0 = 0; ///< atlas texel of the chart's cell (0, 0), inside the border
    int n = 1;          ///< chart side in texels (leaves per side, times 4 with detail)
};

struct Lightmap {
    std::string group;
    ImageRGB atlas;
    std::vector<LightmapChart> charts; ///< in polygon order
    std::string obj, mtl;              ///< file contents
};

/// Builds the lightmap of surface group `group` (see the layout above); `stem` names the
/// files the OBJ refers to (stem.mtl, stem.exr).
/// With `detail` (discontinuities on), charts of polygons with flagged leaves are refined.
class DiscontinuityField;
HEMIRAD_API Lightmap build_lightmap(const Hierarchy& h, std::uint32_t group,
                                    const std::string& stem,
                                    const DiscontinuityField* detail = nullptr);

/// The file stem for a group name (unsafe characters replaced by '_'; "group" if empty).
HEMIRAD_API std::string lightmap_stem(const std::string& group);

/// Writes DIR/G.exr, DIR/G.obj and DIR/G.mtl for every surface group that has polygons,
/// creating DIR if needed. Returns the paths written. Throws RuntimeError naming the path.
/// `discontinuities`: refine the charts that straddle shadow edges (see the layout above).
HEMIRAD_API std::vector<std::string> export_lightmaps(const std::string& dir, const Hierarchy& h,
                                                      bool discontinuities = true);

} // namespace hemirad
