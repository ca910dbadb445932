// Patch addressing and geometry; see include/hemirad/patch.h for the layout.
#include "hemirad/patch.h"

#include "hemirad/error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hemirad {

namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

// A triangle patch as a cell (i,j) of the n x n grid plus which half of it.
struct TriCell {
    std::uint32_t i, j;
    bool inverted; // upper-right half of the cell
};

TriCell tri_cell(std::uint32_t n, std::uint32_t index) {
    const std::uint32_t x = index % n, y = index / n;
    if (x + y <= n - 1) return {x, y, false};
    return {n - 1 - x, n - 1 - y, true};
}

std::uint32_t tri_index(std::uint32_t n, TriCell c) {
    return c.inverted ? (n - 1 - c.j) * n + (n - 1 - c.i) : c.j * n + c.i;
}

} // namespace

dvec3 polygon_point(const Polygon& p, double u, double v) {
    if (p.is_triangle()) return p.v[0] + u * (p.v[1] - p.v[0]) + v * (p.v[2] - p.v[0]);
    return (1 - u) * (1 - v) * p.v[0] + u * (1 - v) * p.v[1] + u * v * p.v[2] +
           (1 - u) * v * p.v[3];
}

namespace {

// The corners of sub-triangle `index` of level `level` of triangle p, counter-clockwise like p
// (patch_geometry() and patch_centre() take them from here).
void tri_corners(const Polygon& p, std::uint32_t level, std::uint32_t index, dvec3* corners) {
    const std::uint32_t n = 1u << level;
    const double h = 1.0 / n;
    const TriCell c = tri_cell(n, index);
    const double u0 = c.i * h, v0 = c.j * h;
    if (!c.inverted) {
        corners[0] = polygon_point(p, u0, v0);
        corners[1] = polygon_point(p, u0 + h, v0);
        corners[2] = polygon_point(p, u0, v0 + h);
    } else {
        corners[0] = polygon_point(p, u0 + h, v0 + h);
        corners[1] = polygon_point(p, u0, v0 + h);
        corners[2] = polygon_point(p, u0 + h, v0);
    }
}

} // namespace

PatchGeometry patch_geometry(const Polygon& p, std::uint32_t level, std::uint32_t index) {
    const std::uint32_t n = 1u << level;
    const double h = 1.0 / n;
    PatchGeometry g;
    if (p.is_triangle()) {
        g.count = 3;
        tri_corners(p, level, index, g.corners.data());
        g.centre = (g.corners[0] + g.corners[1] + g.corners[2]) / 3.0;
        g.area = p.area / double(n) / double(n);
        return g;
    }
    const std::uint32_t x = index % n, y = index / n;
    const double u0 = x * h, v0 = y * h;
    g.count = 4;
    g.corners[0] = polygon_point(p, u0, v0);
    g.corners[1] = polygon_point(p, u0 + h, v0);
    g.corners[2] = polygon_point(p, u0 + h, v0 + h);
    g.corners[3] = polygon_point(p, u0, v0 + h);
    g.centre = polygon_point(p, u0 + 0.5 * h, v0 + 0.5 * h);
    g.area = patch_area(p, level, index);
    return g;
}

double patch_area(const Polygon& p, std::uint32_t level, std::uint32_t index) {
    const std::uint32_t n = 1u << level;
    const double h = 1.0 / n;
    if (p.is_triangle()) return p.area / double(n) / double(n);
    // For a planar quad the Jacobian |dP/du x dP/dv| is affine in (u,v), so its value at the
    // patch centre times the parameter area is the exact area (and areas add up exactly).
    const double uc = (index % n + 0.5) * h, vc = (index / n + 0.5) * h;
    const dvec3 du = (1 - vc) * (p.v[1] - p.v[0]) + vc * (p.v[2] - p.v[3]);
    const dvec3 dv = (1 - uc) * (p.v[3] - p.v[0]) + uc * (p.v[2] - p.v[1]);
    return glm::length(glm::cross(du, dv)) * h * h;
}

dvec3 patch_centre(const Polygon& p, std::uint32_t level, std::uint32_t index) {
    const std::uint32_t n = 1u << level;
    const double h = 1.0 / n;
    if (p.is_triangle()) {
        dvec3 c[3];
        tri_corners(p, level, index, c);
        return (c[0] + c[1] + c[2]) / 3.0;
    }
    const std::uint32_t x = index % n, y = index / n;
    return polygon_point(p, x * h + 0.5 * h, y * h + 0.5 * h);
}

