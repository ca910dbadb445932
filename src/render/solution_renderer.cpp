// SolutionRenderer: draws every polygon subdivided at its leaf level, coloured by its leaf
// values, through a perspective camera.
//
// Smooth reconstruction (the default) is Gouraud shading of nodal averages: the value at a
// vertex of the leaf grid is the area-weighted mean of the leaves that share it,
//
//     B(v) = sum_{leaves L touching v} A_L B_L / sum A_L,
//
// and the GPU interpolates linearly across each leaf's triangles. Vertices on a polygon's
// boundary are welded (by position, within 1e-6 of the scene diagonal) with the boundary
// vertices of neighbouring polygons of the same material and nearly the same normal (within
// 1 degree), so that their leaves join the average: a wall split into 13 x 13 polygons shows no
// seams, while a corner between two walls, or a red wall meeting a white one, stays sharp.
//
// Why this and not a texture or a higher-order fit: it costs one pass over the leaves and one
// vertex attribute per grid corner (so the viewer can recompute it every frame), it has no
// texture-resolution limit (a leaf is never smaller than a texel, whatever the depth), and it
// uses exactly the patch data — the leaf values are constant-basis radiosities, and the nodal
// average is the classic way to display them (Cohen & Greenberg 1985). It is exact for a field
// that is linear over a uniform grid (at interior vertices the mean of the four leaf centres is
// the vertex itself); at a polygon's outer (unwelded) boundary it is one-sided, i.e. the value
// half a leaf inwards. Known limit: at a T-junction (neighbouring polygons at different depths)
// only coinciding vertices are welded, so a faint seam remains there.
//
// Flat shading shows each leaf's own value: the fragment shader finds the leaf of its triangle
// through gl_PrimitiveID (plus the draw's first triangle) and a per-triangle leaf table.
//
// Textured polygons (texture.h) show texture detail: their smooth vertex value is rho (E +
// ambient) without the texture, and the fragment shader multiplies it by the texel's linear
// reflectance (trilinear, through the same box-filtered mipmap the solver averages) and adds
// Be: B(x) = Be + texel(x) rho E(x). They are drawn in runs of consecutive polygons of one
// textured material, one draw call each (an untextured scene is still one draw call). Flat
// shading shows each leaf's own value, Be + rho_leaf E with the leaf's mean reflectance.
#include "hemirad/render.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <sstream>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "core/parse.h"
#include "core/projection.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "gl/state.h"
#include "hemirad/error.h"
#include "render/point_weld.h"

