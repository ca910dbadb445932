#include "hemirad/report.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "core/line_reader.h"
#include "core/parse.h"
#include "hemirad/error.h"
#include "hemirad/image.h"
#include "hemirad/readout.h"
#include "output/atomic_file.h"

namespace hemirad {

Json luminaire_json(const Luminaire& l) {
    Json o = Json::object();
    o["name"] = l.name;
    o["kind"] = l.kind;
    if (!l.file.empty()) o["file"] = l.file;
    o["position"] = l.position;
    o["aim"] = l.aim;
    o["rotation"] = l.rotation;
    o["multiplier"] = l.multiplier;
    o["lumens"] = l.lumens();
    if (l.rated_lumens > 0) o["rated_lumens"] = l.rated_lumens;
    o["max_candela"] = l.multiplier * l.distribution.max_candela();
    o["symmetry"] = to_string(l.distribution.symmetry);
    if (l.opening.size() > 0) {
        Json op = Json::object(); // the luminous opening [m]: an area source up close
        op["length"] = l.opening.length;
        op["width"] = l.opening.width;
        op["height"] = l.opening.height;
        op["round"] = l.opening.round;
        o["opening"] = op;
    }
    return o;
}

Json luminaire_schedule(const Scene& scene) {
    Json o = Json::object();
    double total = 0;
    Json list = Json::array();
    for (const Luminaire& l : scene.luminaires) {
        total += l.lumens();
        list.push_back(luminaire_json(l));
    }
    o["installed_lumens"] = total;
    o["luminaires"] = list;
    return o;
}

Json solve_report(Solver& solver) {
    const Scene& scene = solver.scene();
    Hierarchy& h = solver.solution();
    Json j = Json::object();
    j["scene"] = scene.source;
    j["ff"] = solver.options().ff;
    j["polygons"] = scene.polygons.size();
    j["leaf_patches"] = h.leaf_count();
    j["nodes"] = h.node_count();
    j["bytes_per_leaf"] = h.bytes_per_leaf();
    j["shots"] = solver.shots();
    j["ranks"] = solver.ranks();
    if (solver.ranks() > 1) {
        // What the parallel rounds exchanged (docs/scaling.md): the sparse link lists, and what
        // a dense per-leaf sum of float RGB irradiance would have moved instead.
        const Solver::ParallelStats& ps = solver.parallel_stats();
        const double rounds = double(std::max(ps.rounds, 1L));
        Json p = Json::object();
        p["rounds"] = ps.rounds;
        p["bytes_per_round"] = ps.bytes / rounds;
        p["max_bytes_per_round"] = ps.max_bytes;
        p["dense_bytes_per_round"] = 12.0 * double(h.leaf_count());
        p["exchange_seconds"] = ps.seconds;
        p["exchange_seconds_per_round"] = ps.seconds / rounds;
        p["transfer_seconds_per_round"] = ps.transfer_seconds / rounds;
        j["parallel"] = p;
    }
    j["seconds"] = solver.seconds();
    j["emitted_power"] = solver.emitted_power();
    j["absorbed_power"] = solver.absorbed_power();
    j["escaped_power"] = solver.escaped_power();
    j["unshot_power"] = h.total_unshot_power();
    j["unshot_fraction"] = solver.unshot_fraction();
    j["error_bound"] = solver.error_bound();
    // In every read-out: the irradiance still to arrive from the unshot power (estimated).
    j["unshot_estimate"] = h.unshot_estimate();
    j["tolerance"] = solver.options().tolerance;
    j["converged"] = solver.converged();
    j["stop_reason"] = to_string(solver.stop_reason());
    const Solver::RowSumStats rs = solver.row_sums();
    j["row_sum"]["min"] = rs.min;
    j["row_sum"]["mean"] = rs.mean;
    j["row_sum"]["max"] = rs.max;
    j["row_sum"]["guarded"] = rs.guarded;
    j["quantities"] = "E = incident irradiance [W per scene unit^2], RGB";
    Json groups = Json::array();
    for (std::uint32_t g = 0; g < scene.groups.size(); ++g) {
        const GroupIrradiance gi = group_irradiance(h, g);
        Json o = Json::object();
        o["name"] = scene.groups[g];
        o["area"] = gi.area;
        o["E_avg"] = gi.E_avg;
        o["E_min"] = gi.E_min;
        o["E_max"] = gi.E_max;
        const dvec3 flux = gi.E_avg * gi.area;
        o["flux"] = flux;
        o["lumens"] = kLumensPerWatt * luminance(flux.x, flux.y, flux.z);
        groups.push_back(o);
    }
    j["groups"] = groups;
    if (!scene.luminaires.empty()) {
        Json sched = luminaire_schedule(scene);
        j["installed_lumens"] = sched["installed_lumens"];
        j["luminaires"] = sched["luminaires"];
    }
    return j;
}

Json solve_report(Solver& solver, const std::vector<GridResult>& grids, bool lux,
                  double daylight_lux) {
    Json j = solve_report(solver);
    if (daylight_lux > 0) {
        Json d = Json::object();
        d["E_h"] = daylight_lux;
        d["definition"] = "DF = 100 * 683 lm/W * Y / E_h [%], Y the luminance-weighted "
                          "irradiance [W m^-2], E_h the sky's unobstructed horizontal "
                          "illuminance [lux]; share_ge_k: fraction of a grid's points with "
                          "DF >= k %";
        j["daylight_factor"] = d;
    }
    if (grids.empty()) return j;
    Json a = Json::array();
    for (const GridResult& g : grids) a.push_back(grid_json(g, lux, daylight_lux));
    j["grids"] = a;
    j["grid_quantities"] =
        lux ? "grids: E_min/E_avg/E_max = luminance-weighted irradiance (0.2126 R + 0.7152 G + "
              "0.0722 B) [W per scene unit^2], U0 = E_min/E_avg, E_rgb per channel; lux = 683 "
              "lm/W times that luminance (scene in metres)"
            : "grids: E_min/E_avg/E_max = luminance-weighted irradiance (0.2126 R + 0.7152 G + "
              "0.0722 B) [W per scene unit^2], U0 = E_min/E_avg, E_rgb per channel";
    return j;
}

std::vector<Probe> read_probes(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw InputError(path, 0, "is a directory, not a probe file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, 0, "cannot open probe file");
    constexpr std::size_t kMaxLine = 64 * 1024; // a row is 6 numbers
    std::vector<Probe> probes;
    std::string line;
    int number = 0;
    bool too_long = false, has_nul = false;
    while (read_bounded_line(in, line, kMaxLine, too_long, has_nul)) {
        if (number == INT_MAX) throw InputError(path, number, "too many lines");
        ++number;
        if (too_long) throw InputError(path, number, "line longer than 64 KiB (not a probe CSV?)");
        if (has_nul)
            throw InputError(path, number,
                             "NUL byte in '" + quoted_excerpt(line) + "' (not a text file?)");
        if (!line.empty() && line.back() == '\r') line.pop_back();
        const auto first = line.find_first_not_of(" \t");
        if (first == std::string::npos || line[first] == '#') continue;
        double v[6];
        int count = 0;
        std::stringstream ss(line);
        std::string cell;
        bool numeric = true, text = false;
        std::string bad_cell;
        while (std::getline(ss, cell, ',')) {
            double x = 0;
            const char* last = cell.data() + cell.size();
            const NumberRead r = read_double(cell.data(), last, x);
            if (!r.found(cell.data())) text = true; // no number at all: a header's word
            const char* end = r.end;
            while (end != last && (*end == ' ' || *end == '\t')) ++end;
            if (!r.found(cell.data()) || end != last || !std::isfinite(x)) {
                numeric = false;
                bad_cell = cell;
                break;
            }
            if (count < 6) v[count] = x;
            ++count;
        }
        if (!numeric) {
            if (probes.empty() && number == 1 && text) continue; // header line
            throw InputError(path, number,
                             "'" + quoted_excerpt(bad_cell) +
                                 "' is not a finite number; expected 6 numbers "
                                 "x,y,z,nx,ny,nz: '" +
                                 quoted_excerpt(line) + "'");
        }
        if (count != 6)
            throw InputError(path, number,
                             "expected 6 numbers x,y,z,nx,ny,nz, got " + std::to_string(count) +
                                 ": '" + quoted_excerpt(line) + "'");
        Probe p{dvec3(v[0], v[1], v[2]), dvec3(v[3], v[4], v[5])};
        if (!(glm::length(p.normal) > 0) || !std::isfinite(glm::length(p.normal)))
            throw InputError(path, number,
                             "the normal (" + num(v[3]) + "," + num(v[4]) + "," + num(v[5]) +
                                 ") has no finite direction");
        probes.push_back(p);
    }
    if (in.bad()) throw InputError(path, 0, "cannot read probe file");
    if (probes.empty()) throw InputError(path, 0, "no probe points (rows x,y,z,nx,ny,nz)");
    return probes;
}

std::vector<ProbeValue> evaluate_probes(const std::vector<Probe>& probes, const Hierarchy& h,
                                        const FinalGather* gather) {
    const Scene& scene = h.scene();
    std::vector<std::optional<SurfacePoint>> surfaces;
    std::vector<GatherPoint> queries;
    for (const Probe& p : probes) {
        surfaces.push_back(find_surface(scene, p.position, p.normal));
        const std::optional<SurfacePoint>& sp = surfaces.back();
        queries.push_back({p.position, p.normal, sp ? sp->polygon : GatherPoint::kNoSurface});
    }
    std::vector<GatherValue> gathered;
    if (gather) gathered = gather->at(queries);
    std::vector<ProbeValue> values(probes.size());
    for (std::size_t k = 0; k < probes.size(); ++k) {
        const std::optional<SurfacePoint>& sp = surfaces[k];
        if (sp) values[k].polygon = sp->polygon;
        if (gather)
            values[k].E = gathered[k].E();
        else if (sp)
            values[k].E = irradiance_at(h, *sp);
    }
    return values;
}

std::string probes_csv(const std::vector<Probe>& probes, const Hierarchy& h,
                       const FinalGather* gather, double daylight_lux) {
    const bool df = daylight_lux > 0;
    const Scene& scene = h.scene();
    const std::vector<ProbeValue> values = evaluate_probes(probes, h, gather);
    std::ostringstream s;
    s.precision(9);
    s << "x,y,z,nx,ny,nz,E_r,E_g,E_b,polygon,group" << (df ? ",DF" : "") << "\n";
    for (std::size_t k = 0; k < probes.size(); ++k) {
        const Probe& p = probes[k];
        const ProbeValue& v = values[k];
        s << p.position.x << "," << p.position.y << "," << p.position.z << "," << p.normal.x << ","
          << p.normal.y << "," << p.normal.z << ",";
        if (!v.E) {
            s << ",,,,none" << (df ? "," : "") << "\n";
            continue;
        }
        s << v.E->x << "," << v.E->y << "," << v.E->z << ",";
        if (v.polygon)
            s << *v.polygon << "," << scene.groups[scene.polygons[*v.polygon].group];
        else
            s << ",none";
        if (df) s << "," << 100 * kLumensPerWatt * luminance(v.E->x, v.E->y, v.E->z) / daylight_lux;
        s << "\n";
    }
    return s.str();
}

void write_text_file(const std::string& path, const std::string& contents) {
    write_file_atomically(path, contents);
}

} // namespace hemirad
