// Binned-SAH BVH over triangles and planar convex quads (see bvh.h).
#include "ff/bvh.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "hemirad/error.h"

namespace hemirad {

namespace {

constexpr int kBins = 12;
constexpr std::uint32_t kLeafSize = 4;

double half_area(const dvec3& lo, const dvec3& hi) {
    const dvec3 e = glm::max(hi - lo, dvec3(0.0));
    return e.x * e.y + e.y * e.z + e.z * e.x;
}

double cross2(double ax, double ay, double bx, double by) {
    return ax * by - ay * bx;
}

// Moller-Trumbore against the triangle v0, v0+ea, v0+eb: barycentrics (a, b) along ea, eb.
// Edges are included with a tolerance of 1e-12 so that rays through a shared edge do not leak.
bool ray_triangle(const dvec3& o, const dvec3& d, const dvec3& v0, const dvec3& ea, const dvec3& eb,
                  double tmin, double tmax, double& t, double& a, double& b) {
    constexpr double kEdge = 1e-12;
    const dvec3 pvec = glm::cross(d, eb);
    const double det = glm::dot(ea, pvec);
    if (det == 0.0 || !std::isfinite(det)) return false;
    const double inv = 1.0 / det;
    const dvec3 tvec = o - v0;
    a = glm::dot(tvec, pvec) * inv;
    if (a < -kEdge || a > 1.0 + kEdge) return false;
    const dvec3 qvec = glm::cross(tvec, ea);
    b = glm::dot(d, qvec) * inv;
    if (b < -kEdge || a + b > 1.0 + kEdge) return false;
    t = glm::dot(eb, qvec) * inv;
    return t > tmin && t < tmax;
}

} // namespace

void inverse_bilinear_unclamped(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& d,
                                const dvec3& normal, const dvec3& p, double& u, double& v) {
    // 2D frame in the quad's plane: x along b-a, y = normal x x.
    const dvec3 ex = glm::normalize(b - a);
    const dvec3 ey = glm::cross(normal, ex);
    const auto to2 = [&](const dvec3& q) {
        return std::array<double, 2>{glm::dot(q - a, ex), glm::dot(q - a, ey)};
    };
    // P(u,v) - a = u e + v f + u v g, with e = b-a, f = d-a, g = a-b+c-d; h = p-a.
    const auto B = to2(b), C = to2(c), D = to2(d), H = to2(p);
    const double e[2] = {B[0], B[1]}, f[2] = {D[0], D[1]};
    const double g[2] = {C[0] - B[0] - D[0], C[1] - B[1] - D[1]};
    // Eliminating u: k2 v^2 + k1 v + k0 = 0.
    const double k2 = cross2(g[0], g[1], f[0], f[1]);
    const double k1 = cross2(e[0], e[1], f[0], f[1]) + cross2(H[0], H[1], g[0], g[1]);
    const double k0 = cross2(H[0], H[1], e[0], e[1]);
    const double area = std::abs(cross2(e[0], e[1], f[0], f[1])) + 1e-300;
    const auto solve_u = [&](double vv) {
        // h = u (e + v g) + v f: take the better-conditioned component.
        const double dx = e[0] + g[0] * vv, dy = e[1] + g[1] * vv;
        return std::abs(dx) >= std::abs(dy) ? (H[0] - f[0] * vv) / dx : (H[1] - f[1] * vv) / dy;
    };
    const auto outside = [](double uu, double vv) {
        constexpr double k = 1e-9;
        return !(uu >= -k && uu <= 1 + k && vv >= -k && vv <= 1 + k);
    };
    if (std::abs(k2) <= 1e-12 * area) { // parallelogram-like: linear in v
        v = -k0 / k1;
        u = solve_u(v);
    } else {
        const double w = std::sqrt(std::max(0.0, k1 * k1 - 4.0 * k0 * k2));
        // Numerically stable pair of roots.
        const double q = -0.5 * (k1 + std::copysign(w, k1));
        const double r1 = q / k2, r2 = q != 0 ? k0 / q : r1;
        v = r1;
        u = solve_u(v);
        if (outside(u, v)) {
            const double u2 = solve_u(r2);
            if (!outside(u2, r2) || std::abs(r2 - 0.5) < std::abs(r1 - 0.5)) {
                v = r2;
                u = u2;
            }
        }
    }
    if (!std::isfinite(u)) u = 0;
    if (!std::isfinite(v)) v = 0;
}

void inverse_bilinear(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& d,
                      const dvec3& normal, const dvec3& p, double& u, double& v) {
    inverse_bilinear_unclamped(a, b, c, d, normal, p, u, v);
    u = std::clamp(u, 0.0, 1.0);
    v = std::clamp(v, 0.0, 1.0);
}

Bvh::Bvh(const Scene& scene) {
    const std::size_t n = scene.polygons.size();
    HEMIRAD_CHECK(n < kNoPolygon);
    prims_.resize(n);
    order_.resize(n);
    std::vector<dvec3> lo(n), hi(n), centroid(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Polygon& p = scene.polygons[i];
        Prim& q = prims_[i];
        q.v0 = p.v[0];
        q.e1 = p.v[1] - p.v[0];
        q.e2 = p.v[2] - p.v[0];
        q.e3 = p.count == 4 ? p.v[3] - p.v[0] : dvec3(0.0);
        q.normal = p.normal;
        q.count = p.count;
        q.twinned = p.twin != kNoTwin;
        lo[i] = hi[i] = p.v[0];
        for (int k = 1; k < p.count; ++k) {
            lo[i] = glm::min(lo[i], p.v[k]);
            hi[i] = glm::max(hi[i], p.v[k]);
        }
        centroid[i] = 0.5 * (lo[i] + hi[i]);
        order_[i] = std::uint32_t(i);
    }
    nodes_.reserve(2 * n + 1);
    if (n > 0) build(0, std::uint32_t(n), lo, hi, centroid);
}

std::uint32_t Bvh::build(std::uint32_t begin, std::uint32_t end, std::vector<dvec3>& lo,
                         std::vector<dvec3>& hi, std::vector<dvec3>& centroid) {
    const std::uint32_t index = std::uint32_t(nodes_.size());
    nodes_.emplace_back();
    Node node;
    node.lo = dvec3(1e300);
    node.hi = dvec3(-1e300);
    dvec3 clo(1e300), chi(-1e300);
    for (std::uint32_t i = begin; i < end; ++i) {
        const std::uint32_t p = order_[i];
        node.lo = glm::min(node.lo, lo[p]);
        node.hi = glm::max(node.hi, hi[p]);
        clo = glm::min(clo, centroid[p]);
        chi = glm::max(chi, centroid[p]);
    }
    const std::uint32_t count = end - begin;
    node.first = begin;
    node.count = count;
    if (count > kLeafSize) {
        // Binned SAH over the centroid bounds, best axis and plane.
        int best_axis = -1, best_split = 0;
        double best_cost = double(count) * half_area(node.lo, node.hi);
        for (int axis = 0; axis < 3; ++axis) {
            const double extent = chi[axis] - clo[axis];
            if (!(extent > 0)) continue;
            std::array<std::uint32_t, kBins> bin_count{};
            std::array<dvec3, kBins> bin_lo, bin_hi;
            bin_lo.fill(dvec3(1e300));
            bin_hi.fill(dvec3(-1e300));
            const double scale = kBins / extent;
            for (std::uint32_t i = begin; i < end; ++i) {
                const std::uint32_t p = order_[i];
                const int b = std::min(kBins - 1, int((centroid[p][axis] - clo[axis]) * scale));
                ++bin_count[b];
                bin_lo[b] = glm::min(bin_lo[b], lo[p]);
                bin_hi[b] = glm::max(bin_hi[b], hi[p]);
            }
            std::array<double, kBins> right_cost{};
            dvec3 rlo(1e300), rhi(-1e300);
            std::uint32_t rn = 0;
            for (int b = kBins - 1; b > 0; --b) {
                rlo = glm::min(rlo, bin_lo[b]);
                rhi = glm::max(rhi, bin_hi[b]);
                rn += bin_count[b];
                right_cost[b] = rn ? rn * half_area(rlo, rhi) : 0.0;
            }
            dvec3 llo(1e300), lhi(-1e300);
            std::uint32_t ln = 0;
            for (int b = 0; b + 1 < kBins; ++b) {
                llo = glm::min(llo, bin_lo[b]);
                lhi = glm::max(lhi, bin_hi[b]);
                ln += bin_count[b];
                if (ln == 0 || ln == count) continue;
                // Traversal cost 1 vs intersection cost 1 per primitive, relative to the parent.
                const double cost =
                    half_area(node.lo, node.hi) + ln * half_area(llo, lhi) + right_cost[b + 1];
                if (cost < best_cost) {
                    best_cost = cost;
                    best_axis = axis;
                    best_split = b;
                }
            }
        }
        std::uint32_t mid = begin;
        if (best_axis >= 0) {
            const double scale = kBins / (chi[best_axis] - clo[best_axis]);
            const auto in_left = [&](std::uint32_t p) {
                const double x = (centroid[p][best_axis] - clo[best_axis]) * scale;
                return std::min(kBins - 1, int(x)) <= best_split;
            };
            mid = std::uint32_t(
                std::partition(order_.begin() + begin, order_.begin() + end, in_left) -
                order_.begin());
        } else if (count > 4 * kLeafSize) {
            // SAH found nothing better (e.g. all centroids coincide): median split on the
            // longest axis of the node so that leaves stay small.
            const dvec3 ext = node.hi - node.lo;
            const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
            mid = begin + count / 2;
            std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                             [&](std::uint32_t a, std::uint32_t b) {
                                 return centroid[a][axis] < centroid[b][axis];
                             });
        }
        if (mid > begin && mid < end) {
            node.count = 0;
            build(begin, mid, lo, hi, centroid); // left child = index + 1
            node.first = build(mid, end, lo, hi, centroid);
        }
    }
    nodes_[index] = node;
    return index;
}