namespace hemirad {

namespace {

struct Vertex {        // attributes of solution.vert
    float position[3]; ///< scene-local (world minus the scene centre), for float precision
    float grid[3];     ///< (u n, v n, (triangle ? 1 : 0) + (two-sided ? 2 : 0))
    std::uint32_t node;
    float st[2]; ///< texture coordinates (textured polygons; else 0)
};
static_assert(sizeof(Vertex) == 36);

/// Consecutive polygons drawn with one call: untextured ones, or those of one textured material.
struct DrawRun {
    std::size_t first_index = 0, index_count = 0; ///< into the index buffer
    std::uint32_t first_triangle = 0;             ///< gl_PrimitiveID offset into triangle_leaf
    int texture = -1;                             ///< into SolutionRenderer::Impl::textures
    glm::vec3 emitted{0.f};                       ///< the material's Be, added per fragment
};

/// One polygon's leaf grid in the shared buffers.
struct PolygonGrid {
    std::uint32_t vertex_base = 0; ///< first vertex
    std::uint32_t leaf_base = 0;   ///< first leaf (global leaf id = leaf_base + index)
    std::uint32_t n = 1;           ///< leaves per side: 2^depth
    std::uint32_t depth = 0;
    bool triangle = false;
};

/// Vertex index within a polygon's grid of lattice point (i, j), and whether it lies on the
/// polygon's boundary. Quads: (n+1)^2 vertices, row-major. Triangles: rows j = 0..n of
/// n + 1 - j vertices each (i + j <= n).
std::uint32_t grid_vertex(const PolygonGrid& g, std::uint32_t i, std::uint32_t j) {
    if (!g.triangle) return j * (g.n + 1) + i;
    return j * (g.n + 1) - j * (j - 1) / 2 + i;
}
std::uint32_t grid_vertex_count(const PolygonGrid& g) {
    return g.triangle ? (g.n + 1) * (g.n + 2) / 2 : (g.n + 1) * (g.n + 1);
}

/// The corner vertices (polygon-local) of leaf `index`, counter-clockwise like the polygon (and
/// like patch_geometry()); returns the count (3 or 4).
int leaf_corners(const PolygonGrid& g, std::uint32_t index, std::array<std::uint32_t, 4>& c) {
    const std::uint32_t n = g.n, x = index % n, y = index / n;
    if (!g.triangle) {
        c = {grid_vertex(g, x, y), grid_vertex(g, x + 1, y), grid_vertex(g, x + 1, y + 1),
             grid_vertex(g, x, y + 1)};
        return 4;
    }
    // patch.h: cell (i,j) with i + j <= n - 1 holds the upright triangle at index j n + i;
    // the inverted one of cell (i,j) is stored at the mirrored cell (n-1-i, n-1-j).
    if (x + y <= n - 1) {
        c = {grid_vertex(g, x, y), grid_vertex(g, x + 1, y), grid_vertex(g, x, y + 1), 0};
    } else {
        const std::uint32_t i = n - 1 - x, j = n - 1 - y;
        c = {grid_vertex(g, i + 1, j + 1), grid_vertex(g, i, j + 1), grid_vertex(g, i + 1, j), 0};
    }
    return 3;
}

/// cos(1 degree): polygons whose normals differ by more than this are never welded.
constexpr double kWeldCosAngle = 0.99984769515639;
/// Weld distance relative to the scene's bounding-box diagonal.
constexpr double kWeldRelativeTolerance = 1e-6;

} // namespace

// --- cameras ---------------------------------------------------------------------------------

Camera parse_camera(const std::string& text) {
    std::vector<double> v;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) {
        double x = 0;
        const NumberRead r = read_double(item.data(), item.data() + item.size(), x);
        std::size_t used = r.range_error ? 0 : std::size_t(r.end - item.data());
        while (used < item.size() && std::isspace(static_cast<unsigned char>(item[used]))) ++used;
        if (used == 0 || used != item.size() || !std::isfinite(x))
            throw InputError("camera '" + text + "': value " + std::to_string(v.size() + 1) + " '" +
                             item + "' is not a number");
        v.push_back(x);
    }
    if (!text.empty() && text.back() == ',')
        throw InputError("camera '" + text + "': empty value after the last comma");
    if (v.size() != 10)
        throw InputError("camera '" + text +
                         "': expected 10 values eye,target,up,fov (ex,ey,ez,"
                         "tx,ty,tz,ux,uy,uz,fov), got " +
                         std::to_string(v.size()));
    Camera c;
    c.name = "command line";
    c.eye = dvec3(v[0], v[1], v[2]);
    c.target = dvec3(v[3], v[4], v[5]);
    c.up = dvec3(v[6], v[7], v[8]);
    c.fov_y_deg = v[9];
    const dvec3 d = c.target - c.eye;
    if (!(glm::length(d) > 0))
        throw InputError("camera '" + text + "': the eye and the target are the same point");
    if (!(glm::length(glm::cross(glm::normalize(d), c.up)) > 1e-9 * glm::length(c.up)))
        throw InputError("camera '" + text +
                         "': the up vector is zero or parallel to the "
                         "view direction");
    if (!(c.fov_y_deg > 0 && c.fov_y_deg < 180)) {
        std::ostringstream s;
        s << "camera '" << text << "': fov " << c.fov_y_deg << " must be in (0, 180) degrees";
        throw InputError(s.str());
    }
    return c;
}

