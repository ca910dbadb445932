// The GL side of the hemicube (paper 002 §2; Cohen & Greenberg 1985): five faces (one full,
// four half) rendered into regions of one RGBA32F framebuffer and read back in one call.
// The framebuffer holds, per pixel, the patch ID and the analytic form factor written by
// shaders/hemicube.frag. No solver state here: the provider turns pixels into links.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "gl/objects.h"
#include "hemirad/form_factors.h"
#include "hemirad/scene.h"

namespace hemirad::gpu {

/// Where the faces of a hemicube of resolution `res` (pixels per full face side, even) lie in
/// the framebuffer, and the delta form factor of every pixel (0 where no face is).
///   top face  (0, 0)      res x res        sides (res, 0), (res, res/2), (0, res), (res, res)
/// each res x res/2; the framebuffer region read back is 2res x 1.5res = 3 res^2 pixels.
struct HemicubeLayout {
    int res = 0;
    int width = 0, height = 0;
    struct Face {
        int x, y, w, h;
    };
    Face faces[5];
    /// Delta form factors per pixel, row 0 at the bottom (GL order): on the top face
    /// dA / (pi (x^2 + y^2 + 1)^2), on a side face z dA / (pi (y^2 + z^2 + 1)^2); sum 1.
    std::vector<float> delta_ff;
};
HemicubeLayout make_hemicube_layout(int res);

/// The hemicube's frame at a shooter: N its normal, T along its first edge, B = N x T. The
/// five faces look along N (up: B), T, -T, B, -B (up: N), in the layout's order.
struct HemicubeFrame {
    dvec3 N, T, B;
    dvec3 dir[5], up[5];
};
HemicubeFrame hemicube_frame(const Shooter& shooter);

/// The framebuffer pixel (index into the layout, row 0 at the bottom) that the direction d
/// (from the hemicube's centre) falls in, or -1 if d points below the shooter's plane.
long hemicube_pixel(const HemicubeLayout& layout, const HemicubeFrame& frame, const dvec3& d);

/// Unit direction from the hemicube's centre through the centre of pixel (i, j) of `face`
/// (pixel coordinates within the face, row 0 at the bottom).
dvec3 hemicube_direction(const HemicubeLayout& layout, const HemicubeFrame& frame, int face, int i,
                         int j);

/// Parallax fraction of a rendered hemicube: an estimate of the share of the shooter's form
/// factor whose visibility differs between the shooter's centre (where the hemicube sees from)
/// and the rest of its area. A silhouette, where neighbouring pixels show surfaces at distances
/// t_near < t_far (a jump of more than 25 %, or the void behind), moves by up to
/// w = (s/2) (1/t_near - 1/t_far) radians as the eye moves s/2 across a shooter of size
/// s = sqrt(area); the band of that width behind every silhouette pixel is counted with the
/// delta form factor of its pixels. Sum over the silhouette (each pixel pair once):
///   P = sum delta_ff(far pixel) * min(w / pixel angle, res/4).
/// Near 0 when nothing near the shooter hides anything (a corner of an empty room: surfaces
/// meet without jumps); near or above 1 when a large shooter sits beside a block. `rgba` is
/// the image read back (IDs as in FormFactorProvider::HemicubeImage).
/// With `stride` > 1 the image is read as one of res / stride pixels (near_fraction).
double parallax_fraction(const Scene& scene, const Shooter& shooter, const HemicubeLayout& layout,
                         const float* rgba, int stride = 1);
/// Share of a rendered hemicube (by delta form factor) that shows the front of a polygon
/// nearer than `distance` to the eye [scene units]. With `stride` > 1 only every stride-th
/// pixel of every stride-th row is looked at, standing for its stride x stride block (the
/// share of a coarser hemicube, for a fraction of the work).
double near_fraction(const Scene& scene, const Shooter& shooter, const HemicubeLayout& layout,
                     const float* rgba, double distance, int stride = 1);
/// Does any pixel of a rendered hemicube show the front of a polygon nearer than `distance`
/// to the eye? (Stops at the first.)
bool shows_within(const Scene& scene, const Shooter& shooter, const HemicubeLayout& layout,
                  const float* rgba, double distance);

class HemicubeRenderer {
  public:
    /// Uploads the scene's polygons and the patch-ID mip texture (depth = max of `disc`).
    /// Needs a current GL 4.5 context.
    HemicubeRenderer(const Scene& scene, const Discretisation& disc, int max_resolution);

