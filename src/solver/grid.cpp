// Calculation grids over planar surface groups (see grid.h for the geometry and units).
#include "hemirad/grid.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/parse.h"
#include "hemirad/error.h"
#include "hemirad/image.h"
#include "hemirad/readout.h"

namespace hemirad {

namespace {

double lum(const dvec3& E) {
    return luminance(E.x, E.y, E.z);
}

int parse_count(const std::string& s, const std::string& text) {
    if (s.empty() || s.size() > 6 || s.find_first_not_of("0123456789") != std::string::npos)
        throw InputError("--grid '" + text + "': expected GROUP:NXxNY, e.g. floor:20x10");
    const int n = int(*parse_integer(s)); // at most 6 digits: always one
    if (n < 1 || n > 10000)
        throw InputError("--grid '" + text + "': " + s + " points must be in 1..10000");
    return n;
}

} // namespace

GridSpec parse_grid_spec(const std::string& text) {
    const auto colon = text.rfind(':');
    if (colon == std::string::npos || colon == 0)
        throw InputError("--grid '" + text + "': expected GROUP:NXxNY, e.g. floor:20x10");
    GridSpec g;
    g.group = text.substr(0, colon);
    const std::string dims = text.substr(colon + 1);
    std::size_t sep = dims.find_first_of("xX");
    std::size_t sep_len = 1;
    if (sep == std::string::npos) {
        sep = dims.find("\xc3\x97"); // U+00D7 MULTIPLICATION SIGN in UTF-8
        sep_len = 2;
    }
    if (sep == std::string::npos)
        throw InputError("--grid '" + text + "': expected GROUP:NXxNY, e.g. floor:20x10");
    g.nx = parse_count(dims.substr(0, sep), text);
    g.ny = parse_count(dims.substr(sep + sep_len), text);
    if (long(g.nx) * g.ny > kMaxGridPoints)
        throw InputError("--grid '" + text + "': " + std::to_string(long(g.nx) * g.ny) +
                         " points; at most " + std::to_string(kMaxGridPoints) + " per grid");
    return g;
}

std::vector<std::uint32_t> grid_polygons(const Scene& scene, const GridSpec& spec) {
    const int group = scene.find_group(spec.group);
    if (group < 0) {
        std::string names;
        for (const std::string& n : scene.groups) names += (names.empty() ? "" : ", ") + n;
        throw InputError("--grid: no surface group '" + spec.group + "' in " + scene.source +
                         " (groups: " + names + ")");
    }
    // A two-sided group: the grid lies on the side the file's normals face (the twins, added
    // after the file's polygons, face the other way: Polygon::twin). A face paired with a
    // modelled back in another group (make_two_sided) is this group's whatever its index.
    std::vector<std::uint32_t> polys;
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p) {
        const Polygon& poly = scene.polygons[p];
        if (poly.group == std::uint32_t(group) &&
            (poly.twin == kNoTwin || poly.twin > p ||
             scene.polygons[poly.twin].group != std::uint32_t(group)))
            polys.push_back(p);
    }
    HEMIRAD_CHECK(!polys.empty());
    const Polygon& first = scene.polygons[polys[0]];
    // Coplanar and facing the same way, within a tolerance relative to the scene's size.
    const double tol = 1e-6 * std::max(scene.bounds().diagonal(), 1e-300);
    for (std::uint32_t p : polys) {
        const Polygon& poly = scene.polygons[p];
        bool planar = glm::dot(poly.normal, first.normal) > 1.0 - 1e-6;
        for (int k = 0; k < poly.count && planar; ++k)
            planar = std::abs(glm::dot(poly.v[k] - first.v[0], first.normal)) <= tol;
        if (!planar)
            throw InputError("--grid: surface group '" + spec.group + "' is not planar: polygon " +
                             std::to_string(p) + " is not in the plane of polygon " +
                             std::to_string(polys[0]) +
                             " (or faces another way); a grid needs "
                             "coplanar polygons");
    }
    return polys;
}