// --- renderer --------------------------------------------------------------------------------

struct SolutionRenderer::Impl {
    const Scene* scene;
    dvec3 origin{0.0};     ///< scene centre; GL positions are relative to it
    double diagonal = 1.0; ///< scene bounding-box diagonal [unit]

    // Geometry (built for one discretisation).
    std::vector<std::uint8_t> depths; ///< the discretisation the geometry was built for
    bool built = false;
    std::vector<PolygonGrid> grids;
    std::vector<std::uint32_t> vertex_node; ///< welded node of each vertex
    std::size_t vertex_count = 0, node_count = 0, leaf_count = 0, index_count = 0;
    gl::Buffer vertices, indices, triangle_leaf, node_rgb, leaf_rgb;
    gl::VertexArray vao;
    gl::Program program;
    std::vector<DrawRun> runs;
    std::vector<gl::Texture> textures;  ///< Scene::textures, linear RGB32F with their mipmaps
    std::vector<std::uint8_t> textured; ///< per polygon: drawn with its texture

    // Per-frame scratch.
    std::vector<float> leaf_values;   ///< RGB per leaf
    std::vector<glm::vec4> node_sums; ///< (sum A B, sum A) per node
    std::vector<float> node_values;   ///< RGB per node

    // The highlighted patch (RenderOptions::highlight): its 3 or 4 corners.
    gl::Buffer highlight_vertices;
    gl::VertexArray highlight_vao;

    // Offscreen target of render().
    gl::FloatTarget target;
    std::vector<float> readback;

    void build(const Hierarchy& h);
    void ensure_geometry(const Hierarchy& h) {
        if (!built || depths != h.discretisation().depth) build(h);
    }
    void compute_colours(const Hierarchy& h, const RenderOptions& o);
    glm::mat4 view_projection(const Camera& camera, int width, int height) const;
    void draw_scene(const Camera& camera, const RenderOptions& o, int width, int height);
    void draw_highlight(const Camera& camera, const PatchAddress& patch, const dvec3& colour,
                        int width, int height);
};