    /// Renders the hemicube at the shooter's centre along its normal. Polygons wholly behind
    /// the shooter's plane, and the shooter's own polygon, are not drawn; per face, polygons
    /// outside the face's frustum are skipped on the CPU, first by clusters of consecutive
    /// polygons (their bounding box wholly in or wholly out), then one by one; consecutive
    /// polygons drawn become one range of the multi-draw.
    /// angle_method: 0 the arccos table, 1 GLSL acos, 2 GLSL atan (hemicube.frag).
    void render(const Shooter& shooter, const HemicubeLayout& layout, double lod_bias,
                int angle_method);
    /// The same hemicube with the polygon channel alone (B as in render(); R, G and A 0): what
    /// a view probe reads, without the patch-ID texture's lookups (llvmpipe, room402's probes
    /// at 64: 1.41 ms a render against 1.57).
    void render_polygon_ids(const Shooter& shooter, const HemicubeLayout& layout);
    /// Polygons that later render() calls do not draw (a cluster shooter's own polygons:
    /// they are where its light comes from, not in its way), until the next call; empty:
    /// none but the shooter's own polygon. With `fronts_drawn`, those of them whose front
    /// faces the eye are drawn all the same (a point cluster's polygons that see each other,
    /// as in a corner: without them its light would leave through the hole they leave).
    void set_hidden(const std::vector<std::uint32_t>& polygons, bool fronts_drawn = false);
    /// Reads the region of `layout` back: RGBA floats, row 0 at the bottom.
    void read_back(const HemicubeLayout& layout, std::vector<float>& rgba);

    int max_resolution() const { return max_res_; }
    std::size_t polygons_drawn() const { return drawn_; } ///< over the five faces, last render
    std::size_t draw_ranges() const { return ranges_; }   ///< multi-draw entries, last render
    double cull_seconds() const { return cull_seconds_; } ///< CPU culling, last render [s]

  private:
    const Scene* scene_;
    dvec3 origin_{0.0}; ///< scene centre: GL works in scene-local floats
    double near_ = 0;   ///< near plane distance [scene units]
    int max_res_ = 0;
    std::vector<GLint> first_;   ///< first vertex of each polygon in the vertex buffer
    std::vector<GLsizei> count_; ///< its vertex count (3 or 6)
    /// kClusterSize consecutive polygons and their bounding box, for culling.
    struct Cluster {
        std::uint32_t begin, end;
        dvec3 lo, hi;
    };
    static constexpr std::uint32_t kClusterSize = 64;
    /// Longest range of vertices that joining neighbouring ranges makes (draw_polygons()).
    static constexpr GLsizei kMaxDrawVertices = 192;
    std::vector<Cluster> clusters_;
    std::vector<std::uint32_t> near_first_; ///< clusters_ by distance from the eye, last render
    std::vector<double> cluster_distance_;  ///< of clusters_, squared, last render
    std::vector<std::uint32_t> hidden_;     ///< set_hidden(), sorted
    bool hidden_fronts_drawn_ = false;      ///< set_hidden()'s fronts_drawn
    std::vector<std::uint32_t> hidden_per_cluster_; ///< of clusters_, how many are hidden
    std::vector<std::uint8_t> twinned_cluster_;     ///< of clusters_, holds a two-sided polygon
    bool hidden(std::uint32_t polygon) const {
        return !hidden_.empty() && std::binary_search(hidden_.begin(), hidden_.end(), polygon);
    }
    double eps_ = 0; ///< 1e-9 x the scene's diagonal: "in front of a plane" [scene units]
    std::vector<GLint> draw_first_;
    std::vector<GLsizei> draw_count_;
    std::size_t drawn_ = 0, ranges_ = 0;
    double cull_seconds_ = 0;
    /// Adds polygons [begin, end) to the draw list, extending the last range if they follow it.
    void draw_polygons(std::uint32_t begin, std::uint32_t end);
    /// render() (polygons_only: render_polygon_ids()).
    void draw(const Shooter& shooter, const HemicubeLayout& layout, double lod_bias,
              int angle_method, bool polygons_only);
    gl::Buffer vertices_, polygons_, acos_table_;
    gl::VertexArray vao_;
    gl::Texture patch_ids_;
    /// A framebuffer of one layout's size (colour RGBA32F, depth 32F). Each layout draws into
    /// its own and clears the whole of it: llvmpipe's fast clear. A scissored clear of a
    /// coarse layout's corner of one large framebuffer took 1.25 ms (a 64² view probe's
    /// render 2.5 ms, of a 256² shot's 16 ms).
    std::vector<gl::FloatTarget> targets_;
    /// The framebuffer of `layout`'s size (its GL name), made on first use.
    GLuint target(const HemicubeLayout& layout);
    gl::Program program_;
};

} // namespace hemirad::gpu
