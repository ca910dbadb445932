// The `hemirad` Python module: load a scene, solve it, read irradiance at points (numpy in and
// out), per-group statistics, the shot log and the JSON report.
//
//     import hemirad, numpy as np
//     s = hemirad.Solver(hemirad.load_scene("cornell"), tolerance=1e-3)   # any option by key
//     s.solve(progress=lambda shot: print(shot["shot"], shot["error_bound"]))
//     E = s.irradiance(points, normals)   # (N, 3) float64 array [W unit^-2], RGB
//
// Errors: hemirad's InputError becomes ValueError, RuntimeError stays RuntimeError, with the
// message the command line would print.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <variant>

#include "hemirad/hemirad.h"

namespace py = pybind11;
using namespace hemirad;

namespace {

py::tuple rgb(const dvec3& v) {
    return py::make_tuple(v.x, v.y, v.z);
}

/// One shot as a dict: the keys of a line of `hemirad solve --log`.
py::dict shot_dict(const ShotRecord& r) {
    py::dict d;
    d["shot"] = r.shot;
    if (r.luminaire >= 0) {
        d["luminaire"] = r.luminaire;
    } else {
        py::dict a;
        a["polygon"] = r.shooter.polygon;
        a["level"] = r.shooter.level;
        a["index"] = r.shooter.index;
        d["shooter"] = a;
    }
    d["shooter_power"] = r.shooter_power;
    d["links"] = r.links;
    if (r.refined) d["refined"] = r.refined;
    if (r.probes) d["probes"] = r.probes;
    if (r.discarded) d["discarded"] = r.discarded;
    if (r.parts) d["parts"] = r.parts;
    if (r.parallax >= 0) d["parallax"] = r.parallax;
    py::dict t;
    t["select"] = r.t_select;
    t["push_pull"] = r.t_push_pull;
    t["form_factors"] = r.t_form_factors;
    t["update"] = r.t_update;
    for (const auto& p : r.ff_phases) t[py::str(std::string("ff_") + p.phase)] = p.seconds;
    d["time"] = t;
    d["unshot"] = rgb(r.unshot);
    d["unshot_fraction"] = r.unshot_fraction;
    d["error_bound"] = r.error_bound;
    d["row_sum"] = r.row_sum;
    if (r.row_guarded) d["row_guarded"] = true;
    return d;
}

/// An (N, 3) float64 array (any array convertible to one) as points.
std::vector<dvec3> rows3(const py::handle& obj, const char* what) {
    auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(obj);
    if (!a || a.ndim() != 2 || a.shape(1) != 3)
        throw py::value_error(std::string(what) + " must be an (N, 3) array");
    std::vector<dvec3> out(std::size_t(a.shape(0)));
    auto r = a.unchecked<2>();
    for (py::ssize_t i = 0; i < a.shape(0); ++i) {
        out[std::size_t(i)] = dvec3(r(i, 0), r(i, 1), r(i, 2));
        if (!std::isfinite(out[std::size_t(i)].x) || !std::isfinite(out[std::size_t(i)].y) ||
            !std::isfinite(out[std::size_t(i)].z))
            throw py::value_error(std::string(what) + " row " + std::to_string(i) +
                                  " is not finite");
    }
    return out;
}

/// A colour given as one number (grey) or three (R, G, B).
dvec3 rgb_arg(const py::handle& obj, const char* what) {
    if (py::isinstance<py::float_>(obj) || py::isinstance<py::int_>(obj))
        return dvec3(obj.cast<double>());
    const std::vector<double> v = obj.cast<std::vector<double>>();
    if (v.size() != 3) throw py::value_error(std::string(what) + " must be a number or (r, g, b)");
    return dvec3(v[0], v[1], v[2]);
}

/// The Python value of an option of `o` (solver_options.h): str, float, int or bool.
py::object option_value(const SolverOption& option, const SolverOptions& o) {
    const SolverOption::Field f = option.field(const_cast<SolverOptions&>(o));
    if (auto p = std::get_if<std::string*>(&f)) return py::str(**p);
    if (auto p = std::get_if<double*>(&f)) return py::float_(**p);
    if (auto p = std::get_if<int*>(&f)) return py::int_(**p);
    if (auto p = std::get_if<long*>(&f)) return py::int_(**p);
    if (auto p = std::get_if<bool*>(&f)) return py::bool_(**p != option.inverted);
    return py::int_(*std::get<std::uint64_t*>(f));
}

/// Sets an option of `o` from a Python value; TypeError for a value of the wrong type.
void set_option(const SolverOption& option, SolverOptions& o, const py::handle& value) {
    const std::string key = option.key();
    const SolverOption::Field f = option.field(o);
    try {
        if (auto p = std::get_if<std::string*>(&f)) {
            **p = value.cast<std::string>();
        } else if (auto p = std::get_if<double*>(&f)) {
            **p = value.cast<double>();
        } else if (auto p = std::get_if<int*>(&f)) {
            **p = value.cast<int>();
        } else if (auto p = std::get_if<long*>(&f)) {
            **p = value.cast<long>();
        } else if (auto p = std::get_if<bool*>(&f)) {
            if (!py::isinstance<py::bool_>(value)) throw py::cast_error();
            **p = value.cast<bool>() != option.inverted;
        } else {
            std::uint64_t* out = std::get<std::uint64_t*>(f);
            if (option.size && py::isinstance<py::str>(value))
                *out = parse_memory_size(value.cast<std::string>(), key); // "4G"
            else
                *out = value.cast<std::uint64_t>();
        }
    } catch (const py::cast_error&) {
        throw py::type_error(
            "option " + key + "=" + py::repr(value).cast<std::string>() + ": expected " +
            option_value(option, SolverOptions{}).get_type().attr("__name__").cast<std::string>() +
            (option.size ? " or str (a size such as '4G')" : ""));
    }
}

/// SolverOptions from keyword arguments named as the options table's keys; TypeError for a
/// keyword that is no option.
SolverOptions options_from(const py::kwargs& kwargs) {
    SolverOptions o;
    for (const auto& [k, v] : kwargs) {
        const std::string key = k.cast<std::string>();
        const SolverOption* option = find_solver_option(key);
        if (!option || option->key() != key)
            throw py::type_error("Solver() got an unexpected keyword argument '" + key +
                                 "' (the options are hemirad.solver_option_table()'s keys)");
        set_option(*option, o, v);
    }
    return o;
}

/// Every option of `o` as a dict, by key.
py::dict options_dict(const SolverOptions& o) {
    py::dict d;
    for (const SolverOption& option : solver_option_table())
        d[py::str(option.key())] = option_value(option, o);
    return d;
}

/// The keyword options with their defaults and help, for Solver's docstring.
std::string options_doc() {
    std::string doc = "Progressive radiosity. Solver(scene, **options): keyword options are those "
                      "of `hemirad solve` with '_' for '-', with the same defaults:\n";
    const SolverOptions defaults;
    for (const SolverOption& option : solver_option_table()) {
        doc += "\n  " + option.key() + "=" +
               py::repr(option_value(option, defaults)).cast<std::string>();
        doc += std::string("  ") + option.help;
        if (*option.unit) doc += std::string(" [") + option.unit + "]";
    }
    return doc;
}

/// A Solver that also keeps its shot log, and the scene it solves (a copy: the Python
/// object may go away).
class PySolver {
  public:
    PySolver(const Scene& scene, const SolverOptions& options)
        : scene_(std::make_unique<Scene>(scene)), solver_(*scene_, options) {}