GridResult evaluate_grid(const Hierarchy& h, const GridSpec& spec, const FinalGather* gather) {
    const Scene& scene = h.scene();
    const std::vector<std::uint32_t> polys = grid_polygons(scene, spec);
    GridResult r;
    r.spec = spec;
    const Polygon& first = scene.polygons[polys[0]];
    r.normal = first.normal;
    dvec3 u = first.v[1] - first.v[0];
    u -= glm::dot(u, r.normal) * r.normal;
    r.axis_u = glm::normalize(u);
    r.axis_v = glm::cross(r.normal, r.axis_u);
    double lo_u = 1e300, hi_u = -1e300, lo_v = 1e300, hi_v = -1e300;
    for (std::uint32_t p : polys) {
        const Polygon& poly = scene.polygons[p];
        for (int k = 0; k < poly.count; ++k) {
            const dvec3 d = poly.v[k] - first.v[0];
            lo_u = std::min(lo_u, glm::dot(d, r.axis_u));
            hi_u = std::max(hi_u, glm::dot(d, r.axis_u));
            lo_v = std::min(lo_v, glm::dot(d, r.axis_v));
            hi_v = std::max(hi_v, glm::dot(d, r.axis_v));
        }
    }
    r.origin = first.v[0] + lo_u * r.axis_u + lo_v * r.axis_v;
    r.width = hi_u - lo_u;
    r.height = hi_v - lo_v;

    // Bin the polygons by their bounding boxes over the cells (CSR lists in polygon order), so
    // that each point tests only the polygons whose box holds it: O(points + covered cells).
    const int nx = spec.nx, ny = spec.ny;
    const double cw = r.width / nx, ch = r.height / ny;
    const auto cell_range = [](double lo, double hi, double size, int n, int& a, int& b) {
        const double eps = 1e-9 * n;
        a = size > 0 ? int(std::floor(lo / size - eps)) : 0;
        b = size > 0 ? int(std::floor(hi / size + eps)) : n - 1;
        a = std::clamp(a, 0, n - 1);
        b = std::clamp(b, 0, n - 1);
    };
    struct Box {
        int i0, i1, j0, j1;
    };
    std::vector<Box> boxes(polys.size());
    std::vector<std::uint32_t> start(std::size_t(nx) * ny + 1, 0);
    for (std::size_t k = 0; k < polys.size(); ++k) {
        const Polygon& poly = scene.polygons[polys[k]];
        double u0 = 1e300, u1 = -1e300, v0 = 1e300, v1 = -1e300;
        for (int c = 0; c < poly.count; ++c) {
            const dvec3 d = poly.v[c] - r.origin;
            u0 = std::min(u0, glm::dot(d, r.axis_u)), u1 = std::max(u1, glm::dot(d, r.axis_u));
            v0 = std::min(v0, glm::dot(d, r.axis_v)), v1 = std::max(v1, glm::dot(d, r.axis_v));
        }
        Box& b = boxes[k];
        cell_range(u0, u1, cw, nx, b.i0, b.i1);
        cell_range(v0, v1, ch, ny, b.j0, b.j1);
        for (int j = b.j0; j <= b.j1; ++j)
            for (int i = b.i0; i <= b.i1; ++i) ++start[std::size_t(j) * nx + i + 1];
    }
    for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
    std::vector<std::uint32_t> cell_polys(start.back());
    {
        std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
        for (std::size_t k = 0; k < polys.size(); ++k)
            for (int j = boxes[k].j0; j <= boxes[k].j1; ++j)
                for (int i = boxes[k].i0; i <= boxes[k].i1; ++i)
                    cell_polys[fill[std::size_t(j) * nx + i]++] = polys[k];
    }

    r.points.reserve(std::size_t(nx) * ny);
    double y_sum = 0;
    dvec3 e_sum(0.0);
    for (int j = 0; j < ny; ++j) {
        for (int i = 0; i < nx; ++i) {
            GridPoint gp;
            gp.i = i;
            gp.j = j;
            gp.position = r.origin + (i + 0.5) / nx * r.width * r.axis_u +
                          (j + 0.5) / ny * r.height * r.axis_v;
            const std::size_t cell = std::size_t(j) * nx + i;
            for (std::uint32_t c = start[cell]; c < start[cell + 1]; ++c) {
                const std::uint32_t p = cell_polys[c];
                double pu = 0, pv = 0;
                if (!polygon_uv(scene.polygons[p], gp.position, pu, pv, 1e-9)) continue;
                SurfacePoint sp{p, std::clamp(pu, 0.0, 1.0), std::clamp(pv, 0.0, 1.0), 0.0};
                gp.on_surface = true;
                gp.polygon = p;
                if (!gather) gp.E = irradiance_at(h, sp);
                break;
            }
            r.points.push_back(gp);
        }
    }
    if (gather) {
        std::vector<GatherPoint> queries;
        for (const GridPoint& gp : r.points)
            if (gp.on_surface) queries.push_back({gp.position, r.normal, gp.polygon});
        const std::vector<GatherValue> values = gather->at(queries);
        std::size_t k = 0;
        for (GridPoint& gp : r.points)
            if (gp.on_surface) gp.E = values[k++].E();
    }
    for (const GridPoint& gp : r.points) {
        if (gp.on_surface) {
            const double y = lum(gp.E);
            if (r.evaluated == 0) {
                r.Y_min = r.Y_max = y;
                r.E_min = r.E_max = gp.E;
            } else {
                r.Y_min = std::min(r.Y_min, y);
                r.Y_max = std::max(r.Y_max, y);
                r.E_min = glm::min(r.E_min, gp.E);
                r.E_max = glm::max(r.E_max, gp.E);
            }
            y_sum += y;
            e_sum += gp.E;
            ++r.evaluated;
        } else {
            ++r.skipped;
        }
    }
    if (r.evaluated > 0) {
        r.Y_avg = y_sum / double(r.evaluated);
        r.E_avg = e_sum / double(r.evaluated);
    }
    r.U0 = r.Y_avg > 0 ? r.Y_min / r.Y_avg : 0.0;
    r.min_over_max = r.Y_max > 0 ? r.Y_min / r.Y_max : 0.0;
    return r;
}