std::uint32_t patch_at(const Polygon& p, std::uint32_t level, double u, double v) {
    const std::uint32_t n = 1u << level;
    u = std::clamp(u, 0.0, 1.0);
    v = std::clamp(v, 0.0, 1.0);
    const auto cell = [n](double t) {
        return std::min<std::uint32_t>(n - 1, std::uint32_t(t * n));
    };
    if (!p.is_triangle()) return cell(v) * n + cell(u);
    if (u + v > 1.0) {
        const double s = u + v;
        u /= s;
        v /= s;
    }
    std::uint32_t i = cell(u), j = cell(v);
    if (i + j > n - 1) { // on the hypotenuse, numerically outside
        if (i > 0)
            --i;
        else
            --j;
    }
    const double fu = u * n - i, fv = v * n - j;
    const bool inverted = fu + fv > 1.0 && i + j <= n - 2;
    return tri_index(n, {i, j, inverted});
}

std::array<std::uint32_t, 4> patch_children(bool triangle, std::uint32_t level,
                                            std::uint32_t index) {
    const std::uint32_t n = 1u << level, m = 2 * n;
    if (!triangle) {
        const std::uint32_t x = index % n, y = index / n;
        return {(2 * y) * m + 2 * x, (2 * y) * m + 2 * x + 1, (2 * y + 1) * m + 2 * x,
                (2 * y + 1) * m + 2 * x + 1};
    }
    const TriCell c = tri_cell(n, index);
    const std::uint32_t i = 2 * c.i, j = 2 * c.j;
    if (!c.inverted)
        return {tri_index(m, {i, j, false}), tri_index(m, {i + 1, j, false}),
                tri_index(m, {i, j + 1, false}), tri_index(m, {i, j, true})};
    return {tri_index(m, {i + 1, j, true}), tri_index(m, {i, j + 1, true}),
            tri_index(m, {i + 1, j + 1, true}), tri_index(m, {i + 1, j + 1, false})};
}

std::uint32_t patch_parent(bool triangle, std::uint32_t level, std::uint32_t index) {
    HEMIRAD_CHECK(level > 0);
    const std::uint32_t n = 1u << level, np = n / 2;
    if (!triangle) {
        const std::uint32_t x = index % n, y = index / n;
        return (y / 2) * np + x / 2;
    }
    const TriCell c = tri_cell(n, index);
    const std::uint32_t pi = c.i / 2, pj = c.j / 2;
    const std::uint32_t li = c.i % 2, lj = c.j % 2;
    // Upright children of an upright parent sit at local (0,0),(1,0),(0,1); the inverted
    // child of an upright parent sits at (0,0). The inverted parent's children are the
    // inverted ones at (1,0),(0,1),(1,1) and the upright one at (1,1).
    bool parent_inverted;
    if (!c.inverted)
        parent_inverted = (li == 1 && lj == 1);
    else
        parent_inverted = !(li == 0 && lj == 0);
    return tri_index(np, {pi, pj, parent_inverted});
}

std::array<std::uint32_t, 4> patch_neighbours(bool triangle, std::uint32_t level,
                                              std::uint32_t index) {
    const std::uint32_t n = 1u << level;
    std::array<std::uint32_t, 4> out{kNone, kNone, kNone, kNone};
    if (!triangle) {
        const std::uint32_t x = index % n, y = index / n;
        if (x > 0) out[0] = index - 1;
        if (x + 1 < n) out[1] = index + 1;
        if (y > 0) out[2] = index - n;
        if (y + 1 < n) out[3] = index + n;
        return out;
    }
    const TriCell c = tri_cell(n, index);
    if (!c.inverted) {
        // Upright (i,j): inverted (i,j) across the diagonal, inverted (i-1,j) on the left,
        // inverted (i,j-1) below.
        if (c.i + c.j <= n - 2) out[0] = tri_index(n, {c.i, c.j, true});
        if (c.i > 0) out[1] = tri_index(n, {c.i - 1, c.j, true});
        if (c.j > 0) out[2] = tri_index(n, {c.i, c.j - 1, true});
    } else {
        out[0] = tri_index(n, {c.i, c.j, false});
        out[1] = tri_index(n, {c.i + 1, c.j, false});
        out[2] = tri_index(n, {c.i, c.j + 1, false});
    }
    return out;
}

} // namespace hemirad