    bool step() {
        bool more;
        {
            py::gil_scoped_release release;
            more = solver_.step();
        }
        if (more) log_.push_back(solver_.last_shot());
        return more;
    }

    /// Steps until a stop criterion holds; progress(shot_dict) after every shot may return
    /// False to stop early. Returns the stop reason.
    std::string solve(const std::optional<std::function<py::object(py::dict)>>& progress) {
        while (step()) {
            if (PyErr_CheckSignals() != 0) throw py::error_already_set();
            if (progress) {
                py::object r = (*progress)(shot_dict(solver_.last_shot()));
                if (!r.is_none() && !r.cast<bool>()) return "stopped";
            }
        }
        return to_string(solver_.stop_reason());
    }

    py::array_t<double> irradiance(const py::handle& points, const py::handle& normals, bool gather,
                                   int gather_rays, double gather_angle, double gather_error,
                                   double gather_bright, std::uint64_t seed) {
        const std::vector<dvec3> p = rows3(points, "points");
        const std::vector<dvec3> n = rows3(normals, "normals");
        if (p.size() != n.size())
            throw py::value_error("points and normals differ in length (" +
                                  std::to_string(p.size()) + " and " + std::to_string(n.size()) +
                                  ")");
        std::vector<Probe> probes(p.size());
        for (std::size_t i = 0; i < p.size(); ++i) probes[i] = {p[i], n[i]};
        GatherOptions go;
        go.rays = gather_rays;
        go.emitter_angle = gather_angle;
        go.indirect_error = gather_error;
        go.bright_factor = gather_bright;
        go.seed = seed;
        validate_gather_options(go);
        std::vector<ProbeValue> values;
        {
            py::gil_scoped_release release;
            const Hierarchy& h = solver_.solution();
            std::unique_ptr<FinalGather> fg;
            if (gather) fg = std::make_unique<FinalGather>(h, go);
            values = evaluate_probes(probes, h, fg.get());
        }
        py::array_t<double> out({py::ssize_t(values.size()), py::ssize_t(3)});
        auto w = out.mutable_unchecked<2>();
        const double nan = std::numeric_limits<double>::quiet_NaN();
        for (std::size_t i = 0; i < values.size(); ++i) {
            const dvec3 E = values[i].E ? *values[i].E : dvec3(nan);
            for (int c = 0; c < 3; ++c) w(py::ssize_t(i), c) = E[c];
        }
        return out;
    }

