// How much of a shooter's view changes across its area (hemicube.h, parallax_fraction): the
// criterion that decides whether one hemicube at the centre is good enough for a shooter.
#include <algorithm>
#include <cmath>
#include <limits>

#include "gpu/hemicube.h"

namespace hemirad::gpu {

dvec3 hemicube_direction(const HemicubeLayout& L, const HemicubeFrame& f, int face, int i, int j) {
    const double d = 2.0 / L.res;
    const double x = -1 + (i + 0.5) * d;
    const double y = face == 0 ? -1 + (j + 0.5) * d : (j + 0.5) * d;
    const dvec3 screen_x = glm::cross(f.dir[face], f.up[face]);
    return glm::normalize(f.dir[face] + x * screen_x + y * f.up[face]);
}

double parallax_fraction(const Scene& scene, const Shooter& shooter, const HemicubeLayout& L,
                         const float* rgba, int stride) {
    constexpr double kJump = 1.25; // t_far / t_near above this is a silhouette
    constexpr double kInf = std::numeric_limits<double>::infinity();
    const HemicubeFrame frame = hemicube_frame(shooter);
    const dvec3& eye = shooter.geometry.centre;
    const double half = 0.5 * std::sqrt(shooter.geometry.area);
    // A stride s reads the image as one of res / s: every s-th pixel of every s-th row
    // stands for its s x s block.
    const int s = std::max(stride, 1);
    const double block = double(s) * s;
    const double cap = 0.25 * L.res / s;
    double total = 0;
    for (int f = 0; f < 5; ++f) {
        const HemicubeLayout::Face& face = L.faces[f];
        const int w = face.w / s, h = face.h / s; // samples across and up the face
        const auto pixel_i = [s](int k) { return k * s + s / 2; };
        // Distance along each sample's ray to the plane of the polygon it shows (inf: none).
        std::vector<double> t(std::size_t(w) * h);
        for (int j = 0; j < h; ++j)
            for (int i = 0; i < w; ++i) {
                const int pi = pixel_i(i), pj = pixel_i(j);
                const std::size_t px = std::size_t(face.y + pj) * L.width + face.x + pi;
                const float id = rgba[4 * px + 2];
                double& dist = t[std::size_t(j) * w + i];
                dist = kInf;
                if (id > -0.5f && id < 0.5f) continue;
                const Polygon& q = scene.polygons[std::uint32_t(std::abs(id)) - 1];
                const dvec3 dir = hemicube_direction(L, frame, f, pi, pj);
                const double along = glm::dot(dir, q.normal);
                if (along != 0) dist = std::max(glm::dot(q.v[0] - eye, q.normal) / along, 0.0);
            }
        const double pixel = 2.0 / L.res; // pixel side at unit distance along the face axis
        const auto pair = [&](int i0, int j0, int i1, int j1) {
            double a = t[std::size_t(j0) * w + i0], b = t[std::size_t(j1) * w + i1];
            int fi = pixel_i(i1), fj = pixel_i(j1); // the far sample
            if (a > b) std::swap(a, b), fi = pixel_i(i0), fj = pixel_i(j0);
            if (!(b > kJump * a) || a == kInf) return;
            const double shift = half * (1.0 / a - (b == kInf ? 0.0 : 1.0 / b));
            // Angular size of the far sample: its side over its distance from the eye on the
            // unit-distance face plane, foreshortened (|d|^-1.5 between |d|^-1 and |d|^-2).
            const double x = -1 + (fi + 0.5) * pixel;
            const double y = f == 0 ? -1 + (fj + 0.5) * pixel : (fj + 0.5) * pixel;
            const double len = std::sqrt(1 + x * x + y * y);
            const double angle = s * pixel / std::pow(len, 1.5);
            const std::size_t px = std::size_t(face.y + fj) * L.width + face.x + fi;
            total += block * double(L.delta_ff[px]) * std::min(shift / angle, cap);
        };
        for (int j = 0; j < h; ++j)
            for (int i = 0; i < w; ++i) {
                if (i + 1 < w) pair(i, j, i + 1, j);
                if (j + 1 < h) pair(i, j, i, j + 1);
            }
    }
    return total;
}

namespace {

// Calls visit(w) with each looked-at pixel's weight (its delta form factor times the block it
// stands for) where it shows the front of a polygon nearer than `distance` along its ray;
// stops when visit returns false.
template <class Visit>
void visit_near_pixels(const Scene& scene, const Shooter& shooter, const HemicubeLayout& L,
                       const float* rgba, double distance, int stride, Visit&& visit) {
    const HemicubeFrame frame = hemicube_frame(shooter);
    const dvec3& eye = shooter.geometry.centre;
    const int s = std::max(stride, 1);
    const double block = double(s) * s;
    for (int f = 0; f < 5; ++f) {
        const HemicubeLayout::Face& face = L.faces[f];
        for (int j = s / 2; j < face.h; j += s)
            for (int i = s / 2; i < face.w; i += s) {
                const std::size_t px = std::size_t(face.y + j) * L.width + face.x + i;
                const float id = rgba[4 * px + 2];
                if (id < 0.5f) continue; // nothing, or a back (counted apart)
                const Polygon& q = scene.polygons[std::uint32_t(id) - 1];
                const dvec3 dir = hemicube_direction(L, frame, f, i, j);
                const double along = glm::dot(dir, q.normal);
                if (along == 0) continue;
                const double t = glm::dot(q.v[0] - eye, q.normal) / along;
                if (t > 0 && t < distance && !visit(block * double(L.delta_ff[px]))) return;
            }
    }
}

} // namespace

double near_fraction(const Scene& scene, const Shooter& shooter, const HemicubeLayout& L,
                     const float* rgba, double distance, int stride) {
    double total = 0;
    visit_near_pixels(scene, shooter, L, rgba, distance, stride, [&](double w) {
        total += w;
        return true;
    });
    return total;
}

bool shows_within(const Scene& scene, const Shooter& shooter, const HemicubeLayout& L,
                  const float* rgba, double distance) {
    bool any = false;
    visit_near_pixels(scene, shooter, L, rgba, distance, 1, [&](double) {
        any = true;
        return false;
    });
    return any;
}

} // namespace hemirad::gpu
