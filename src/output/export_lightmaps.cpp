// Lightmap atlases of leaf radiosity per surface group (layout in export.h).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <memory>
#include <sstream>

#include "hemirad/error.h"
#include "hemirad/export.h"
#include "output/atomic_file.h"
#include "render/discontinuity_field.h"

namespace hemirad {

namespace {

// Chart values, n x n, row-major by (i, j): the leaf radiosity at each parameter cell.
std::vector<glm::vec3> chart_texels(const Hierarchy& h, std::uint32_t p) {
    const Polygon& poly = h.scene().polygons[p];
    const std::uint32_t level = std::uint32_t(h.depth(p));
    const std::uint32_t n = 1u << level;
    std::vector<glm::vec3> t(std::size_t(n) * n);
    const auto B = [&](std::uint32_t index) { return h.radiosity({p, level, index}); };
    if (!poly.is_triangle()) {
        for (std::uint32_t i = 0; i < n * n; ++i) t[i] = glm::vec3(B(i));
        return t;
    }
    // Triangle: cell (i, j), i + j <= n-1, holds the upright leaf j*n+i and, if i + j <= n-2,
    // the inverted leaf stored at the mirrored cell (equal areas: a plain average).
    for (std::uint32_t j = 0; j < n; ++j)
        for (std::uint32_t i = 0; i + j <= n - 1; ++i) {
            dvec3 v = B(j * n + i);
            if (i + j + 2 <= n) v = 0.5 * (v + B((n - 1 - j) * n + (n - 1 - i)));
            t[j * n + i] = glm::vec3(v);
        }
    // Outside the triangle: copy the nearest texel on the diagonal i + j = n-1.
    for (std::uint32_t j = 0; j < n; ++j)
        for (std::uint32_t i = 0; i < n; ++i) {
            if (i + j <= n - 1) continue;
            const std::uint32_t k = i + j - (n - 1);
            t[j * n + i] = t[(j - k / 2) * n + (i - (k + 1) / 2)];
        }
    return t;
}

std::string fmt(double v) {
    std::ostringstream s;
    s.precision(9);
    s << v;
    return s.str();
}

} // namespace

std::string lightmap_stem(const std::string& group) {
    std::string s = group;
    for (char& c : s)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'))
            c = '_';
    if (s.empty() || s == "." || s == "..") s = "group" + s;
    return s;
}

namespace {

/// Most texels per leaf side of a textured quad's chart (texture detail).
constexpr int kMaxTextureTexelsPerLeaf = 8;

// Texels per leaf side of polygon p's chart: 4 for a quad with a flagged leaf (with detail); for
// a textured quad, about one per texture texel (at most kMaxTextureTexelsPerLeaf).
int texels_per_leaf(const Hierarchy& h, std::uint32_t p, const DiscontinuityField* detail) {
    const Polygon& poly = h.scene().polygons[p];
    if (poly.is_triangle()) return 1;
    const std::uint32_t level = std::uint32_t(h.depth(p));
    int k = 1;
    if (const Texture* t = h.scene().texture_of(p)) {
        // The polygon's footprint in texels (the texture map's Jacobian at its centre), per leaf.
        const glm::dvec2 ds =
            (polygon_texcoord(h.scene(), p, 1, 0.5) - polygon_texcoord(h.scene(), p, 0, 0.5)) *
            double(t->width());
        const glm::dvec2 dt =
            (polygon_texcoord(h.scene(), p, 0.5, 1) - polygon_texcoord(h.scene(), p, 0.5, 0)) *
            double(t->height());
        const double side = std::sqrt(std::abs(ds.x * dt.y - ds.y * dt.x)) / double(1u << level);
        k = std::clamp(int(std::ceil(side)), 1, kMaxTextureTexelsPerLeaf);
    }
    if (detail)
        for (std::uint32_t i = 0; i < (1u << (2 * level)); ++i)
            if (detail->flagged(p, i)) return std::max(k, 4);
    return k;
}

// A refined chart (quads): k x k texels per leaf, the flagged leaves' texels with detail (if
// `detail`), a textured polygon's texels with its texture: Be + texel rho (H + detail).
std::vector<glm::vec3> refined_texels(const Hierarchy& h, std::uint32_t p, int k,
                                      const DiscontinuityField* detail) {
    const Polygon& poly = h.scene().polygons[p];
    const Material& m = h.scene().material_of(poly);
    const std::uint32_t level = std::uint32_t(h.depth(p));
    const int leaves = 1 << level, n = leaves * k;
    std::vector<glm::vec3> t(std::size_t(n) * n);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const std::uint32_t leaf = std::uint32_t((j / k) * leaves + i / k);
            dvec3 B = h.radiosity({p, level, leaf});
            const double u = (i + 0.5) / n, v = (j + 0.5) / n;
            dvec3 d(0.0);
            const bool flagged =
                detail &&
                detail->detail(p, u, v, polygon_point(poly, u, v), std::uint64_t(j) * n + i,
                               DiscontinuityField::Reconstruction::Leaf, d);
            if (h.scene().texture_of(p))
                B = glm::max(m.exitance() + reflectance_at(h.scene(), p, u, v) *
                                                (h.irradiance({p, level, leaf}) + d),
                             m.exitance());
            else if (flagged)
                B = glm::max(B + m.rho * d, m.exitance());
            t[std::size_t(j) * n + i] = glm::vec3(B);
        }
    return t;
}

} // namespace