    py::dict group_statistics() {
        const Hierarchy& h = solver_.solution();
        py::dict groups;
        for (std::uint32_t g = 0; g < scene_->groups.size(); ++g) {
            const GroupIrradiance s = group_irradiance(h, g);
            py::dict d;
            d["area"] = s.area;
            d["E_avg"] = rgb(s.E_avg);
            d["E_min"] = rgb(s.E_min);
            d["E_max"] = rgb(s.E_max);
            d["flux"] = rgb(s.E_avg * s.area);
            groups[py::str(scene_->groups[g])] = d;
        }
        return groups;
    }

    py::list shot_log() const {
        py::list l;
        for (const ShotRecord& r : log_) l.append(shot_dict(r));
        return l;
    }

    py::object report() {
        return py::module_::import("json").attr("loads")(solve_report(solver_).dump(0));
    }

    Solver& solver() { return solver_; }
    const Scene& scene() const { return *scene_; }

  private:
    std::unique_ptr<Scene> scene_;
    Solver solver_;
    std::vector<ShotRecord> log_;
};

} // namespace

PYBIND11_MODULE(hemirad, m) {
    m.doc() = "hemirad: radiosity by progressive shooting with GPU hemicube form factors";
    m.attr("__version__") = HEMIRAD_VERSION;
    static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const InputError& e) {
            PyErr_SetString(input_error.ptr(), e.what());
        }
    });

    py::class_<Scene>(m, "Scene", "A scene: polygons, materials, surface groups, luminaires.")
        .def_readonly("source", &Scene::source)
        .def_readonly("groups", &Scene::groups)
        .def_readonly("warnings", &Scene::warnings)
        .def_property_readonly("polygon_count", [](const Scene& s) { return s.polygons.size(); })
        .def_property_readonly("emitted_power",
                               [](const Scene& s) { return rgb(s.emitted_power()); })
        .def_property_readonly("total_area", &Scene::total_area)
        .def("__repr__", [](const Scene& s) {
            return "<hemirad.Scene " + s.source + ": " + std::to_string(s.polygons.size()) +
                   " polygons>";
        });

    m.def(
        "load_scene",
        [](const std::string& name, int subdiv, double rho, int sphere_rings,
           double max_reflectance) {
            BuiltinOptions b;
            b.subdiv = subdiv;
            b.rho = rho;
            b.sphere_rings = sphere_rings;
            ObjOptions o;
            o.max_reflectance = max_reflectance;
            return load_scene(name, b, o);
        },
        py::arg("name"), py::arg("subdiv") = 1, py::arg("rho") = -1.0, py::arg("sphere_rings") = 16,
        py::arg("max_reflectance") = 0.98,
        "A built-in scene (cornell, cube, ...), an OBJ file or a SCENE.json file, with the "
        "options of `hemirad solve` (--subdiv, --rho, --rings, --max-reflectance).");
    m.def("builtin_names", []() { return std::string(builtin_names()); });

    m.def(
        "solver_option_table",
        []() {
            py::list l;
            const SolverOptions defaults;
            for (const SolverOption& option : solver_option_table()) {
                py::dict d;
                d["key"] = option.key();
                d["flag"] = option.flag;
                d["default"] = option_value(option, defaults);
                d["unit"] = option.unit;
                d["help"] = option.help;
                d["saved"] = option.saved;
                l.append(d);
            }
            return l;
        },
        "Every solver option (the options table, hemirad/solver_options.h): key, flag, default, "
        "unit, help, saved (kept in solution files).");
    m.def(
        "solver_options",
        [](const py::kwargs& kwargs) { return options_dict(options_from(kwargs)); },
        "The solver options that Solver(scene, **kwargs) would use, as a dict by key (nothing is "
        "checked but the names and types).");

    py::class_<PySolver>(m, "Solver", options_doc().c_str())
        .def(py::init([](const Scene& scene, const py::kwargs& kwargs) {
                 return std::make_unique<PySolver>(scene, options_from(kwargs));
             }),
             py::arg("scene"))
        .def("step", &PySolver::step, "Shoots once; False once a stop criterion holds.")
        .def("solve", &PySolver::solve, py::arg("progress") = py::none(),
             "Shoots until converged (or max_shots, time_limit); progress(shot) is called "
             "after every shot with the shot's dict and may return False to stop. Returns "
             "the stop reason.")
        .def("irradiance", &PySolver::irradiance, py::arg("points"), py::arg("normals"),
             py::kw_only(), py::arg("gather") = true, py::arg("gather_rays") = GatherOptions{}.rays,
             py::arg("gather_angle") = GatherOptions{}.emitter_angle,
             py::arg("gather_error") = GatherOptions{}.indirect_error,
             py::arg("gather_bright") = GatherOptions{}.bright_factor,
             py::arg("seed") = GatherOptions{}.seed,
             "Irradiance [W unit^-2] at points on surfaces facing `normals`, an (N, 3) array, "
             "as `hemirad solve --probes` computes it (final gather unless gather=False; "
             "without the gather a point on no surface gets NaN).")
        .def("group_statistics", &PySolver::group_statistics,
             "Per surface group: area, E_avg, E_min, E_max (RGB irradiance), flux (RGB, W).")
        .def(
            "set_luminaire_multiplier",
            [](PySolver& s, const std::string& name, double f) {
                s.solver().set_luminaire_multiplier(name, f);
            },
            py::arg("name"), py::arg("multiplier"),
            "Sets a luminaire's multiplier (0 = off); solve() then re-converges incrementally "
            "from the current solution (with light layers, the default for up to 16 "
            "luminaires, its share is rescaled at once; else the difference of its power is "
            "shot).")
        .def(
            "place_luminaire",
            [](PySolver& s, const std::string& name, const py::handle& position,
               const py::handle& aim) {
                const auto xyz = [](const py::handle& obj, const char* what) {
                    const std::vector<double> v = obj.cast<std::vector<double>>();
                    if (v.size() != 3)
                        throw py::value_error(std::string(what) + " must be (x, y, z)");
                    return dvec3(v[0], v[1], v[2]);
                };
                s.solver().place_luminaire(name, xyz(position, "position"), xyz(aim, "aim"));
            },
            py::arg("name"), py::arg("position"), py::arg("aim"),
            "Moves and aims a luminaire; its light leaves its old place at once and solve() "
            "shoots it from the new one (needs light layers: options light_layers).")
        .def(
            "set_reflectance",
            [](PySolver& s, const std::string& group, const py::handle& rho) {
                s.solver().set_reflectance(group, rgb_arg(rho, "rho"));
            },
            py::arg("group"), py::arg("rho"),
            "Sets a surface group's reflectance (a number or (r, g, b), each in [0, 1)); "
            "solve() then re-converges incrementally.")
        .def(
            "set_emission",
            [](PySolver& s, const std::string& group, const py::handle& Ke) {
                s.solver().set_emission(group, rgb_arg(Ke, "Ke"));
            },
            py::arg("group"), py::arg("Ke"),
            "Sets a surface group's emitted radiance Ke [W sr^-1 unit^-2] (a number or (r, g, "
            "b), >= 0); solve() then re-converges incrementally.")
        .def_property_readonly("shot_log", &PySolver::shot_log,
                               "Every shot so far, as dicts (the keys of `--log`).")
        .def("report", &PySolver::report, "The JSON report of `hemirad solve --report`, as a dict.")
        .def(
            "export_lightmaps",
            [](PySolver& s, const std::string& dir) {
                return export_lightmaps(dir, s.solver().solution());
            },
            py::arg("dir"), "Writes lightmaps (EXR + OBJ per group) into dir; returns the files.")
        .def(
            "export_ply",
            [](PySolver& s, const std::string& path) { export_ply(path, s.solver().solution()); },
            py::arg("path"))
        .def_property_readonly("shots", [](PySolver& s) { return s.solver().shots(); })
        .def_property_readonly("error_bound", [](PySolver& s) { return s.solver().error_bound(); })
        .def_property_readonly("converged", [](PySolver& s) { return s.solver().converged(); })
        .def_property_readonly(
            "stop_reason",
            [](PySolver& s) { return std::string(to_string(s.solver().stop_reason())); })
        .def_property_readonly("seconds", [](PySolver& s) { return s.solver().seconds(); })
        .def_property_readonly(
            "options", [](PySolver& s) { return options_dict(s.solver().options()); },
            "The solver's options, as a dict by key (solver_option_table()).")
        .def_property_readonly("form_factors",
                               [](PySolver& s) { return s.solver().provider().name(); })
        .def_property_readonly("scene", &PySolver::scene, py::return_value_policy::copy);
}
