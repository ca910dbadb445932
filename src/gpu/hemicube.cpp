#include "gpu/hemicube.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "core/projection.h"
#include "core/timer.h"
#include "gl/program.h"
#include "gl/state.h"
#include "gpu/acos_table.h"
#include "hemirad/error.h"

namespace hemirad::gpu {

namespace {

struct Vertex {
    float position[3];
    float param[2];
    float polygon;
};

struct PolygonGpu { // std430 layout of PolygonData in hemicube.frag
    float v[4][4];
    float normal[4];
    std::int32_t info[4];
};
static_assert(sizeof(PolygonGpu) == 96);

} // namespace

HemicubeLayout make_hemicube_layout(int res) {
    HEMIRAD_CHECK(res >= 2 && res % 2 == 0);
    HemicubeLayout L;
    L.res = res;
    L.width = 2 * res;
    L.height = res + res / 2;
    const int h = res / 2;
    L.faces[0] = {0, 0, res, res};
    L.faces[1] = {res, 0, res, h};
    L.faces[2] = {res, h, res, h};
    L.faces[3] = {0, res, res, h};
    L.faces[4] = {res, res, res, h};
    L.delta_ff.assign(std::size_t(L.width) * L.height, 0.f);
    const double d = 2.0 / res; // pixel side on a face at distance 1 spanning [-1, 1]
    const double pi = std::numbers::pi;
    for (int f = 0; f < 5; ++f) {
        const auto& face = L.faces[f];
        for (int j = 0; j < face.h; ++j)
            for (int i = 0; i < face.w; ++i) {
                const double x = -1 + (i + 0.5) * d;
                double w;
                if (f == 0) {
                    const double y = -1 + (j + 0.5) * d;
                    const double q = x * x + y * y + 1;
                    w = d * d / (pi * q * q);
                } else {
                    const double z = (j + 0.5) * d; // height above the shooter's plane
                    const double q = x * x + z * z + 1;
                    w = z * d * d / (pi * q * q);
                }
                L.delta_ff[std::size_t(face.y + j) * L.width + face.x + i] = float(w);
            }
    }
    return L;
}

HemicubeFrame hemicube_frame(const Shooter& shooter) {
    HemicubeFrame f;
    f.N = shooter.normal;
    const dvec3 e = shooter.geometry.corners[1] - shooter.geometry.corners[0];
    f.T = glm::normalize(e - glm::dot(e, f.N) * f.N);
    f.B = glm::cross(f.N, f.T);
    const dvec3 dirs[5] = {f.N, f.T, -f.T, f.B, -f.B};
    for (int k = 0; k < 5; ++k) {
        f.dir[k] = dirs[k];
        f.up[k] = k == 0 ? f.B : f.N;
    }
    return f;
}

long hemicube_pixel(const HemicubeLayout& L, const HemicubeFrame& f, const dvec3& d) {
    if (glm::dot(d, f.N) <= 0) return -1;
    // The face whose view direction is closest to d; glm::lookAt's screen x is dir x up.
    int face = 0;
    double best = -1;
    for (int k = 0; k < 5; ++k) {
        const double c = glm::dot(d, f.dir[k]);
        if (c > best) best = c, face = k;
    }
    const dvec3 screen_x = glm::cross(f.dir[face], f.up[face]);
    const double sx = glm::dot(d, screen_x) / best, sy = glm::dot(d, f.up[face]) / best;
    const auto& r = L.faces[face];
    const int i = std::clamp(int((sx + 1) * 0.5 * L.res), 0, r.w - 1);
    const int j = face == 0 ? std::clamp(int((sy + 1) * 0.5 * L.res), 0, r.h - 1)
                            : std::clamp(int(sy * 0.5 * L.res), 0, r.h - 1);
    return long(r.y + j) * L.width + r.x + i;
}

HemicubeRenderer::HemicubeRenderer(const Scene& scene, const Discretisation& disc,
                                   int max_resolution)
    : scene_(&scene), max_res_(max_resolution) {
    const Bounds b = scene.bounds();
    origin_ = 0.5 * (b.lo + b.hi);
    near_ = 1e-5 * b.diagonal();
    eps_ = 1e-9 * b.diagonal();
    for (std::uint32_t i = 0; i < scene.polygons.size(); i += kClusterSize) {
        Cluster c{i,
                  std::min<std::uint32_t>(i + kClusterSize, std::uint32_t(scene.polygons.size())),
                  dvec3(1e300), dvec3(-1e300)};
        for (std::uint32_t j = c.begin; j < c.end; ++j)
            for (int k = 0; k < scene.polygons[j].count; ++k) {
                c.lo = glm::min(c.lo, scene.polygons[j].v[k]);
                c.hi = glm::max(c.hi, scene.polygons[j].v[k]);
            }
        clusters_.push_back(c);
    }
    hidden_per_cluster_.assign(clusters_.size(), 0);
    twinned_cluster_.assign(clusters_.size(), 0);
    for (std::size_t i = 0; i < scene.polygons.size(); ++i)
        if (scene.polygons[i].twin != kNoTwin) twinned_cluster_[i / kClusterSize] = 1;

    // Vertices: every polygon as one triangle or two, with its (u,v) parameters.
    std::vector<Vertex> verts;
    std::vector<PolygonGpu> polys(scene.polygons.size());
    const auto vertex = [&](const dvec3& p, float u, float v, std::size_t id) {
        const dvec3 q = p - origin_;
        verts.push_back({{float(q.x), float(q.y), float(q.z)}, {u, v}, float(id)});
    };
    int max_depth = 0;
    for (std::size_t i = 0; i < scene.polygons.size(); ++i) {
        const Polygon& p = scene.polygons[i];
        first_.push_back(GLint(verts.size()));
        if (p.is_triangle()) {
            vertex(p.v[0], 0, 0, i);
            vertex(p.v[1], 1, 0, i);
            vertex(p.v[2], 0, 1, i);
        } else {
            vertex(p.v[0], 0, 0, i);
            vertex(p.v[1], 1, 0, i);
            vertex(p.v[2], 1, 1, i);
            vertex(p.v[0], 0, 0, i);
            vertex(p.v[2], 1, 1, i);
            vertex(p.v[3], 0, 1, i);
        }
        count_.push_back(GLsizei(verts.size()) - first_.back());
        PolygonGpu& g = polys[i];
        for (int k = 0; k < 4; ++k) {
            const dvec3 q = (k < p.count ? p.v[k] : p.v[0]) - origin_;
            g.v[k][0] = float(q.x), g.v[k][1] = float(q.y), g.v[k][2] = float(q.z), g.v[k][3] = 1;
        }
        g.normal[0] = float(p.normal.x), g.normal[1] = float(p.normal.y);
        g.normal[2] = float(p.normal.z), g.normal[3] = p.is_triangle() ? 1.f : 0.f;
        g.info[0] = disc.depth[i];
        g.info[1] = g.info[2] = g.info[3] = 0;
        max_depth = std::max(max_depth, int(disc.depth[i]));
    }
    vertices_ = gl::Buffer::create();
    vertices_.storage(GLsizeiptr(verts.size() * sizeof(Vertex)), verts.data(), 0);
    polygons_ = gl::Buffer::create();
    polygons_.storage(GLsizeiptr(polys.size() * sizeof(PolygonGpu)), polys.data(), 0);
    const std::vector<float> table = make_acos_table();
    acos_table_ = gl::Buffer::create();
    acos_table_.storage(GLsizeiptr(table.size() * sizeof(float)), table.data(), 0);

    vao_ = gl::VertexArray::create();
    vao_.vertex_buffer(0, vertices_, 0, sizeof(Vertex));
    vao_.attribute(0, 0, 3, GL_FLOAT, offsetof(Vertex, position));
    vao_.attribute(1, 0, 2, GL_FLOAT, offsetof(Vertex, param));
    vao_.attribute(2, 0, 1, GL_FLOAT, offsetof(Vertex, polygon));

    // What the GL driver can allocate: refuse, naming the option, rather than render into a
    // framebuffer that is incomplete or was never allocated.
    const int levels = max_depth + 1;
    const int base = 1 << max_depth;
    {
        GLint max_tex = 0, max_rb = 0, max_vp[2] = {0, 0};
        glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_tex);
        glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_rb);
        glGetIntegerv(GL_MAX_VIEWPORT_DIMS, max_vp);
        const long fb_w = 2L * max_res_, fb_h = max_res_ + max_res_ / 2;
        if (fb_w > max_tex || fb_w > max_rb || fb_w > max_vp[0] || fb_h > max_vp[1])
            throw InputError("--max-resolution (or --resolution) " + std::to_string(max_res_) +
                             ": its hemicube needs a " + std::to_string(fb_w) + "x" +
                             std::to_string(fb_h) + " framebuffer, but this GL driver allows " +
                             std::to_string(std::min<long>({max_tex, max_rb, max_vp[0]})) +
                             " pixels at most; use " +
                             std::to_string(std::min<long>({max_tex, max_rb, max_vp[0]}) / 2) +
                             " or less");
        if (base > max_tex)
            throw InputError("--max-depth " + std::to_string(max_depth) +
                             ": the patch-ID texture would be " + std::to_string(base) +
                             " texels wide, but this GL driver allows " + std::to_string(max_tex) +
                             "; use a smaller --max-depth");
        while (glGetError() != GL_NO_ERROR) {}
    }

    // Patch-ID texture: mip m of a 2^D texture holds, at texel (x,y), the patch (x, y, D-m).
    patch_ids_ = gl::Texture::create(GL_TEXTURE_2D);
    patch_ids_.storage_2d(levels, GL_RGBA16UI, base, base);
    std::vector<std::uint16_t> texels;
    for (int m = 0; m < levels; ++m) {
        const int size = base >> m;
        texels.resize(std::size_t(size) * size * 4);
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                std::uint16_t* t = &texels[(std::size_t(y) * size + x) * 4];
                t[0] = std::uint16_t(x), t[1] = std::uint16_t(y);
                t[2] = std::uint16_t(max_depth - m), t[3] = 0;
            }
        glTextureSubImage2D(patch_ids_.id(), m, 0, 0, size, size, GL_RGBA_INTEGER,
                            GL_UNSIGNED_SHORT, texels.data());
    }
    glTextureParameteri(patch_ids_.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
    glTextureParameteri(patch_ids_.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(patch_ids_.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(patch_ids_.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

    if (glGetError() == GL_OUT_OF_MEMORY) {
        const double mib = double(base) * base * 8 * 4 / 3 / (1 << 20);
        throw InputError(
            "the GL driver could not allocate the patch-ID texture (" + std::to_string(long(mib)) +
            " MiB): use a smaller --max-resolution "
            "(or --resolution; now " +
            std::to_string(max_res_) + ") or --max-depth (now " + std::to_string(max_depth) + ")");
    }
    // The largest hemicube's framebuffer now, so that a lack of memory shows at the start.
    target(make_hemicube_layout(max_res_));

    program_ = gl::link_program({"hemicube.vert", "hemicube.frag"});
}

GLuint HemicubeRenderer::target(const HemicubeLayout& layout) {
    for (const gl::FloatTarget& t : targets_)
        if (t.width == layout.width && t.height == layout.height) return t.fbo.id();
    try {
        targets_.push_back(gl::FloatTarget::create(layout.width, layout.height));
    } catch (const InputError& e) {
        throw InputError(std::string(e.what()) + " for the hemicube: use a smaller " +
                         "--max-resolution (or --resolution; now " + std::to_string(max_res_) +
                         ")");
    }
    return targets_.back().fbo.id();
}

void HemicubeRenderer::render(const Shooter& shooter, const HemicubeLayout& layout, double lod_bias,
                              int angle_method) {
    draw(shooter, layout, lod_bias, angle_method, false);
}

void HemicubeRenderer::render_polygon_ids(const Shooter& shooter, const HemicubeLayout& layout) {
    draw(shooter, layout, 0.0, 0, true);
}

void HemicubeRenderer::draw(const Shooter& shooter, const HemicubeLayout& layout, double lod_bias,
                            int angle_method, bool polygons_only) {
    HEMIRAD_CHECK_LE(layout.res, max_res_);
    const HemicubeFrame frame = hemicube_frame(shooter);
    const dvec3 N = frame.N;
    const dvec3 c = shooter.geometry.centre;

    // Near plane: far below any patch, above float noise.
    const double near = std::min(near_, 1e-3 * std::sqrt(std::max(shooter.geometry.area, 1e-300)));
    const dvec3 eye = c - origin_;
    const double eps = eps_;

    const GLuint fbo = target(layout);
    const gl::StateGuard guard; // restores what this changes (gl/state.h)
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glViewport(0, 0, layout.width, layout.height);
    glDisable(GL_SCISSOR_TEST); // the whole of the layout's own framebuffer: a fast clear
    const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(fbo, GL_COLOR, 0, zero);
    glClearNamedFramebufferfi(fbo, GL_DEPTH_STENCIL, 0, 0.0f, 0);
    glUseProgram(program_.id());
    glBindVertexArray(vao_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, polygons_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, acos_table_.id());
    glBindTextureUnit(0, patch_ids_.id());
    float corners[12] = {};
    for (int k = 0; k < shooter.geometry.count; ++k) {
        const dvec3 q = shooter.geometry.corners[k] - origin_;
        corners[3 * k] = float(q.x), corners[3 * k + 1] = float(q.y),
                    corners[3 * k + 2] = float(q.z);
    }
    glUniform3fv(2, 4, corners);
    glUniform1i(6, shooter.geometry.count);
    glUniform1f(7, float(lod_bias));
    glUniform1i(8, angle_method);
    glUniform1i(9, int(shooter.address.polygon));
    glUniform1i(10, polygons_only ? 1 : 0);
    glUniform3f(1, float(eye.x), float(eye.y), float(eye.z));

    drawn_ = ranges_ = 0;
    cull_seconds_ = 0;
    // Near groups of polygons first: the shader's early depth test (early_fragment_tests)
    // then rejects most hidden fragments before they are shaded. On llvmpipe, where shading
    // is most of a render, the courtyard's 1038 shots rendered in 29.4 s instead of 36.8 s.
    // Only which of two polygons at exactly the same depth wins a pixel depends on the order.
    const auto t_order = SteadyClock::now();
    near_first_.resize(clusters_.size());
    cluster_distance_.resize(clusters_.size());
    for (std::size_t i = 0; i < clusters_.size(); ++i) {
        const dvec3 d = glm::clamp(c, clusters_[i].lo, clusters_[i].hi) - c;
        cluster_distance_[i] = glm::dot(d, d);
        near_first_[i] = std::uint32_t(i);
    }
    std::stable_sort(near_first_.begin(), near_first_.end(), [&](std::uint32_t a, std::uint32_t b) {
        return cluster_distance_[a] < cluster_distance_[b];
    });
    cull_seconds_ += seconds_since(t_order);
    for (int f = 0; f < 5; ++f) {
        const auto& face = layout.faces[f];
        struct {
            dvec3 dir, up;
        } v{frame.dir[f], frame.up[f]};
        const glm::dmat4 view = glm::lookAt(dvec3(0.0), v.dir, v.up);
        const glm::mat4 proj = f == 0 ? reversed_z_frustum(-near, near, -near, near, near)
                                      : reversed_z_frustum(-near, near, 0, near, near);
        const glm::mat4 vp = proj * glm::mat4(view);
        // Per-face culling: a polygon is skipped if all its corners lie outside one of the
        // face's side planes (or behind the shooter's plane).
        const dvec3 side = glm::cross(v.dir, v.up); // screen x
        dvec3 planes[4] = {v.dir + side, v.dir - side, v.dir + v.up, v.dir - v.up};
        if (f != 0) planes[2] = v.up; // the bottom of a side face is the shooter's plane
        const auto t_cull = SteadyClock::now();
        draw_first_.clear();
        draw_count_.clear();
        // Range of dot(x - c, n) over a box: min and max over its corners.
        const auto box_range = [&](const Cluster& k, const dvec3& n) {
            const dvec3 a = (k.lo - c) * n, b = (k.hi - c) * n;
            const dvec3 lo = glm::min(a, b), hi = glm::max(a, b);
            return std::pair{lo.x + lo.y + lo.z, hi.x + hi.y + hi.z};
        };
        const std::uint32_t own = shooter.address.polygon;
        for (const std::uint32_t ki : near_first_) {
            const Cluster& k = clusters_[ki];
            // Wholly behind the shooter's plane, or outside a side plane: nothing to draw.
            // Wholly in front and inside every side plane: every polygon is drawn.
            const auto [nlo, nhi] = box_range(k, N);
            if (nhi <= eps) continue;
            bool all_in = nlo > eps, all_out = false;
            for (const dvec3& pl : planes) {
                const auto [lo, hi] = box_range(k, pl);
                all_out |= hi < -eps;
                all_in &= lo >= -eps;
            }
            if (all_out) continue;
            if (all_in && hidden_per_cluster_[ki] == 0 && !twinned_cluster_[ki]) {
                if (own >= k.begin && own < k.end) {
                    draw_polygons(k.begin, own);
                    draw_polygons(own + 1, k.end);
                } else {
                    draw_polygons(k.begin, k.end);
                }
                continue;
            }
            const bool some_hidden = hidden_per_cluster_[ki] > 0;
            for (std::uint32_t i = k.begin; i < k.end; ++i) {
                if (i == own) continue;
                const Polygon& p = scene_->polygons[i];
                if (some_hidden && hidden(i) &&
                    !(hidden_fronts_drawn_ && glm::dot(p.normal, c - p.v[0]) > eps))
                    continue;
                // A two-sided surface shows the eye the side that faces it: the back of a
                // twinned polygon is its twin's front, drawn instead (the two would z-fight).
                if (p.twin != kNoTwin && glm::dot(p.normal, p.v[0] - c) >= 0) continue;
                bool above = false;
                for (int j = 0; j < p.count; ++j) above |= glm::dot(p.v[j] - c, N) > eps;
                if (!above) continue;
                bool outside = false;
                for (const dvec3& pl : planes) {
                    bool all_out_p = true;
                    for (int j = 0; j < p.count && all_out_p; ++j)
                        all_out_p = glm::dot(p.v[j] - c, pl) < -eps;
                    if (all_out_p) {
                        outside = true;
                        break;
                    }
                }
                if (!outside) draw_polygons(i, i + 1);
            }
        }
        cull_seconds_ += seconds_since(t_cull);
        if (draw_first_.empty()) continue;
        ranges_ += draw_first_.size();
        glViewport(face.x, face.y, face.w, face.h);
        glUniformMatrix4fv(0, 1, GL_FALSE, glm::value_ptr(vp));
        glMultiDrawArrays(GL_TRIANGLES, draw_first_.data(), draw_count_.data(),
                          GLsizei(draw_first_.size()));
    }
    // Wait for the rasteriser here, so that the time of render() is the rendering and that
    // of read_back() the copy (the readback would wait anyway; nothing is lost).
    glFinish();
}

void HemicubeRenderer::set_hidden(const std::vector<std::uint32_t>& polygons, bool fronts_drawn) {
    for (std::uint32_t p : hidden_) hidden_per_cluster_[p / kClusterSize] = 0;
    hidden_ = polygons;
    hidden_fronts_drawn_ = fronts_drawn;
    std::sort(hidden_.begin(), hidden_.end());
    for (std::uint32_t p : hidden_) ++hidden_per_cluster_[p / kClusterSize];
}

void HemicubeRenderer::draw_polygons(std::uint32_t begin, std::uint32_t end) {
    if (begin >= end) return;
    drawn_ += end - begin;
    const GLint first = first_[begin];
    const GLsizei count = first_[end - 1] + count_[end - 1] - first;
    // Ranges are joined up to kMaxDrawVertices: Mesa's draw module (llvmpipe), on a draw
    // that needs clipping, goes over all of the draw's vertices at each flush of its small
    // vertex buffer, a cost that grows with the square of a draw's length (the courtyard's
    // solve: 17 % faster than with the ranges joined without limit).
    if (!draw_first_.empty() && draw_first_.back() + draw_count_.back() == first &&
        draw_count_.back() + count <= kMaxDrawVertices)
        draw_count_.back() += count;
    else
        draw_first_.push_back(first), draw_count_.push_back(count);
}

void HemicubeRenderer::read_back(const HemicubeLayout& layout, std::vector<float>& rgba) {
    rgba.resize(std::size_t(layout.width) * layout.height * 4);
    const GLuint fbo = target(layout);
    glNamedFramebufferReadBuffer(fbo, GL_COLOR_ATTACHMENT0);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, layout.width, layout.height, GL_RGBA, GL_FLOAT, rgba.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
}

} // namespace hemirad::gpu