Lightmap build_lightmap(const Hierarchy& h, std::uint32_t group, const std::string& stem,
                        const DiscontinuityField* detail) {
    const Scene& scene = h.scene();
    constexpr int pad = kLightmapPadding;
    Lightmap lm;
    lm.group = scene.groups[group];
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p)
        if (scene.polygons[p].group == group)
            lm.charts.push_back({p, 0, 0, (1 << h.depth(p)) * texels_per_leaf(h, p, detail)});
    if (lm.charts.empty()) return lm;

    // Shelf packing, largest first, into a width of about sqrt(total area).
    std::vector<std::size_t> order(lm.charts.size());
    double total = 0;
    int widest = 0;
    for (std::size_t c = 0; c < order.size(); ++c) {
        order[c] = c;
        const int s = lm.charts[c].n + 2 * pad;
        total += double(s) * s;
        widest = std::max(widest, s);
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return lm.charts[a].n > lm.charts[b].n; });
    const int width = std::max(widest, int(std::ceil(std::sqrt(total))));
    int x = 0, y = 0, shelf = 0;
    for (std::size_t c : order) {
        const int s = lm.charts[c].n + 2 * pad;
        if (x + s > width) x = 0, y += shelf, shelf = 0;
        lm.charts[c].x0 = x + pad;
        lm.charts[c].y0 = y + pad;
        x += s;
        shelf = std::max(shelf, s);
    }
    const int height = y + shelf;
    lm.atlas = ImageRGB(width, height);

    // Texels, with a border of `pad` texels filled by clamp-to-edge dilation.
    for (const LightmapChart& c : lm.charts) {
        const int k = c.n >> h.depth(c.polygon);
        const std::vector<glm::vec3> t =
            k > 1 ? refined_texels(h, c.polygon, k, detail) : chart_texels(h, c.polygon);
        for (int j = -pad; j < c.n + pad; ++j)
            for (int i = -pad; i < c.n + pad; ++i) {
                const int ci = std::clamp(i, 0, c.n - 1), cj = std::clamp(j, 0, c.n - 1);
                const glm::vec3& v = t[std::size_t(cj) * c.n + ci];
                float* px = lm.atlas.at(c.x0 + i, c.y0 + j);
                px[0] = v.x, px[1] = v.y, px[2] = v.z;
            }
    }

    // The mesh: one v/vt/vn per polygon corner, UVs at the chart's parameter corners.
    std::ostringstream obj;
    obj << "# hemirad lightmap mesh of group '" << lm.group << "': texture " << stem
        << ".exr = radiosity B [W per scene unit^2], linear RGB, " << width << "x" << height
        << "\nmtllib " << stem << ".mtl\no " << stem << "\nusemtl " << stem << "\n";
    std::ostringstream faces;
    int next = 1;
    for (const LightmapChart& c : lm.charts) {
        const Polygon& poly = scene.polygons[c.polygon];
        static constexpr double kQuad[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        static constexpr double kTri[3][2] = {{0, 0}, {1, 0}, {0, 1}};
        faces << "f";
        for (int k = 0; k < poly.count; ++k) {
            const double* uv = poly.is_triangle() ? kTri[k] : kQuad[k];
            const dvec3& v = poly.v[k];
            obj << "v " << fmt(v.x) << " " << fmt(v.y) << " " << fmt(v.z) << "\n";
            obj << "vt " << fmt((c.x0 + uv[0] * c.n) / width) << " "
                << fmt(1.0 - (c.y0 + uv[1] * c.n) / height) << "\n";
            obj << "vn " << fmt(poly.normal.x) << " " << fmt(poly.normal.y) << " "
                << fmt(poly.normal.z) << "\n";
            faces << " " << next << "/" << next << "/" << next;
            ++next;
        }
        faces << "\n";
    }
    lm.obj = obj.str() + faces.str();
    lm.mtl = "newmtl " + stem + "\nKd 1 1 1\nmap_Kd " + stem + ".exr\n";
    return lm;
}

std::vector<std::string> export_lightmaps(const std::string& dir, const Hierarchy& h,
                                          bool discontinuities) {
    std::unique_ptr<DiscontinuityField> detail;
    if (discontinuities) detail = std::make_unique<DiscontinuityField>(h);
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw RuntimeError("cannot create directory " + dir + ": " + ec.message());
    std::vector<std::string> written;
    std::vector<std::string> stems;
    for (std::uint32_t g = 0; g < h.scene().groups.size(); ++g) {
        std::string stem = lightmap_stem(h.scene().groups[g]);
        // Two groups that sanitise to the same name get numbered.
        if (std::find(stems.begin(), stems.end(), stem) != stems.end())
            stem.append(1, '_').append(std::to_string(g));
        stems.push_back(stem);
        const Lightmap lm = build_lightmap(h, g, stem, detail.get());
        if (lm.charts.empty()) continue;
        const std::string base = (std::filesystem::path(dir) / stem).string();
        write_exr(base + ".exr", lm.atlas, /*half=*/false);
        write_file_atomically(base + ".obj", lm.obj);
        write_file_atomically(base + ".mtl", lm.mtl);
        written.push_back(base + ".exr");
        written.push_back(base + ".obj");
        written.push_back(base + ".mtl");
    }
    return written;
}

} // namespace hemirad
