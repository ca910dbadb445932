// Polygons that other polygons pass through, cut where they meet (scene.h,
// split_intersections). Models built by others are full of them: a floor that runs on under
// the walls, a jar sunk into a shelf, a laptop 4 mm into a desk. The part of such a polygon
// on the far side is inside the other object; as one polygon, its leaf patches straddle the
// two sides, take light on one and carry it into the other (a closed cavity lit from inside).
// Cut along the meeting line, each side is a polygon of its own, and the buried one is never
// seen by a shooter outside.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "hemirad/error.h"
#include "hemirad/patch.h"
#include "hemirad/readout.h"
#include "hemirad/scene.h"

namespace hemirad {

namespace {

/// A cut: the line through `point` along `dir` (unit) in a polygon's plane; the meeting
/// segment runs from `point` to point + length dir.
struct Cut {
    dvec3 point, dir;
    double length; ///< of the meeting segment within the polygon (the longest cuts are kept)
    /// Under a tenth of the polygon's size: it cuts only a piece that the meeting segment
    /// crosses from side to side (a post's footprint left as a strip by the cuts of its two
    /// long sides), not the whole polygon along its line.
    bool short_one = false;
};

struct Box {
    dvec3 lo{1e300}, hi{-1e300};
};

Box box_of(const Polygon& p) {
    Box b;
    for (int k = 0; k < p.count; ++k) {
        b.lo = glm::min(b.lo, p.v[k]);
        b.hi = glm::max(b.hi, p.v[k]);
    }
    return b;
}

double longest_edge(const Polygon& p) {
    double l = 0;
    for (int k = 0; k < p.count; ++k) l = std::max(l, glm::length(p.v[(k + 1) % p.count] - p.v[k]));
    return l;
}

// Where polygon q passes through the plane of polygon p, or stands on p's front with an edge
// in p's plane (a box on a floor, a wall under a ceiling that runs on over it), as a segment in
// p's interior (strictly inside, by `eps`). Returns false if they do not meet, or only on p's
// boundary or outside p.
bool meeting(const Polygon& p, const Polygon& q, double eps, Cut& cut) {
    if (std::abs(glm::dot(p.normal, q.normal)) > 1 - 1e-9) return false; // parallel planes
    double d[4];
    bool above = false, below = false;
    int on = 0;
    for (int k = 0; k < q.count; ++k) {
        d[k] = glm::dot(q.v[k] - p.v[0], p.normal);
        above |= d[k] > eps;
        below |= d[k] < -eps;
        on += std::abs(d[k]) <= eps ? 1 : 0;
    }
    const bool through = above && below, standing = above && !below && on >= 2;
    if (!through && !standing) return false; // q does not reach p's plane from its front
    // The points of q in p's plane: corners on it, edges across it.
    const dvec3 dir = glm::normalize(glm::cross(p.normal, q.normal));
    double s0 = 1e300, s1 = -1e300;
    dvec3 origin(0.0);
    bool have = false;
    const auto take = [&](const dvec3& x) {
        if (!have) origin = x, have = true;
        const double s = glm::dot(x - origin, dir);
        s0 = std::min(s0, s), s1 = std::max(s1, s);
    };
    for (int k = 0; k < q.count; ++k) {
        const int j = (k + 1) % q.count;
        if (std::abs(d[k]) <= eps) take(q.v[k]);
        if ((d[k] > eps && d[j] < -eps) || (d[k] < -eps && d[j] > eps))
            take(q.v[k] + (q.v[j] - q.v[k]) * (d[k] / (d[k] - d[j])));
    }
    if (!have || s1 - s0 <= eps) return false;
    // Clip the segment to p's interior, each edge's half plane shrunk by eps.
    for (int k = 0; k < p.count; ++k) {
        const dvec3& a = p.v[k];
        const dvec3 e = glm::normalize(p.v[(k + 1) % p.count] - a);
        const dvec3 inward = glm::cross(p.normal, e);
        // inside: dot(x - a, inward) > eps, with x = origin + s dir.
        const double c0 = glm::dot(origin - a, inward) - eps, c1 = glm::dot(dir, inward);
        if (std::abs(c1) < 1e-15) {
            if (c0 <= 0) return false;
            continue;
        }
        const double s = -c0 / c1;
        if (c1 > 0)
            s0 = std::max(s0, s);
        else
            s1 = std::min(s1, s);
        if (s1 - s0 <= eps) return false;
    }
    cut.point = origin + s0 * dir;
    cut.dir = dir;
    cut.length = s1 - s0;
    return true;
}

double area_of(const std::vector<dvec3>& c, const dvec3& n) {
    dvec3 s(0.0);
    for (std::size_t k = 0; k < c.size(); ++k) s += glm::cross(c[k], c[(k + 1) % c.size()]);
    return 0.5 * std::abs(glm::dot(s, n));
}

// Whether the meeting segment of a short cut crosses the convex piece `c` (in a plane of
// normal n) from side to side: the piece's chord along the cut's line lies within the segment,
// to a hundredth of the chord (the segment's ends are where the other polygon's sides meet
// this plane, the chord's where the cuts of those sides ended the piece).
bool crosses_piece(const std::vector<dvec3>& c, const dvec3& n, const Cut& cut) {
    const dvec3 side = glm::cross(cut.dir, n);
    double t0 = 1e300, t1 = -1e300;
    for (std::size_t k = 0; k < c.size(); ++k) {
        const std::size_t j = (k + 1) % c.size();
        const double dk = glm::dot(c[k] - cut.point, side), dj = glm::dot(c[j] - cut.point, side);
        if ((dk > 0 && dj < 0) || (dk < 0 && dj > 0)) {
            const double t = glm::dot(c[k] + (c[j] - c[k]) * (dk / (dk - dj)) - cut.point, cut.dir);
            t0 = std::min(t0, t), t1 = std::max(t1, t);
        }
    }
    const double chord = t1 - t0;
    if (!(chord > 0)) return false;
    const double slack = 0.01 * chord;
    return t0 >= -slack && t1 <= cut.length + slack;
}

// Splits the convex piece `c` (in a plane of normal n) by the line: the two sides, in order,
// when each keeps at least `min_share` of its area; else false (the piece stays whole).
bool split_piece(const std::vector<dvec3>& c, const dvec3& n, const Cut& cut, double min_share,
                 std::vector<dvec3>& a, std::vector<dvec3>& b) {
    const dvec3 side = glm::cross(cut.dir, n);
    std::vector<double> d(c.size());
    for (std::size_t k = 0; k < c.size(); ++k) d[k] = glm::dot(c[k] - cut.point, side);
    a.clear(), b.clear();
    for (std::size_t k = 0; k < c.size(); ++k) {
        const std::size_t j = (k + 1) % c.size();
        if (d[k] >= 0) a.push_back(c[k]);
        if (d[k] <= 0) b.push_back(c[k]);
        if ((d[k] > 0 && d[j] < 0) || (d[k] < 0 && d[j] > 0)) {
            const dvec3 x = c[k] + (c[j] - c[k]) * (d[k] / (d[k] - d[j]));
            a.push_back(x), b.push_back(x);
        }
    }
    if (a.size() < 3 || b.size() < 3) return false;
    const double whole = area_of(c, n);
    return area_of(a, n) >= min_share * whole && area_of(b, n) >= min_share * whole;
}

} // namespace

SplitStats split_intersections(Scene& scene) {
    SplitStats stats;
    const std::size_t n = scene.polygons.size();
    if (n < 2) return stats;
    const Bounds bounds = scene.bounds();
    const double eps = 1e-7 * std::max(bounds.diagonal(), 1e-300);
    // Candidate pairs: boxes that overlap, by a sweep along the scene's longest axis.
    const dvec3 ext = bounds.hi - bounds.lo;
    const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : ext.y >= ext.z ? 1 : 2;
    std::vector<Box> boxes(n);
    for (std::size_t i = 0; i < n; ++i) boxes[i] = box_of(scene.polygons[i]);
    std::vector<std::uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        return boxes[a].lo[axis] != boxes[b].lo[axis] ? boxes[a].lo[axis] < boxes[b].lo[axis]
                                                      : a < b;
    });
    std::vector<std::vector<Cut>> cuts(n);
    std::vector<std::uint32_t> active;
    const auto overlap = [&](const Box& a, const Box& b) {
        for (int k = 0; k < 3; ++k)
            if (a.hi[k] < b.lo[k] - eps || b.hi[k] < a.lo[k] - eps) return false;
        return true;
    };
    const auto consider = [&](std::uint32_t p, std::uint32_t q) {
        const Polygon& P = scene.polygons[p];
        Cut c;
        if (!meeting(P, scene.polygons[q], eps, c)) return;
        // Where another object's corner or thin edge barely enters, a cut along the whole
        // line would only add polygons: a meeting line of at least a tenth of the polygon's
        // size is cut so; a shorter one only where it crosses a piece (crosses_piece).
        const double tenth = 0.1 * longest_edge(P);
        c.short_one = c.length < tenth;
        for (Cut& o : cuts[p]) {
            // The same line already (a box's face and its neighbour, the two triangles of a
            // quad): where the segments meet or overlap they become one (a post's side made
            // of two triangles meets the floor in two pieces of one segment).
            const double along = glm::dot(o.dir, c.dir);
            if (std::abs(along) <= 1 - 1e-9 ||
                glm::length(glm::cross(c.point - o.point, o.dir)) > eps)
                continue;
            if (!o.short_one) return; // the whole line is cut already
            if (!c.short_one) {       // the whole line now
                o = c;
                return;
            }
            const double a = glm::dot(c.point - o.point, o.dir), b = a + c.length * along;
            const double lo = std::min(a, b), hi = std::max(a, b);
            if (lo > o.length + eps || hi < -eps) continue; // apart on the line
            const double from = std::min(0.0, lo), to = std::max(o.length, hi);
            o.point += from * o.dir;
            o.length = to - from;
            o.short_one = o.length < tenth;
            return;
        }
        cuts[p].push_back(c);
    };
    for (std::uint32_t i : order) {
        const double lo = boxes[i].lo[axis];
        std::size_t keep = 0;
        for (std::uint32_t a : active)
            if (boxes[a].hi[axis] >= lo - eps) active[keep++] = a;
        active.resize(keep);
        for (std::uint32_t a : active) {
            if (!overlap(boxes[a], boxes[i])) continue;
            consider(a, i);
            consider(i, a);
        }
        active.push_back(i);
    }
    // Cut, at most kMaxCuts whole lines a polygon (the longest meetings first), then short
    // ones, at most 2 kMaxCuts cuts in all.
    constexpr std::size_t kMaxCuts = 16;
    constexpr double kShortShare = 0.05;
    Scene out = scene;
    out.polygons.clear();
    out.texcoords.clear();
    const bool uv = !scene.texcoords.empty();
    for (std::uint32_t p = 0; p < n; ++p) {
        const Polygon& P = scene.polygons[p];
        HEMIRAD_CHECK(P.twin == kNoTwin); // cut before two-sided polygons are paired
        std::vector<Cut>& cs = cuts[p];
        std::vector<std::vector<dvec3>> pieces{{P.v.begin(), P.v.begin() + P.count}};
        if (!cs.empty()) {
            // Long cuts first (longest first), then short ones (longest first).
            std::sort(cs.begin(), cs.end(), [](const Cut& a, const Cut& b) {
                return a.short_one != b.short_one ? !a.short_one : a.length > b.length;
            });
            const auto first_short =
                std::find_if(cs.begin(), cs.end(), [](const Cut& c) { return c.short_one; });
            const std::size_t long_ones = std::size_t(first_short - cs.begin());
            if (long_ones > kMaxCuts) cs.erase(cs.begin() + kMaxCuts, first_short);
            if (cs.size() > 2 * kMaxCuts) cs.resize(2 * kMaxCuts);
            std::vector<dvec3> a, b;
            for (const Cut& c : cs) {
                std::vector<std::vector<dvec3>> next;
                for (const std::vector<dvec3>& piece : pieces) {
                    // A short cut leaves no sliver (a millimetre between a wall and the
                    // back of a desk's leg): each side keeps a twentieth of the piece.
                    if ((!c.short_one || crosses_piece(piece, P.normal, c)) &&
                        split_piece(piece, P.normal, c, c.short_one ? kShortShare : 1e-3, a, b)) {
                        next.push_back(a);
                        next.push_back(b);
                    } else {
                        next.push_back(piece);
                    }
                }
                pieces.swap(next);
            }
        }
        if (pieces.size() == 1) { // unchanged
            out.polygons.push_back(P);
            if (uv) out.texcoords.push_back(scene.texcoords[p]);
            continue;
        }
        ++stats.polygons_cut;
        for (const std::vector<dvec3>& piece : pieces) {
            std::vector<glm::dvec2> st;
            if (uv)
                for (const dvec3& x : piece) {
                    double u = 0, v = 0;
                    polygon_uv(P, x, u, v, 1e-3);
                    st.push_back(polygon_texcoord(scene, p, u, v));
                }
            const std::size_t before = out.polygons.size();
            add_polygon(out, piece, P.material, P.group, 1e-6, uv ? &st : nullptr);
            if (uv && out.texcoords.size() < out.polygons.size())
                out.texcoords.resize(out.polygons.size());
            stats.pieces += out.polygons.size() - before;
        }
    }
    scene = std::move(out);
    return stats;
}

} // namespace hemirad
