// Leaf-level mesh with per-vertex radiosity, as binary PLY (layout in export.h).
#include <bit>
#include <cstring>

#include "hemirad/export.h"
#include "output/atomic_file.h"

namespace hemirad {

namespace {

// Leaf corners as vertex-grid coordinates (a, b), a + b <= n for triangles (see patch.h).
int leaf_corners(bool triangle, std::uint32_t n, std::uint32_t index,
                 std::array<glm::uvec2, 4>& c) {
    const std::uint32_t x = index % n, y = index / n;
    if (!triangle) {
        c = {glm::uvec2(x, y), glm::uvec2(x + 1, y), glm::uvec2(x + 1, y + 1),
             glm::uvec2(x, y + 1)};
        return 4;
    }
    if (x + y <= n - 1) {
        c[0] = {x, y}, c[1] = {x + 1, y}, c[2] = {x, y + 1};
    } else {
        const std::uint32_t i = n - 1 - x, j = n - 1 - y;
        c[0] = {i + 1, j + 1}, c[1] = {i, j + 1}, c[2] = {i + 1, j};
    }
    return 3;
}

std::uint32_t vertex_index(bool triangle, std::uint32_t n, glm::uvec2 g) {
    if (!triangle) return g.y * (n + 1) + g.x;
    return g.y * (n + 1) - g.y * (g.y - 1) / 2 + g.x; // rows of n+1, n, ..., 1 vertices
}

void put_f32(std::string& out, float v) {
    const std::uint32_t b = std::bit_cast<std::uint32_t>(v);
    for (int i = 0; i < 4; ++i) out.push_back(char((b >> (8 * i)) & 0xff));
}
void put_u32(std::string& out, std::uint32_t b) {
    for (int i = 0; i < 4; ++i) out.push_back(char((b >> (8 * i)) & 0xff));
}

} // namespace

LeafMesh leaf_mesh(const Hierarchy& h) {
    const Scene& scene = h.scene();
    LeafMesh m;
    std::vector<dvec3> sum;
    std::vector<double> weight;
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p) {
        const Polygon& poly = scene.polygons[p];
        const bool tri = poly.is_triangle();
        const std::uint32_t level = std::uint32_t(h.depth(p));
        const std::uint32_t n = 1u << level;
        const std::uint32_t base = std::uint32_t(m.positions.size());
        const std::uint32_t count = tri ? (n + 1) * (n + 2) / 2 : (n + 1) * (n + 1);
        m.positions.resize(base + count);
        sum.assign(count, dvec3(0.0));
        weight.assign(count, 0.0);
        for (std::uint32_t b = 0; b <= n; ++b)
            for (std::uint32_t a = 0; a <= n - (tri ? b : 0); ++a)
                m.positions[base + vertex_index(tri, n, {a, b})] =
                    glm::vec3(polygon_point(poly, double(a) / n, double(b) / n));
        for (std::uint32_t i = 0; i < n * n; ++i) {
            const PatchAddress leaf{p, level, i};
            const dvec3 B = h.radiosity(leaf);
            const double area = double(h.node(leaf).area);
            std::array<glm::uvec2, 4> c;
            const int k = leaf_corners(tri, n, i, c);
            std::uint32_t id[4];
            for (int j = 0; j < k; ++j) {
                id[j] = vertex_index(tri, n, c[j]);
                sum[id[j]] += B * area;
                weight[id[j]] += area;
            }
            m.triangles.push_back({base + id[0], base + id[1], base + id[2]});
            if (k == 4) m.triangles.push_back({base + id[0], base + id[2], base + id[3]});
        }
        m.radiosity.resize(base + count);
        for (std::uint32_t v = 0; v < count; ++v)
            m.radiosity[base + v] = weight[v] > 0 ? glm::vec3(sum[v] / weight[v]) : glm::vec3(0.f);
    }
    return m;
}

std::string ply_bytes(const LeafMesh& m) {
    std::string out = "ply\nformat binary_little_endian 1.0\n"
                      "comment hemirad leaf mesh: red green blue = radiosity B [W per scene "
                      "unit^2], linear RGB\n";
    out += "element vertex " + std::to_string(m.positions.size()) + "\n";
    out += "property float x\nproperty float y\nproperty float z\n"
           "property float red\nproperty float green\nproperty float blue\n";
    out += "element face " + std::to_string(m.triangles.size()) + "\n";
    out += "property list uchar int vertex_indices\nend_header\n";
    out.reserve(out.size() + m.positions.size() * 24 + m.triangles.size() * 13);
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
        for (int c = 0; c < 3; ++c) put_f32(out, m.positions[i][c]);
        for (int c = 0; c < 3; ++c) put_f32(out, m.radiosity[i][c]);
    }
    for (const auto& t : m.triangles) {
        out.push_back(char(3));
        for (std::uint32_t v : t) put_u32(out, v);
    }
    return out;
}

void export_ply(const std::string& path, const Hierarchy& h) {
    write_file_atomically(path, ply_bytes(leaf_mesh(h)));
}

} // namespace hemirad