void SolutionRenderer::Impl::build(const Hierarchy& h) {
    const Scene& s = *scene;
    depths = h.discretisation().depth;
    HEMIRAD_CHECK_EQ(depths.size(), s.polygons.size());
    grids.assign(s.polygons.size(), {});
    std::uint64_t nv = 0, nl = 0, ni = 0;
    for (std::size_t p = 0; p < s.polygons.size(); ++p) {
        PolygonGrid& g = grids[p];
        g.depth = depths[p];
        g.n = 1u << g.depth;
        g.triangle = s.polygons[p].is_triangle();
        g.vertex_base = std::uint32_t(nv);
        g.leaf_base = std::uint32_t(nl);
        nv += grid_vertex_count(g);
        nl += std::uint64_t(g.n) * g.n;
        ni += std::uint64_t(g.n) * g.n * (g.triangle ? 3 : 6);
    }
    if (nv >= (std::uint64_t(1) << 31) || ni >= (std::uint64_t(1) << 31))
        throw RuntimeError("solution view: " + std::to_string(nl) +
                           " leaf patches are too many to draw");
    vertex_count = std::size_t(nv);
    leaf_count = std::size_t(nl);
    index_count = std::size_t(ni);

    // Vertices: every polygon's leaf grid; positions from the same bilinear/affine map as
    // patch_geometry(), so that leaves drawn are exactly the patches solved.
    std::vector<Vertex> verts(vertex_count);
    std::vector<dvec3> world(vertex_count);
    std::vector<std::uint8_t> boundary(vertex_count, 0);
    for (std::size_t p = 0; p < s.polygons.size(); ++p) {
        const PolygonGrid& g = grids[p];
        const Polygon& poly = s.polygons[p];
        for (std::uint32_t j = 0; j <= g.n; ++j) {
            const std::uint32_t imax = g.triangle ? g.n - j : g.n;
            for (std::uint32_t i = 0; i <= imax; ++i) {
                const std::uint32_t v = g.vertex_base + grid_vertex(g, i, j);
                const dvec3 P = polygon_point(poly, double(i) / g.n, double(j) / g.n);
                const dvec3 q = P - origin;
                world[v] = P;
                glm::vec2 st(0.f);
                if (s.texture_of(std::uint32_t(p)))
                    st = glm::vec2(
                        polygon_texcoord(s, std::uint32_t(p), double(i) / g.n, double(j) / g.n));
                verts[v] = {{float(q.x), float(q.y), float(q.z)},
                            {float(i), float(j),
                             (g.triangle ? 1.f : 0.f) + (poly.twin != kNoTwin ? 2.f : 0.f)},
                            v,
                            {st.x, st.y}};
                boundary[v] = i == 0 || j == 0 || j == g.n || i == imax;
            }
        }
    }

    // Weld boundary vertices (see the header comment): a hash grid of cells of the weld
    // tolerance; each vertex looks at the 27 cells around its own.
    const double tol = std::max(kWeldRelativeTolerance * diagonal, 1e-300);
    std::vector<std::uint32_t> polygon_of(vertex_count);
    for (std::size_t p = 0; p < s.polygons.size(); ++p)
        std::fill_n(polygon_of.begin() + grids[p].vertex_base, grid_vertex_count(grids[p]),
                    std::uint32_t(p));
    const std::vector<std::uint32_t> root =
        weld_points(world, boundary, tol, [&](std::uint32_t v, std::uint32_t w) {
            const Polygon& pv = s.polygons[polygon_of[v]];
            const Polygon& pw = s.polygons[polygon_of[w]];
            return polygon_of[w] != polygon_of[v] && pw.material == pv.material &&
                   glm::dot(pw.normal, pv.normal) >= kWeldCosAngle;
        });
    vertex_node.assign(vertex_count, 0);
    std::size_t nodes = 0;
    for (std::uint32_t v = 0; v < vertex_count; ++v) {
        const std::uint32_t r = root[v];
        vertex_node[v] = r == v ? std::uint32_t(nodes++) : vertex_node[r]; // roots come first
        verts[v].node = vertex_node[v];
    }
    node_count = nodes;

    // Triangles in leaf order; quads as two triangles (c0 c1 c2, c0 c2 c3).
    std::vector<std::uint32_t> idx;
    std::vector<std::uint32_t> tri_leaf;
    idx.reserve(index_count);
    tri_leaf.reserve(index_count / 3);
    runs.clear();
    textured.assign(s.polygons.size(), 0);
    for (std::size_t p = 0; p < s.polygons.size(); ++p) {
        const PolygonGrid& g = grids[p];
        const Material& mat = s.material_of(s.polygons[p]);
        textured[p] = s.texture_of(std::uint32_t(p)) != nullptr;
        const int texture = textured[p] ? mat.texture : -1;
        const glm::vec3 Be = textured[p] ? glm::vec3(mat.exitance()) : glm::vec3(0.f);
        if (runs.empty() || runs.back().texture != texture || runs.back().emitted != Be) {
            if (!runs.empty()) runs.back().index_count = idx.size() - runs.back().first_index;
            runs.push_back({idx.size(), 0, std::uint32_t(tri_leaf.size()), texture, Be});
        }
        std::array<std::uint32_t, 4> c{};
        for (std::uint32_t i = 0; i < g.n * g.n; ++i) {
            const int k = leaf_corners(g, i, c);
            for (auto& x : c) x += g.vertex_base;
            idx.insert(idx.end(), {c[0], c[1], c[2]});
            tri_leaf.push_back(g.leaf_base + i);
            if (k == 4) {
                idx.insert(idx.end(), {c[0], c[2], c[3]});
                tri_leaf.push_back(g.leaf_base + i);
            }
        }
    }
    if (!runs.empty()) runs.back().index_count = idx.size() - runs.back().first_index;
    if (textures.empty())
        for (const Texture& t : s.textures) {
            gl::Texture tex = gl::Texture::create(GL_TEXTURE_2D);
            tex.storage_2d(GLsizei(t.levels.size()), GL_RGB32F, t.width(), t.height());
            glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
            for (std::size_t l = 0; l < t.levels.size(); ++l)
                glTextureSubImage2D(tex.id(), GLint(l), 0, 0, t.levels[l].width, t.levels[l].height,
                                    GL_RGB, GL_FLOAT, t.levels[l].texels.data());
            glTextureParameteri(tex.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
            glTextureParameteri(tex.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
            glTextureParameteri(tex.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
            glTextureParameteri(tex.id(), GL_TEXTURE_WRAP_T, GL_REPEAT);
            textures.push_back(std::move(tex));
        }

    vertices = gl::Buffer::create();
    vertices.storage(GLsizeiptr(verts.size() * sizeof(Vertex)), verts.data(), 0);
    indices = gl::Buffer::create();
    indices.storage(GLsizeiptr(idx.size() * sizeof(std::uint32_t)), idx.data(), 0);
    triangle_leaf = gl::Buffer::create();
    triangle_leaf.storage(GLsizeiptr(tri_leaf.size() * sizeof(std::uint32_t)), tri_leaf.data(), 0);
    const std::vector<float> zeros_nodes(3 * std::max<std::size_t>(node_count, 1), 0.f);
    node_rgb = gl::Buffer::create();
    node_rgb.storage(GLsizeiptr(zeros_nodes.size() * sizeof(float)), zeros_nodes.data(),
                     GL_DYNAMIC_STORAGE_BIT);
    const std::vector<float> zeros_leaves(3 * std::max<std::size_t>(leaf_count, 1), 0.f);
    leaf_rgb = gl::Buffer::create();
    leaf_rgb.storage(GLsizeiptr(zeros_leaves.size() * sizeof(float)), zeros_leaves.data(),
                     GL_DYNAMIC_STORAGE_BIT);

    vao = gl::VertexArray::create();
    vao.vertex_buffer(0, vertices, 0, sizeof(Vertex));
    vao.attribute(0, 0, 3, GL_FLOAT, offsetof(Vertex, position));
    vao.attribute(1, 0, 3, GL_FLOAT, offsetof(Vertex, grid));
    glEnableVertexArrayAttrib(vao.id(), 2);
    glVertexArrayAttribIFormat(vao.id(), 2, 1, GL_UNSIGNED_INT, offsetof(Vertex, node));
    glVertexArrayAttribBinding(vao.id(), 2, 0);
    vao.attribute(3, 0, 2, GL_FLOAT, offsetof(Vertex, st));
    glVertexArrayElementBuffer(vao.id(), indices.id());

    leaf_values.assign(3 * leaf_count, 0.f);
    node_sums.assign(node_count, glm::vec4(0.f));
    node_values.assign(3 * node_count, 0.f);
    built = true;
}

void SolutionRenderer::Impl::compute_colours(const Hierarchy& h, const RenderOptions& o) {
    const Scene& s = *scene;
    const bool irradiance = o.quantity == RenderOptions::Quantity::Irradiance;
    const bool smooth = o.shading == RenderOptions::Shading::Smooth;
    const dvec3 ambient = o.ambient ? h.unshot_estimate() : dvec3(0.0);
    if (smooth) std::fill(node_sums.begin(), node_sums.end(), glm::vec4(0.f));
    std::array<std::uint32_t, 4> c{};
    for (std::size_t p = 0; p < s.polygons.size(); ++p) {
        const PolygonGrid& g = grids[p];
        const Material& m = s.material_of(s.polygons[p]);
        // Display value = Be + rho (E + ambient) for radiosity, E + ambient for irradiance.
        // Textured (smooth): rho (E + ambient) alone; the shader adds Be and the texel factor.
        // Flat: every leaf's own value, with its mean reflectance.
        const bool detail = textured[p] && !irradiance;
        const glm::vec3 Be =
            irradiance || (detail && smooth) ? glm::vec3(0.f) : glm::vec3(m.exitance());
        const glm::vec3 rho = irradiance ? glm::vec3(1.f) : glm::vec3(m.rho);
        const glm::vec3 amb(ambient);
        // A pushed polygon holds all its light in the leaves' H (and dI = 0); otherwise ask the
        // hierarchy, which adds the ancestors' unpushed dI.
        const bool pushed = !h.needs_push_pull(std::uint32_t(p));
        const std::uint32_t leaves = g.n * g.n;
        for (std::uint32_t i = 0; i < leaves; ++i) {
            const PatchAddress a{std::uint32_t(p), g.depth, i};
            const Hierarchy::Node& node = h.node(a);
            const glm::vec3 E = pushed ? node.H + node.dI : glm::vec3(h.irradiance_shot(a));
            const glm::vec3 value =
                Be + (detail && !smooth ? glm::vec3(h.reflectance(a)) : rho) * (E + amb);
            if (!smooth) {
                float* out = &leaf_values[3 * (std::size_t(g.leaf_base) + i)];
                out[0] = value.r, out[1] = value.g, out[2] = value.b;
                continue;
            }
            const glm::vec4 w(node.area * value, node.area);
            const int k = leaf_corners(g, i, c);
            for (int j = 0; j < k; ++j) node_sums[vertex_node[g.vertex_base + c[j]]] += w;
        }
    }
    if (smooth) {
        for (std::size_t k = 0; k < node_count; ++k) {
            const glm::vec4& w = node_sums[k];
            const glm::vec3 v = w.w > 0 ? glm::vec3(w) / w.w : glm::vec3(0.f);
            node_values[3 * k] = v.r, node_values[3 * k + 1] = v.g, node_values[3 * k + 2] = v.b;
        }
        glNamedBufferSubData(node_rgb.id(), 0, GLsizeiptr(node_values.size() * sizeof(float)),
                             node_values.data());
    } else {
        glNamedBufferSubData(leaf_rgb.id(), 0, GLsizeiptr(leaf_values.size() * sizeof(float)),
                             leaf_values.data());
    }
}

glm::mat4 SolutionRenderer::Impl::view_projection(const Camera& camera, int width,
                                                  int height) const {
    const double aspect = double(std::max(width, 1)) / double(std::max(height, 1));
    const glm::dmat4 view = glm::lookAt(camera.eye - origin, camera.target - origin, camera.up);
    const double near = 1e-5 * diagonal;
    return reversed_z_perspective(glm::radians(camera.fov_y_deg), aspect, near) * glm::mat4(view);
}

void SolutionRenderer::Impl::draw_scene(const Camera& camera, const RenderOptions& o, int width,
                                        int height) {
    const glm::mat4 vp = view_projection(camera, width, height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_TRUE);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    if (o.two_sided) {
        glDisable(GL_CULL_FACE);
    } else {
        glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
    }
    glDisable(GL_BLEND);
    glFrontFace(GL_CCW);
    glUseProgram(program.id());
    glBindVertexArray(vao.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, node_rgb.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, triangle_leaf.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, leaf_rgb.id());
    glUniformMatrix4fv(0, 1, GL_FALSE, glm::value_ptr(vp));
    glUniform1i(1, o.shading == RenderOptions::Shading::Flat ? 1 : 0);
    glUniform1i(2, o.patch_edges ? 1 : 0);
    glUniform1f(3, float(o.scale));
    glUniform1i(4, o.tone_map ? 1 : 0);
    glUniform1f(5, float(kReinhardWhite));
    glUniform4f(6, 0.f, 0.f, 0.f, 0.f);
    const bool detail = o.quantity == RenderOptions::Quantity::Radiosity &&
                        o.shading == RenderOptions::Shading::Smooth;
    for (const DrawRun& r : runs) {
        const bool tex = detail && r.texture >= 0;
        glUniform1i(7, tex ? 1 : 0);
        glUniform3f(8, r.emitted.r, r.emitted.g, r.emitted.b);
        glUniform1ui(9, r.first_triangle);
        if (tex) glBindTextureUnit(0, textures[std::size_t(r.texture)].id());
        glDrawElements(GL_TRIANGLES, GLsizei(r.index_count), GL_UNSIGNED_INT,
                       reinterpret_cast<const void*>(r.first_index * sizeof(std::uint32_t)));
    }
    glBindTextureUnit(0, 0);
    if (o.highlight) draw_highlight(camera, *o.highlight, o.highlight_colour, width, height);
}

// The patch's polygon (tint, alpha kHighlightTint) and its outline (opaque), on top of whatever
// is in the framebuffer: no depth test. Core profiles have no wide lines, so the one-pixel
// outline is drawn four times with the viewport shifted by (0|1, 0|1) pixels: 2 pixels wide.
void SolutionRenderer::Impl::draw_highlight(const Camera& camera, const PatchAddress& a,
                                            const dvec3& colour, int width, int height) {
    constexpr float kHighlightTint = 0.35f;
    const Scene& s = *scene;
    if (a.polygon >= s.polygons.size() || a.level > std::uint32_t(kMaxDepth) ||
        !patch_valid(a.level, a.index))
        return;
    const PatchGeometry g = patch_geometry(s.polygons[a.polygon], a.level, a.index);
    Vertex v[4] = {};
    for (int k = 0; k < g.count; ++k) {
        const dvec3 q = g.corners[std::size_t(k)] - origin;
        v[k] = {{float(q.x), float(q.y), float(q.z)}, {0.f, 0.f, 0.f}, 0, {0.f, 0.f}};
    }
    if (!highlight_vao) {
        highlight_vertices = gl::Buffer::create();
        highlight_vertices.storage(GLsizeiptr(sizeof v), nullptr, GL_DYNAMIC_STORAGE_BIT);
        highlight_vao = gl::VertexArray::create();
        highlight_vao.vertex_buffer(0, highlight_vertices, 0, sizeof(Vertex));
        highlight_vao.attribute(0, 0, 3, GL_FLOAT, offsetof(Vertex, position));
        highlight_vao.attribute(1, 0, 3, GL_FLOAT, offsetof(Vertex, grid));
        glEnableVertexArrayAttrib(highlight_vao.id(), 2);
        glVertexArrayAttribIFormat(highlight_vao.id(), 2, 1, GL_UNSIGNED_INT,
                                   offsetof(Vertex, node));
        glVertexArrayAttribBinding(highlight_vao.id(), 2, 0);
    }
    glNamedBufferSubData(highlight_vertices.id(), 0, GLsizeiptr(sizeof v), v);
    const glm::mat4 vp = view_projection(camera, width, height);
    GLint viewport[4] = {};
    glGetIntegerv(GL_VIEWPORT, viewport);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glDisable(GL_CULL_FACE);
    glUseProgram(program.id());
    glBindVertexArray(highlight_vao.id());
    glUniformMatrix4fv(0, 1, GL_FALSE, glm::value_ptr(vp));
    glUniform1i(1, 1); // "flat": the vertex shader reads no node colours; the fragment
    glUniform1i(2, 0); // shader returns the highlight colour before any leaf lookup
    glUniform1i(7, 0);
    const glm::vec3 c(colour);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
    glUniform4f(6, c.r, c.g, c.b, kHighlightTint);
    glDrawArrays(GL_TRIANGLE_FAN, 0, g.count);
    glDisable(GL_BLEND);
    glUniform4f(6, c.r, c.g, c.b, 1.f);
    for (int k = 0; k < 4; ++k) {
        glViewport(viewport[0] + (k & 1), viewport[1] + (k >> 1), viewport[2], viewport[3]);
        glDrawArrays(GL_LINE_LOOP, 0, g.count);
    }
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
}

SolutionRenderer::SolutionRenderer(const Scene& scene) : impl_(std::make_unique<Impl>()) {
    impl_->scene = &scene;
    const Bounds b = scene.bounds();
    impl_->origin = 0.5 * (b.lo + b.hi);
    impl_->diagonal = std::max(b.diagonal(), 1e-300);
    impl_->program = gl::link_program({"solution.vert", "solution.frag"});
}

SolutionRenderer::~SolutionRenderer() = default;

SolutionRenderer::Stats SolutionRenderer::stats() const {
    return {impl_->leaf_count, impl_->vertex_count, impl_->node_count, impl_->index_count / 3};
}

namespace {
void check_size(const char* what, int v) {
    if (v < 16 || v > 8192)
        throw InputError(std::string("image ") + what + " " + std::to_string(v) +
                         " must be in 16..8192 pixels");
}
} // namespace

ImageRGB SolutionRenderer::render(const Hierarchy& h, const Camera& camera,
                                  const RenderOptions& options) {
    check_size("width", options.width);
    check_size("height", options.height);
    Impl& m = *impl_;
    const gl::StateGuard guard;
    m.ensure_geometry(h);
    m.compute_colours(h, options);
    const int w = options.width, ht = options.height;
    if (!m.target.fbo || m.target.width != w || m.target.height != ht)
        m.target = gl::FloatTarget::create(w, ht);
    const float bg[4] = {float(options.background.r), float(options.background.g),
                         float(options.background.b), 1.f};
    glClearNamedFramebufferfv(m.target.fbo.id(), GL_COLOR, 0, bg);
    glClearNamedFramebufferfi(m.target.fbo.id(), GL_DEPTH_STENCIL, 0, 0.0f,
                              0); // reversed Z: far = 0
    glBindFramebuffer(GL_FRAMEBUFFER, m.target.fbo.id());
    glViewport(0, 0, w, ht);
    m.draw_scene(camera, options, w, ht);

    m.readback.resize(std::size_t(w) * ht * 4);
    glNamedFramebufferReadBuffer(m.target.fbo.id(), GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, w, ht, GL_RGBA, GL_FLOAT, m.readback.data());
    ImageRGB image(w, ht);
    for (int y = 0; y < ht; ++y) { // GL row 0 is the bottom
        const float* src = &m.readback[std::size_t(ht - 1 - y) * w * 4];
        float* dst = image.at(0, y);
        for (int x = 0; x < w; ++x) {
            dst[3 * x] = src[4 * x];
            dst[3 * x + 1] = src[4 * x + 1];
            dst[3 * x + 2] = src[4 * x + 2];
        }
    }
    return image;
}

void SolutionRenderer::draw(const Hierarchy& h, const Camera& camera, const RenderOptions& options,
                            int viewport_width, int viewport_height) {
    Impl& m = *impl_;
    const gl::StateGuard guard;
    m.ensure_geometry(h);
    m.compute_colours(h, options);
    const float bg[4] = {float(options.background.r), float(options.background.g),
                         float(options.background.b), 1.f};
    const float far_depth = 0.f; // reversed Z
    glDepthMask(GL_TRUE);
    glClearBufferfv(GL_COLOR, 0, bg);
    glClearBufferfv(GL_DEPTH, 0, &far_depth);
    m.draw_scene(camera, options, viewport_width, viewport_height);
}

void SolutionRenderer::draw_highlight(const Camera& camera, const PatchAddress& patch,
                                      const dvec3& colour, int viewport_width,
                                      int viewport_height) {
    const gl::StateGuard guard;
    impl_->draw_highlight(camera, patch, colour, viewport_width, viewport_height);
}

} // namespace hemirad
