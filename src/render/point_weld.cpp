#include "render/point_weld.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>

#include "hemirad/error.h"

namespace hemirad {

namespace {

/// Union-find over point indices (path halving); the root of a set is its smallest index.
struct UnionFind {
    std::vector<std::uint32_t> parent;
    explicit UnionFind(std::size_t n) : parent(n) {
        for (std::size_t i = 0; i < n; ++i) parent[i] = std::uint32_t(i);
    }
    std::uint32_t find(std::uint32_t a) {
        while (parent[a] != a) a = parent[a] = parent[parent[a]];
        return a;
    }
    void unite(std::uint32_t a, std::uint32_t b) {
        a = find(a), b = find(b);
        if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
};

using Cell = std::array<std::int64_t, 3>;

struct Entry {
    Cell cell;
    std::uint32_t point;
    bool operator<(const Entry& o) const {
        return std::tie(cell, point) < std::tie(o.cell, o.point);
    }
};

std::int64_t cell_of(double x, double size) {
    return std::int64_t(std::floor(x / size));
}

} // namespace

std::vector<std::uint32_t>
weld_points(const std::vector<glm::dvec3>& points, const std::vector<std::uint8_t>& candidate,
            double tolerance, const std::function<bool(std::uint32_t, std::uint32_t)>& may_join) {
    HEMIRAD_CHECK_EQ(points.size(), candidate.size());
    HEMIRAD_CHECK(tolerance > 0);
    const double size = 2 * tolerance;
    std::vector<Entry> entries;
    for (std::uint32_t i = 0; i < points.size(); ++i)
        if (candidate[i])
            entries.push_back({{cell_of(points[i].x, size), cell_of(points[i].y, size),
                                cell_of(points[i].z, size)},
                               i});
    std::sort(entries.begin(), entries.end());

    UnionFind uf(points.size());
    const auto join = [&](std::uint32_t a, std::uint32_t b) {
        if (glm::length(points[a] - points[b]) <= tolerance && may_join(a, b)) uf.unite(a, b);
    };
    for (std::size_t k = 0; k < entries.size(); ++k) {
        const Entry& e = entries[k];
        const glm::dvec3& p = points[e.point];
        // The cells that |q - p| <= tolerance can reach, per axis: one or two.
        Cell lo, hi;
        for (int a = 0; a < 3; ++a) {
            lo[a] = cell_of(p[a] - tolerance, size);
            hi[a] = cell_of(p[a] + tolerance, size);
        }
        // Each pair once: only the points with a smaller index, which in the point's own
        // cell are the entries just before it.
        for (std::size_t j = k; j-- > 0 && entries[j].cell == e.cell;)
            join(entries[j].point, e.point);
        if (lo == hi) continue; // away from the cell's walls: its own cell is all
        Cell c;
        for (c[0] = lo[0]; c[0] <= hi[0]; ++c[0])
            for (c[1] = lo[1]; c[1] <= hi[1]; ++c[1])
                for (c[2] = lo[2]; c[2] <= hi[2]; ++c[2]) {
                    if (c == e.cell) continue;
                    auto it = std::lower_bound(entries.begin(), entries.end(), Entry{c, 0});
                    for (; it != entries.end() && it->cell == c && it->point < e.point; ++it)
                        join(it->point, e.point);
                }
    }
    std::vector<std::uint32_t> root(points.size());
    for (std::uint32_t i = 0; i < points.size(); ++i) root[i] = uf.find(i);
    return root;
}

} // namespace hemirad