bool Bvh::hit_prim(const Prim& p, const dvec3& o, const dvec3& d, double tmin, double tmax,
                   double& t, double& u, double& v) const {
    double a, b;
    if (p.count == 3) {
        if (!ray_triangle(o, d, p.v0, p.e1, p.e2, tmin, tmax, t, a, b)) return false;
        u = std::clamp(a, 0.0, 1.0);
        v = std::clamp(b, 0.0, 1.0);
        return true;
    }
    if (!ray_triangle(o, d, p.v0, p.e1, p.e2, tmin, tmax, t, a, b) &&
        !ray_triangle(o, d, p.v0, p.e2, p.e3, tmin, tmax, t, a, b))
        return false;
    inverse_bilinear(p.v0, p.v0 + p.e1, p.v0 + p.e2, p.v0 + p.e3, p.normal, o + t * d, u, v);
    return true;
}

template <class Visit>
void Bvh::traverse(const dvec3& o, const dvec3& d, double tmin, double& tmax, Visit visit) const {
    if (nodes_.empty()) return;
    dvec3 inv;
    for (int k = 0; k < 3; ++k) inv[k] = 1.0 / (d[k] != 0.0 ? d[k] : 1e-300);
    const auto box = [&](const Node& n, double& tnear) {
        double t0 = tmin, t1 = tmax;
        for (int k = 0; k < 3; ++k) {
            double a = (n.lo[k] - o[k]) * inv[k], b = (n.hi[k] - o[k]) * inv[k];
            if (a > b) std::swap(a, b);
            t0 = std::max(t0, a);
            t1 = std::min(t1, b * (1 + 1e-12) + 1e-300); // conservative far plane
        }
        tnear = t0;
        return t0 <= t1;
    };
    std::array<std::uint32_t, 128> stack;
    int top = 0;
    double tn;
    if (!box(nodes_[0], tn)) return;
    stack[top++] = 0;
    while (top > 0) {
        const Node& n = nodes_[stack[--top]];
        if (n.count > 0) {
            for (std::uint32_t i = n.first; i < n.first + n.count; ++i)
                if (visit(order_[i])) return; // visit may shrink tmax
            continue;
        }
        const std::uint32_t left = std::uint32_t(&n - nodes_.data()) + 1, right = n.first;
        double tl, tr;
        const bool hl = box(nodes_[left], tl), hr = box(nodes_[right], tr);
        HEMIRAD_CHECK(top + 2 <= int(stack.size()));
        if (hl && hr) {
            // Push the farther child first so the nearer one is visited first.
            if (tl <= tr) {
                stack[top++] = right;
                stack[top++] = left;
            } else {
                stack[top++] = left;
                stack[top++] = right;
            }
        } else if (hl) {
            stack[top++] = left;
        } else if (hr) {
            stack[top++] = right;
        }
    }
}

