// hemirad scene: what was loaded.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "cli/cli_options.h"
#include "commands.h"
#include "hemirad/error.h"
#include "hemirad/json.h"
#include "hemirad/report.h"

namespace hemirad::cli {

void print_warnings(const Scene& scene, bool quiet) {
    print_scene_warnings("hemirad", scene, quiet);
}

namespace {

/// Per glazing group (glazing.h): its panes, their area and transmittance.
struct GlazingGroup {
    std::string name;
    long panes = 0;
    double area = 0;
    PaneTransmittance transmittance;
};

std::vector<GlazingGroup> glazing_groups(const Scene& scene) {
    std::vector<GlazingGroup> out;
    for (const GlazingPane& g : scene.glazing) {
        const std::string& name = scene.groups[g.polygon.group];
        auto it = std::find_if(out.begin(), out.end(),
                               [&](const GlazingGroup& o) { return o.name == name; });
        if (it == out.end()) it = out.insert(out.end(), {name, 0, 0.0, g.transmittance});
        ++it->panes;
        it->area += g.polygon.area;
    }
    return out;
}

} // namespace

int cmd_scene(int argc, char** argv) {
    std::string name, obj_out;
    bool json = false;
    BuiltinOptions builtin;
    ObjOptions obj;
    ArgParser args("hemirad scene", "hemirad scene SCENE [--json] [--obj FILE.obj] [options]",
                   "Loads a scene and prints what it holds; writes it as OBJ/MTL with --obj.");
    args.positional(
        "SCENE", &name,
        std::string("OBJ or glTF (.gltf, .glb) file, SCENE.json (OBJ or glTF files, luminaires, "
                    "cameras) or built-in scene (") +
            builtin_names() + ")");
    args.flag("--json", &json, "print JSON instead of text");
    args.option("--obj", &obj_out, "FILE.obj",
                "also write the scene as OBJ, with its materials in FILE.mtl beside it (how "
                "the files in assets/ are made from the built-in scenes)");
    long points = 0;
    std::string points_out;
    args.option("--surface-points", &points, "N",
                "write about N points spread over every polygon (x,y,z,nx,ny,nz; the input of "
                "--probes) to --points-out");
    long random_points = 0;
    args.option("--random-points", &random_points, "N",
                "write N points drawn at random, uniformly by area over all surfaces (x,y,z,"
                "nx,ny,nz) to --points-out");
    args.option("--points-out", &points_out, "FILE.csv",
                "where --surface-points or --random-points go");
    add_scene_options(args, builtin, obj);
    if (!args.parse(argc, argv, 2)) return 0;
    if (points > 0 && random_points > 0)
        throw InputError("--surface-points and --random-points: give one of them");
    if ((points > 0 || random_points > 0) != !points_out.empty())
        throw InputError("--surface-points N (or --random-points N) and --points-out FILE.csv "
                         "go together");
    if (points < 0 || points > 100'000'000)
        throw InputError("--surface-points " + std::to_string(points) + " must be in 1..1e8");
    if (random_points < 0 || random_points > 100'000'000)
        throw InputError("--random-points " + std::to_string(random_points) + " must be in 1..1e8");

    const Scene scene = load_scene(name, builtin, obj);
    if (points > 0 || random_points > 0) {
        const std::vector<Probe> probes =
            points > 0 ? surface_points(scene, std::size_t(points))
                       : random_surface_points(scene, std::size_t(random_points));
        write_text_file(points_out, probe_points_csv(probes));
        std::fprintf(stderr, "hemirad: wrote %zu surface points to %s\n", probes.size(),
                     points_out.c_str());
        return 0;
    }
    if (!obj_out.empty()) {
        const std::string mtl = write_obj(scene, obj_out);
        std::fprintf(stderr, "hemirad: wrote %s and %s\n", obj_out.c_str(), mtl.c_str());
    }
    const Bounds b = scene.bounds();
    const dvec3 power = scene.emitted_power();
    std::size_t two_sided = 0;
    for (const Polygon& p : scene.polygons) two_sided += p.twin != kNoTwin ? 1 : 0;
    if (json) {
        Json j = Json::object();
        j["source"] = scene.source;
        j["polygons"] = scene.polygons.size();
        j["triangles"] = scene.triangle_count();
        j["quads"] = scene.quad_count();
        j["two_sided_polygons"] = two_sided;
        j["total_area"] = scene.total_area();
        j["emitted_power"] = power;
        j["surface_power"] = scene.surface_power();
        j["luminaire_power"] = scene.luminaire_power();
        j["bounds"]["min"] = b.lo;
        j["bounds"]["max"] = b.hi;
        Json mats = Json::array();
        for (const Material& m : scene.materials) {
            Json o = Json::object();
            o["name"] = m.name;
            o["rho"] = m.rho;
            o["Ke"] = m.Ke;
            mats.push_back(o);
        }
        j["materials"] = mats;
        Json groups = Json::array();
        for (std::size_t g = 0; g < scene.groups.size(); ++g) {
            double area = 0;
            long count = 0;
            dvec3 gp(0.0);
            for (const Polygon& p : scene.polygons)
                if (p.group == g) {
                    area += p.area;
                    ++count;
                    gp += scene.material_of(p).exitance() * p.area;
                }
            Json o = Json::object();
            o["name"] = scene.groups[g];
            o["polygons"] = count;
            o["area"] = area;
            o["emitted_power"] = gp;
            groups.push_back(o);
        }
        j["groups"] = groups;
        Json sched = luminaire_schedule(scene);
        j["installed_lumens"] = sched["installed_lumens"];
        j["luminaires"] = sched["luminaires"];
        if (scene.sun) {
            Json o = Json::object();
            o["direction"] = scene.sun->direction;
            o["altitude"] = scene.sun->altitude_deg;
            o["azimuth"] = scene.sun->azimuth_deg;
            o["illuminance"] = scene.sun->illuminance;
            j["sun"] = o;
        }
        if (scene.sky) {
            Json o = Json::object();
            o["model"] = sky_model_name(scene.sky->model);
            o["illuminance"] = scene.sky->illuminance;
            o["ground_reflectance"] = scene.sky->ground_reflectance;
            o["zenith_luminance"] = scene.sky->luminance(scene.sky->up);
            o["ground_luminance"] = scene.sky->ground_luminance();
            o["horizon_blend"] = scene.sky->horizon_blend;
            j["sky"] = o;
        }
        if (!scene.glazing.empty()) {
            Json gl = Json::array();
            for (const GlazingGroup& g : glazing_groups(scene)) {
                Json o = Json::object();
                o["group"] = g.name;
                o["panes"] = g.panes;
                o["area"] = g.area;
                o["transmittance"] = g.transmittance.normal;
                o["angular"] = g.transmittance.angular;
                gl.push_back(o);
            }
            j["glazing"] = gl;
        }
        Json cams = Json::array();
        for (const Camera& c : scene.cameras) cams.push_back(c.name);
        j["cameras"] = cams;
        Json warnings = Json::array();
        for (const std::string& w : scene.warnings) warnings.push_back(w);
        j["warnings"] = warnings;
        std::cout << j.dump() << "\n";
        return 0;
    }
    print_warnings(scene, false);
    std::printf("scene      %s\n", scene.source.c_str());
    std::printf("polygons   %zu (%zu triangles, %zu quads)\n", scene.polygons.size(),
                scene.triangle_count(), scene.quad_count());
    if (two_sided > 0)
        std::printf(
            "two-sided  %zu polygons (each side a polygon of its own, both counted above)\n",
            two_sided);
    std::printf("area       %.6g unit^2\n", scene.total_area());
    std::printf("emitted    %.6g %.6g %.6g W (RGB)\n", power.x, power.y, power.z);
    std::printf("bounds     (%.6g, %.6g, %.6g) .. (%.6g, %.6g, %.6g)\n", b.lo.x, b.lo.y, b.lo.z,
                b.hi.x, b.hi.y, b.hi.z);
    std::printf("materials  %zu\n", scene.materials.size());
    for (const Material& m : scene.materials)
        std::printf("  %-16s rho (%.3f %.3f %.3f)  Ke (%.4g %.4g %.4g)\n", m.name.c_str(), m.rho.x,
                    m.rho.y, m.rho.z, m.Ke.x, m.Ke.y, m.Ke.z);
    std::printf("groups     %zu:", scene.groups.size());
    for (const std::string& g : scene.groups) std::printf(" %s", g.c_str());
    std::printf("\n");
    if (!scene.luminaires.empty()) {
        double total = 0;
        for (const Luminaire& l : scene.luminaires) total += l.lumens();
        std::printf("luminaires %zu, %.6g lm installed\n", scene.luminaires.size(), total);
        for (const Luminaire& l : scene.luminaires) {
            std::printf("  %-12s %-7s %9.6g lm  at (%.4g, %.4g, %.4g), %.6g cd max%s%s",
                        l.name.c_str(), l.kind.c_str(), l.lumens(), l.position.x, l.position.y,
                        l.position.z, l.multiplier * l.distribution.max_candela(),
                        l.file.empty() ? "" : "  ", l.file.c_str());
            const LuminousOpening& o = l.opening;
            if (o.round)
                std::printf(", opening %.3g m across", o.length);
            else if (o.size() > 0)
                std::printf(", opening %.3g x %.3g m", o.length, o.width);
            std::printf("\n");
        }
    }
    if (scene.sun) {
        const Sun& s = *scene.sun;
        const auto c = [](double x) { return std::abs(x) < 5e-5 ? 0.0 : x; }; // no "-0.0000"
        std::printf("sun        towards (%.4f, %.4f, %.4f), altitude %.2f deg, azimuth %.2f deg "
                    "(from north, clockwise), E_n %.6g lx%s\n",
                    c(s.direction.x), c(s.direction.y), c(s.direction.z), s.altitude_deg,
                    s.azimuth_deg, s.illuminance,
                    s.normal_irradiance() > 0 ? "" : " (below the horizon: dark)");
    }
    if (scene.sky) {
        const Sky& k = *scene.sky;
        std::printf("sky        %s, E_h %.6g lx (horizontal, sky alone), zenith %.6g cd/m2, "
                    "ground reflectance %.3g (%.6g cd/m2), horizon %s\n",
                    sky_model_name(k.model), k.illuminance, k.luminance(k.up), k.ground_reflectance,
                    k.ground_luminance(), k.horizon_blend ? "blended (as Radiance)" : "sharp");
    }
    for (const GlazingGroup& g : glazing_groups(scene))
        std::printf(
            "glazing    %s: %ld pane%s, %.6g unit^2, transmittance %.3g at normal "
            "incidence%s\n",
            g.name.c_str(), g.panes, g.panes == 1 ? "" : "s", g.area, g.transmittance.normal,
            g.transmittance.angular ? ", less at grazing angles (Fresnel)" : " at every angle");
    return 0;
}

} // namespace hemirad::cli
