// Visibility read from a rendered hemicube's patch IDs (hemicube_visibility.h).
#include "gpu/hemicube_visibility.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <numeric>
#include <tuple>
#include <vector>

#include "core/parallel.h"
#include "gpu/pixel_runs.h"

namespace hemirad::gpu {

namespace {

// Is p (in q's plane) inside the convex polygon q, away from its edges by a small relative
// margin (a point on a shared edge is in neither polygon)?
bool inside(const Polygon& q, const dvec3& p) {
    for (int k = 0; k < q.count; ++k) {
        const dvec3& a = q.v[k];
        const dvec3 e = q.v[(k + 1) % q.count] - a;
        if (glm::dot(glm::cross(e, p - a), q.normal) <= 1e-7 * glm::dot(e, e)) return false;
    }
    return true;
}

// Ray parameter (in units of u, from `from`) where the ray meets q's plane, or -1.
double plane_hit(const Polygon& q, const dvec3& from, const dvec3& u) {
    const double denom = glm::dot(u, q.normal);
    if (denom == 0) return -1;
    return glm::dot(q.v[0] - from, q.normal) / denom;
}

// Is p (in q's plane) inside q or within `tol` of it?
bool within(const Polygon& q, const dvec3& p, double tol) {
    for (int k = 0; k < q.count; ++k) {
        const dvec3& a = q.v[k];
        const dvec3 e = q.v[(k + 1) % q.count] - a;
        if (glm::dot(glm::cross(e, p - a), q.normal) < -tol * glm::length(e)) return false;
    }
    return true;
}

// Can the segment from `eye` to a point within `slack` of x0 = eye + d0 (x0 and the point in
// P's plane) cross Q's plane before its end (at a parameter in (0, 1 - 1e-6))? A cheap
// test before fill_cracks' exact one, which moves x0 by less than slack within P's plane:
// that moves the segment's end across Q's plane by at most slack times the sine between the
// planes. False where no such point can: most neighbours (coplanar pieces, a wall standing
// behind a floor pixel).
bool may_cross_before(const Polygon& P, const Polygon& Q, const dvec3& eye, const dvec3& d0,
                      double slack) {
    const double c = glm::dot(P.normal, Q.normal);
    const double reach = slack * std::sqrt(std::max(0.0, 1 - c * c));
    const double num = glm::dot(Q.v[0] - eye, Q.normal); // the crossing is at num / den
    const double den = glm::dot(d0, Q.normal);           // den within reach of this
    if (std::abs(den) <= reach) return true;             // den may be 0 or change sign
    const double limit = 1 - 1e-6;
    // (Rounding: the exact test computes the same quantities another way; these margins
    // are many orders of magnitude above it.)
    if (den > 0) return num > 0 && num < limit * (den + reach) * (1 + 1e-9);
    return num < 0 && num > limit * (den - reach) * (1 + 1e-9);
}

// The polygon pixel `at` of a hemicube image shows (front or back), or -1 for nothing.
long shown_polygon(const float* rgba, std::size_t at) {
    const float id = rgba[4 * at + 2];
    if (id > -0.5f && id < 0.5f) return -1;
    return long(std::abs(id) + 0.5f) - 1; // (IDs are whole numbers: no lround needed)
}

// Direction (not normalised) through point (i + di, j + dj) of face f's pixels, (0.5, 0.5)
// being pixel (i, j)'s centre.
dvec3 pixel_ray(const HemicubeLayout& L, const HemicubeFrame& frame, int f, int i, int j,
                double di = 0.5, double dj = 0.5) {
    const double d = 2.0 / L.res; // pixel side at unit distance along the face axis
    const double x = -1 + (i + di) * d;
    const double y = f == 0 ? -1 + (j + dj) * d : (j + dj) * d;
    const dvec3 screen_x = glm::cross(frame.dir[f], frame.up[f]);
    return frame.dir[f] + x * screen_x + y * frame.up[f];
}

} // namespace

std::size_t fill_cracks(const Scene& scene, const HemicubeLayout& L, const HemicubeFrame& frame,
                        float* rgba, const dvec3& eye, std::vector<float>& ids) {
    const double pixel = 2.0 / L.res; // pixel side at unit distance along the face axis
    ids.resize(std::size_t(L.width) * std::size_t(L.height));
    // The faces are apart in the image and a pixel takes only its own face's values: each
    // face on its own thread gives what one thread would.
    std::array<std::size_t, 5> filled_in{};
    parallel_for(5, face_threads(L), [&](std::size_t face_index) {
        const int f = int(face_index);
        std::size_t& filled = filled_in[face_index];
        const HemicubeLayout::Face& face = L.faces[f];
        const auto at = [&](int i, int j) {
            return std::size_t(face.y + j) * std::size_t(L.width) + std::size_t(face.x + i);
        };
        // The IDs apart, 4 bytes a pixel: the searches compare neighbours' IDs in a quarter
        // of the memory, 64 at a time. A row's are taken as the row below it is searched.
        const auto copy_row = [&](int j) {
            for (int i = 0; i < face.w; ++i) ids[at(i, j)] = rgba[4 * at(i, j) + 2];
        };
        // Pixel a = (i, j) shows P, its neighbour b shows Q: if the ray to the point a shows,
        // nudged a hundredth of a pixel into P, crosses Q (a ray that meets P on an edge
        // shared with nearer polygons, a face meeting the floor from below hit on the meeting
        // line, shows what lies just beside it), a takes b's value.
        const auto fill = [&](std::size_t a, int i, int j, std::size_t b) {
            const long p = shown_polygon(rgba, a), q = shown_polygon(rgba, b);
            if (p < 0 || q < 0 || p == q) return false;
            const dvec3 u = pixel_ray(L, frame, f, i, j);
            const Polygon& P = scene.polygons[std::size_t(p)];
            const double tp = plane_hit(P, eye, u);
            if (!(tp > 0)) return false;
            const double tol = 0.01 * pixel * tp * glm::length(u);
            const Polygon& Q = scene.polygons[std::size_t(q)];
            if (!may_cross_before(P, Q, eye, tp * u, 2 * tol)) return false;
            dvec3 x = eye + tp * u;
            const dvec3 inward = P.centroid() - x;
            const double l = glm::length(inward);
            if (l > tol) x += inward * (tol / l);
            const dvec3 d = x - eye;
            const double tq = plane_hit(Q, eye, d);
            if (!(tq > 0 && tq < 1 - 1e-6) || !within(Q, eye + tq * d, tol)) return false;
            for (int c = 0; c < 4; ++c) rgba[4 * a + c] = rgba[4 * b + c];
            ids[a] = ids[b];
            ++filled;
            return true;
        };
        // Pixel by pixel, each with its right neighbour, then the one above; a filled pixel
        // changes the IDs that the pairs after it compare, so the block's are compared again.
        if (face.h > 0) copy_row(0);
        for (int j = 0; j < face.h; ++j) {
            const bool top = j + 1 == face.h;
            if (!top) copy_row(j + 1);
            const std::size_t row = at(0, j);
            for (int i0 = 0; i0 < face.w; i0 += 64) {
                const std::size_t a0 = row + std::size_t(i0);
                const std::size_t n = std::size_t(std::min(64, face.w - i0));
                const std::size_t n_right = n - (i0 + 64 >= face.w); // the row's last: none
                const auto masks = [&](std::size_t from) {
                    const std::uint64_t keep = ~std::uint64_t(0) << from;
                    return std::pair{unequal_ids(&ids[a0], &ids[a0 + 1], n_right) & keep,
                                     top ? 0 : unequal_ids(&ids[a0], &ids[a0 + L.width], n) & keep};
                };
                auto [right, up] = masks(0);
                while (right | up) {
                    const int k = std::countr_zero(right | up);
                    const std::uint64_t bit = std::uint64_t(1) << k;
                    const int i = i0 + k;
                    const std::size_t a = a0 + std::size_t(k);
                    const std::size_t b = a + std::size_t(L.width);
                    bool changed = false;
                    if (right & bit) changed = fill(a, i, j, a + 1) | fill(a + 1, i + 1, j, a);
                    // (a filled pixel has a new ID to compare with the one above)
                    if (changed ? !top && ids[a] != ids[b] : (up & bit) != 0)
                        changed |= fill(a, i, j, b) | fill(b, i, j + 1, a);
                    if (k == 63) break;
                    if (changed) {
                        std::tie(right, up) = masks(std::size_t(k) + 1);
                    } else {
                        right &= ~(bit | (bit - 1));
                        up &= ~(bit | (bit - 1));
                    }
                }
            }
        }
    });
    return std::accumulate(filled_in.begin(), filled_in.end(), std::size_t(0));
}

bool segment_crosses(const Polygon& q, const dvec3& from, const dvec3& d) {
    const double t = plane_hit(q, from, d);
    if (!(t > 1e-9 && t < 1 - 1e-6)) return false;
    return inside(q, from + t * d);
}

HemicubeVisibility::HemicubeVisibility(const Scene& scene, const HemicubeLayout& layout,
                                       const HemicubeFrame& frame, const float* rgba,
                                       const dvec3& eye, const float* ids)
    : scene_(&scene), layout_(&layout), frame_(frame), rgba_(rgba), ids_(ids), eye_(eye) {}

long HemicubeVisibility::shown(std::size_t at) const {
    return shown_polygon(rgba_, at);
}

bool HemicubeVisibility::hides(int f, int i, int j, std::uint32_t p, int from_i, int from_j) const {
    const HemicubeLayout::Face& face = layout_->faces[f];
    const long q =
        shown(std::size_t(face.y + j) * std::size_t(layout_->width) + std::size_t(face.x + i));
    if (q < 0) return false; // nothing there: nothing hides p along that ray
    const Polygon& P = scene_->polygons[p];
    const Polygon& Q = scene_->polygons[std::size_t(q)];
    // Does ray u meet q's plane in front of p's (at tq, before tp)?
    double tp = 0, tq = 0;
    const auto in_front = [&](const dvec3& u) {
        tp = plane_hit(P, eye_, u);
        tq = plane_hit(Q, eye_, u);
        return tp > 0 && tq > 0 && tq < tp * (1 - 1e-6);
    };
    // Does q lie there within q, and p go on behind it? (The centre ray met q.)
    const auto behind = [&](const dvec3& u) {
        return in_front(u) && inside(Q, eye_ + tq * u) && inside(P, eye_ + tp * u);
    };
    const dvec3 u = pixel_ray(*layout_, frame_, f, i, j);
    if (!in_front(u)) return false;            // q is not in front of p
    if (inside(P, eye_ + tp * u)) return true; // p goes on there
    // Where p goes on behind q for less than a pixel, the centre ray misses it: rays near the
    // two corners on the side of the pixel that shows p too. (The office glb's PC case seen
    // past an LED bar 3.3 mm wide, 4 cm from the shooter: the part of the case behind the bar
    // was 0.7 pixel across at 64^2, its nodes, half hidden, were linked whole: rows up to
    // 1.0095; tests/hemicube_gl_test.cpp, SubPixelSilhouettes.)
    const double near = 0.05, far = 0.95;
    const double di = from_i < i ? near : far, dj = from_j < j ? near : far;
    if (from_i != i) // beside it: the corners on that side
        return behind(pixel_ray(*layout_, frame_, f, i, j, di, near)) ||
               behind(pixel_ray(*layout_, frame_, f, i, j, di, far));
    return behind(pixel_ray(*layout_, frame_, f, i, j, near, dj)) ||
           behind(pixel_ray(*layout_, frame_, f, i, j, far, dj));
}

bool HemicubeVisibility::visible(const dvec3& x, std::uint32_t own) const {
    const dvec3 d = x - eye_;
    const long pixel = hemicube_pixel(*layout_, frame_, d);
    if (pixel < 0) return false;
    return !crossed_around(pixel, own, d);
}

bool HemicubeVisibility::crossed_around(long pixel, std::uint32_t own, const dvec3& d) const {
    const long w = long(layout_->width);
    const long px = pixel % w, py = pixel / w;
    for (const HemicubeLayout::Face& f : layout_->faces) {
        if (px < f.x || px >= f.x + f.w || py < f.y || py >= f.y + f.h) continue;
        for (long y = std::max(py - 1, long(f.y)); y <= std::min(py + 1, long(f.y + f.h - 1)); ++y)
            for (long x_ = std::max(px - 1, long(f.x)); x_ <= std::min(px + 1, long(f.x + f.w - 1));
                 ++x_) {
                const long r = shown(std::size_t(y * w + x_));
                if (r >= 0 && std::uint32_t(r) != own &&
                    segment_crosses(scene_->polygons[std::size_t(r)], eye_, d))
                    return true;
            }
        break;
    }
    return false;
}

bool HemicubeVisibility::visible_in_depth_map(const dvec3& x, std::uint32_t own) const {
    const dvec3 d = x - eye_;
    const long pixel = hemicube_pixel(*layout_, frame_, d);
    if (pixel < 0) return false;
    const long q = shown(std::size_t(pixel));
    if (q >= 0 && std::uint32_t(q) == own) return true;
    if (q >= 0 && plane_hit(scene_->polygons[std::size_t(q)], eye_, d) < 1 - 1e-6) return false;
    // What the pixel shows may lie in x's plane (a neighbour of x's polygon, the two beyond
    // a nearer floor), or be nothing where x lies within a pixel of a silhouette (the pixel's
    // centre ray passing beside a panel that hides x: the office glb's desk panel hid the
    // inner face of its end 6 mm inside its edge from an LED bar 1.5 m away, and that face
    // was linked whole): x is also hidden by what the pixels around it show, if the segment
    // to x crosses it.
    return !crossed_around(pixel, own, d);
}

} // namespace hemirad::gpu
