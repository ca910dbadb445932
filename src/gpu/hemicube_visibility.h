// Visibility read from a rendered hemicube (hemicube.h): the patch IDs it holds make it a
// shadow map of polygons. Used to link a receiver only where the shooter sees it: a node
// that a silhouette crosses is linked by the parts of it that are seen (solver issue: light
// must not reach what the shooter cannot see, and a form-factor row must not exceed 1).
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <vector>

#include "gpu/hemicube.h"
#include "gpu/pixel_runs.h"

namespace hemirad::gpu {

/// Does the open segment from `from` along `d` (t in (0, 1 - 1e-6), in units of d) cross the
/// polygon q (convex, its edges excluded by a relative margin)?
bool segment_crosses(const Polygon& q, const dvec3& from, const dvec3& d);

/// Threads for searches over a hemicube's five faces, one face a thread: all cores from faces of
/// 256 x 256 pixels up; one below, where starting the threads costs more than they save (the
/// Cornell box's adaptive 64..256 hemicubes: reduce 0.68-0.72 s over 905 shots on one thread,
/// 0.87-0.91 s on threads).
inline int face_threads(const HemicubeLayout& layout) {
    return layout.res >= 256 ? 0 : 1;
}

/// Pixels that show a polygon through a crack: rasterisation leaves gaps along T-junctions (a
/// corner of one polygon on the edge of another, as split_intersections makes them), where a
/// pixel's centre ray passes within rounding of the edge between two nearer polygons and shows
/// what lies behind them (a face below the floor, a room behind a wall). Such a pixel (its ray
/// meets the polygon a 4-neighbour shows, within a hundredth of a pixel of its edges, in front
/// of what it shows) takes that neighbour's value. A true silhouette is left alone: there the
/// ray passes beside the nearer polygon by a share of a pixel. Returns the pixels changed.
/// `ids` receives every pixel's ID (rgba's third channel) after the filling, 4 bytes a pixel,
/// for HemicubeVisibility's searches.
std::size_t fill_cracks(const Scene& scene, const HemicubeLayout& layout,
                        const HemicubeFrame& frame, float* rgba, const dvec3& eye,
                        std::vector<float>& ids);

class HemicubeVisibility {
  public:
    /// The hemicube `rgba` (IDs as in FormFactorProvider::HemicubeImage) rendered with
    /// `layout` from the shooter whose frame is `frame`, its eye at `eye`; `ids` holds rgba's
    /// third channel alone (as fill_cracks leaves it), where the searches compare neighbours.
    /// Keeps pointers: all must outlive this object.
    HemicubeVisibility(const Scene& scene, const HemicubeLayout& layout, const HemicubeFrame& frame,
                       const float* rgba, const dvec3& eye, const float* ids);

    /// Is point x, on polygon `own`, seen from the eye? It is unless the segment from the eye
    /// to x crosses a polygon other than `own` that the pixel its direction falls in, or one
    /// of the 8 around it, shows (x may lie within a pixel of the silhouette of what hides it,
    /// the pixel showing `own` or nothing). Points below the hemicube's plane are not seen.
    bool visible(const dvec3& x, std::uint32_t own) const;

    /// The same as a depth map would tell it, for a point whose polygon covers no pixel (it
    /// is smaller than one): x is hidden if the plane of what its pixel shows lies in front of
    /// it along its ray (the shown surface is taken to fill the pixel: a sub-pixel polygon
    /// behind a thin occluder is not seen through it); and it is hidden if the segment to x
    /// crosses a polygon shown in the 3 x 3 pixels around (what the pixel shows may lie in x's
    /// plane, beside the floor that hides x, or be nothing, x lying within a pixel of the
    /// silhouette of what hides it).
    bool visible_in_depth_map(const dvec3& x, std::uint32_t own) const;

    /// Calls mark(i) for every pixel i that shows the front of a polygon P next to a pixel
    /// (4-neighbour, same face) whose centre ray meets P (within P) behind what that pixel
    /// shows, or a ray near one of its two corners beside pixel i meets P behind that polygon
    /// (P goes on behind it for less than a pixel): P goes on behind an occluder there, so the
    /// node pixel i shows is partly hidden.
    template <class Mark> void occlusion_edges(Mark mark) const {
        for (int f = 0; f < 5; ++f) occlusion_edges(f, mark);
    }
    /// The same on face f alone (faces may be taken on threads of their own).
    template <class Mark> void occlusion_edges(int f, Mark mark) const;

  private:
    /// Does the segment from the eye along d cross a polygon other than `own` that one of
    /// the 3 x 3 pixels around `pixel` shows?
    bool crossed_around(long pixel, std::uint32_t own, const dvec3& d) const;
    /// The polygon pixel `at` shows (front or back), or -1 for nothing.
    long shown(std::size_t at) const;
    /// Does pixel (i, j) of face f show something in front of polygon p, where its centre ray
    /// meets p within p, or where a ray near one of its two corners beside pixel (from_i,
    /// from_j) (a 4-neighbour, which shows p) meets both within them?
    bool hides(int f, int i, int j, std::uint32_t p, int from_i, int from_j) const;

    const Scene* scene_;
    const HemicubeLayout* layout_;
    HemicubeFrame frame_;
    const float* rgba_;
    const float* ids_; ///< rgba_'s third channel apart
    dvec3 eye_;
};

template <class Mark> void HemicubeVisibility::occlusion_edges(int f, Mark mark) const {
    const HemicubeLayout& L = *layout_;
    const HemicubeLayout::Face& face = L.faces[f];
    const std::size_t width = std::size_t(L.width);
    const auto test = [&](std::size_t a, int i0, int j0, std::size_t b, int i1, int j1) {
        const long pa = shown(a), pb = shown(b);
        if (pa == pb) return;
        // Each way: a front of P at one pixel, something else at its neighbour.
        if (pa >= 0 && rgba_[4 * a + 2] > 0 && hides(f, i1, j1, std::uint32_t(pa), i0, j0)) mark(a);
        if (pb >= 0 && rgba_[4 * b + 2] > 0 && hides(f, i0, j0, std::uint32_t(pb), i1, j1)) mark(b);
    };
    // Neighbours with the same ID (the same polygon, same side) are passed over 64 at a time.
    for (int j = 0; j < face.h; ++j) {
        const std::size_t row = std::size_t(face.y + j) * width + std::size_t(face.x);
        for (int i0 = 0; i0 < face.w; i0 += 64) {
            const std::size_t n = std::size_t(std::min(64, face.w - i0));
            const std::size_t a0 = row + std::size_t(i0);
            const std::size_t n_right = n - (i0 + 64 >= face.w); // the row's last: none
            const std::uint64_t right = unequal_ids(ids_ + a0, ids_ + a0 + 1, n_right);
            const std::uint64_t up =
                j + 1 < face.h ? unequal_ids(ids_ + a0, ids_ + a0 + width, n) : 0;
            for (std::uint64_t m = right | up; m; m &= m - 1) {
                const int k = std::countr_zero(m);
                const int i = i0 + k;
                const std::size_t a = a0 + std::size_t(k);
                if (right >> k & 1) test(a, i, j, a + 1, i + 1, j);
                if (up >> k & 1) test(a, i, j, a + width, i, j + 1);
            }
        }
    }
}

} // namespace hemirad::gpu