bool Bvh::occluded(const dvec3& from, const dvec3& to, std::uint32_t ignore_a,
                   std::uint32_t ignore_b) const {
    const dvec3 d = to - from;
    constexpr double kEnd = 1e-7;
    double tmax = 1.0 - kEnd;
    bool blocked = false;
    traverse(from, d, kEnd, tmax, [&](std::uint32_t p) {
        if (p == ignore_a || p == ignore_b) return false;
        double t, u, v;
        if (hit_prim(prims_[p], from, d, kEnd, tmax, t, u, v)) {
            blocked = true;
            return true;
        }
        return false;
    });
    return blocked;
}

bool Bvh::intersect(const dvec3& origin, const dvec3& dir, double tmax, Hit& hit,
                    std::uint32_t ignore) const {
    const double tmin = 1e-9;
    double best = tmax;
    bool found = false;
    traverse(origin, dir, tmin, best, [&](std::uint32_t p) {
        if (p == ignore) return false;
        // The back of a two-sided surface's polygon is its twin's front, at the same place.
        if (prims_[p].twinned && glm::dot(prims_[p].normal, dir) >= 0) return false;
        double t, u, v;
        if (hit_prim(prims_[p], origin, dir, tmin, best, t, u, v)) {
            best = t;
            hit.polygon = p;
            hit.t = t;
            hit.u = u;
            hit.v = v;
            hit.front = glm::dot(prims_[p].normal, dir) < 0;
            found = true;
        }
        return false;
    });
    return found;
}

} // namespace hemirad