std::vector<double> daylight_factors(const GridResult& g, double daylight_lux) {
    std::vector<double> df;
    for (const GridPoint& p : g.points)
        if (p.on_surface) df.push_back(100 * kLumensPerWatt * lum(p.E) / daylight_lux);
    return df;
}

namespace {

struct DaylightStats {
    std::size_t points = 0;
    double avg = 0, min = 0, median = 0, max = 0; ///< [%]
    double share[3] = {0, 0, 0};                  ///< fractions with DF >= 1, 2, 3 %
};

DaylightStats daylight_stats(const GridResult& g, double daylight_lux) {
    std::vector<double> df = daylight_factors(g, daylight_lux);
    DaylightStats d;
    d.points = df.size();
    if (df.empty()) return d;
    std::sort(df.begin(), df.end());
    double sum = 0;
    for (double v : df) sum += v;
    const std::size_t n = df.size();
    d.avg = sum / double(n);
    d.min = df.front();
    d.median = n % 2 ? df[n / 2] : 0.5 * (df[n / 2 - 1] + df[n / 2]);
    d.max = df.back();
    // DF >= k %, to 1e-9 %: a point at exactly k % after the 683 / E_h round trip counts.
    for (int k = 0; k < 3; ++k)
        d.share[k] =
            double(df.end() - std::lower_bound(df.begin(), df.end(), double(k + 1) - 1e-9)) /
            double(n);
    return d;
}

} // namespace

Json grid_json(const GridResult& g, bool lux, double daylight_lux) {
    Json o = Json::object();
    o["group"] = g.spec.group;
    o["nx"] = g.spec.nx;
    o["ny"] = g.spec.ny;
    o["points"] = g.evaluated;
    o["skipped"] = g.skipped;
    o["E_min"] = g.Y_min;
    o["E_avg"] = g.Y_avg;
    o["E_max"] = g.Y_max;
    o["U0"] = g.U0;
    o["Emin/Emax"] = g.min_over_max;
    o["E_rgb"]["min"] = g.E_min;
    o["E_rgb"]["avg"] = g.E_avg;
    o["E_rgb"]["max"] = g.E_max;
    if (lux) {
        o["lux"]["min"] = kLumensPerWatt * g.Y_min;
        o["lux"]["avg"] = kLumensPerWatt * g.Y_avg;
        o["lux"]["max"] = kLumensPerWatt * g.Y_max;
    }
    if (daylight_lux > 0) {
        const DaylightStats d = daylight_stats(g, daylight_lux);
        Json o_df = Json::object();
        if (d.points > 0) {
            o_df["avg"] = d.avg;
            o_df["min"] = d.min;
            o_df["median"] = d.median;
            o_df["max"] = d.max;
            for (int k = 0; k < 3; ++k) o_df["share_ge_" + std::to_string(k + 1)] = d.share[k];
        }
        o["DF"] = o_df;
    }
    o["width"] = g.width;
    o["height"] = g.height;
    return o;
}

std::string grid_summary(const GridResult& g, bool lux, double daylight_lux) {
    const double k = lux ? kLumensPerWatt : 1.0;
    const char* unit = lux ? " lx" : " W/unit²";
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "%s %dx%d: Emin %.4g%s, Eavg %.4g%s, Emax %.4g%s, U0 = Emin/Eavg %.3f, "
                  "Emin/Emax %.3f",
                  g.spec.group.c_str(), g.spec.nx, g.spec.ny, k * g.Y_min, unit, k * g.Y_avg, unit,
                  k * g.Y_max, unit, g.U0, g.min_over_max);
    std::string line = buf;
    if (daylight_lux > 0) {
        const DaylightStats d = daylight_stats(g, daylight_lux);
        if (d.points > 0) {
            std::snprintf(buf, sizeof buf, ", DF avg %.3g %%, min %.3g %%, median %.3g %%", d.avg,
                          d.min, d.median);
            line += buf;
        }
    }
    return line;
}

std::string grids_csv(const std::vector<GridResult>& grids, bool lux, double daylight_lux) {
    const bool df = daylight_lux > 0;
    std::ostringstream s;
    s.precision(9);
    s << "group,i,j,x,y,z,E_r,E_g,E_b,E_Y" << (lux ? ",lux" : "") << (df ? ",DF" : "") << "\n";
    for (const GridResult& g : grids) {
        for (const GridPoint& p : g.points) {
            s << g.spec.group << "," << p.i << "," << p.j << "," << p.position.x << ","
              << p.position.y << "," << p.position.z << ",";
            if (!p.on_surface) {
                s << ",,," << (lux ? "," : "") << (df ? "," : "") << "\n";
                continue;
            }
            const double y = lum(p.E);
            s << p.E.x << "," << p.E.y << "," << p.E.z << "," << y;
            if (lux) s << "," << kLumensPerWatt * y;
            if (df) s << "," << 100 * kLumensPerWatt * y / daylight_lux;
            s << "\n";
        }
    }
    return s.str();
}

} // namespace hemirad
