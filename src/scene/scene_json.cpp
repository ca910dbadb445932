// SCENE.json: a project file that assembles a scene from geometry files, luminaires and
// cameras (scene_io.h, load_scene_json). Parsed with nlohmann::json; a second, SAX pass over
// the text finds the line of every key, so that each message names file:line and the key.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <system_error>

#include <nlohmann/json.hpp>

#include "hemirad/error.h"
#include "hemirad/scene_io.h"

namespace hemirad {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// Lines of the keys of a JSON text, by JSON pointer ("/luminaires/0/position"); an array
// element or object is located by its first key. Keys are found in the text in document order
// (a key is a string followed by ':', which a string value never is).
class KeyLines final : public nlohmann::json_sax<json> {
  public:
    explicit KeyLines(const std::string& text) : text_(text) {}
    std::map<std::string, int> lines;

    bool null() override { return value(); }
    bool boolean(bool) override { return value(); }
    bool number_integer(number_integer_t) override { return value(); }
    bool number_unsigned(number_unsigned_t) override { return value(); }
    bool number_float(number_float_t, const string_t&) override { return value(); }
    bool string(string_t&) override { return value(); }
    bool binary(binary_t&) override { return value(); }
    bool start_object(std::size_t) override { return open(false); }
    bool start_array(std::size_t) override { return open(true); }
    bool end_object() override { return close(); }
    bool end_array() override { return close(); }
    bool key(string_t& k) override {
        frames_.back().key = k;
        const int line = find_key(k);
        std::string container = pointer();
        if (!lines.count(container)) lines[container] = line;
        lines[container + "/" + escape(k)] = line;
        return true;
    }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
        return false;
    }

  private:
    struct Frame {
        bool array = false;
        long next = 0;    // arrays: index of the next element
        std::string key;  // objects: the last key
        std::string name; // this container's pointer component
    };

    static std::string escape(const std::string& k) {
        std::string out;
        for (char c : k) out += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
        return out;
    }
    std::string pointer() const {
        std::string p;
        for (std::size_t i = 1; i < frames_.size(); ++i) p += "/" + frames_[i].name;
        return p;
    }
    std::string component() {
        if (frames_.empty()) return "";
        Frame& f = frames_.back();
        return f.array ? std::to_string(f.next++) : escape(f.key);
    }
    bool value() {
        component();
        return true;
    }
    bool open(bool array) {
        Frame f;
        f.array = array;
        f.name = component();
        frames_.push_back(f);
        return true;
    }
    bool close() {
        frames_.pop_back();
        return true;
    }
    int find_key(const std::string& k) {
        const std::string quoted = "\"" + k + "\"";
        for (std::size_t pos = cursor_; (pos = text_.find(quoted, pos)) != std::string::npos;
             ++pos) {
            std::size_t after = pos + quoted.size();
            while (after < text_.size() && std::isspace(static_cast<unsigned char>(text_[after])))
                ++after;
            if (after < text_.size() && text_[after] == ':') {
                line_ +=
                    int(std::count(text_.begin() + long(cursor_), text_.begin() + long(pos), '\n'));
                cursor_ = pos;
                return line_;
            }
        }
        return 0; // not found as written (escapes): no line
    }

    const std::string& text_;
    std::size_t cursor_ = 0;
    int line_ = 1;
    std::vector<Frame> frames_;
};

// Reads one SCENE.json: the document, the lines of its keys, and where relative paths start.
class Reader {
  public:
    Reader(const std::string& path, const std::map<std::string, int>& lines)
        : path_(path), lines_(lines), dir_(fs::path(path).parent_path()) {}

    [[noreturn]] void fail(const std::string& pointer, const std::string& what) const {
        throw InputError(path_, line(pointer), readable(pointer) + ": " + what);
    }
    int line(const std::string& pointer) const {
        // The key itself, else the nearest enclosing key that has a line.
        for (std::string p = pointer;; p = p.substr(0, p.rfind('/'))) {
            const auto it = lines_.find(p);
            if (it != lines_.end() && it->second > 0) return it->second;
            if (p.empty()) return 0;
        }
    }
    // "/luminaires/0/position" -> "luminaires[0].position" (for messages).
    static std::string readable(const std::string& pointer) {
        std::string out;
        std::istringstream in(pointer);
        std::string part;
        std::getline(in, part, '/'); // leading empty
        while (std::getline(in, part, '/')) {
            const bool index = !part.empty() && std::all_of(part.begin(), part.end(), ::isdigit);
            if (index)
                out += "[" + part + "]";
            else
                out += (out.empty() ? "" : ".") + part;
        }
        return out.empty() ? "(top level)" : out;
    }

    void only_keys(const json& o, const std::string& at,
                   std::initializer_list<const char*> allowed) const {
        if (!o.is_object()) fail(at, "expected an object {...}, got " + dump(o));
        for (const auto& item : o.items()) {
            const std::string& k = item.key(); // a plain name: clang 14 cannot capture bindings
            if (std::none_of(allowed.begin(), allowed.end(),
                             [&](const char* a) { return k == a; })) {
                std::string list;
                for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
                fail(at + "/" + k, "unknown key '" + k + "' (expected: " + list + ")");
            }
        }
    }
    double number(const json& v, const std::string& at) const {
        if (!v.is_number()) fail(at, "expected a number, got " + dump(v));
        const double x = v.get<double>();
        if (!std::isfinite(x)) fail(at, "expected a finite number, got " + dump(v));
        return x;
    }
    dvec3 vec3(const json& v, const std::string& at) const {
        if (!v.is_array() || v.size() != 3)
            fail(at, "expected 3 numbers [x, y, z], got " + dump(v));
        return {number(v[0], at), number(v[1], at), number(v[2], at)};
    }
    std::string string(const json& v, const std::string& at) const {
        if (!v.is_string()) fail(at, "expected a string, got " + dump(v));
        return v.get<std::string>();
    }
    /// A path relative to the JSON file's folder (absolute paths as they are).
    std::string resolve(const std::string& p) const {
        const fs::path q(p);
        return (q.is_absolute() || dir_.empty() ? q : dir_ / q).lexically_normal().string();
    }
    static std::string dump(const json& v) {
        std::string s = v.dump();
        return s.size() > 60 ? s.substr(0, 57) + "..." : s;
    }

  private:
    std::string path_;
    const std::map<std::string, int>& lines_;
    fs::path dir_;
};

std::string lower_extension(const std::string& path) {
    std::string e = fs::path(path).extension().string();
    for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

// Appends `part` to `out`: materials after out's, groups merged by name.
void merge(Scene& out, const Scene& part) {
    const auto offset = std::uint32_t(out.materials.size());
    const int texture_offset = int(out.textures.size());
    out.materials.insert(out.materials.end(), part.materials.begin(), part.materials.end());
    for (std::size_t m = offset; m < out.materials.size(); ++m)
        if (out.materials[m].texture >= 0) out.materials[m].texture += texture_offset;
    out.textures.insert(out.textures.end(), part.textures.begin(), part.textures.end());
    // Texture coordinates stay parallel to the polygons once either side has them.
    if (!part.texcoords.empty() || !out.texcoords.empty()) {
        out.texcoords.resize(out.polygons.size(), TexCoords{});
        if (part.texcoords.empty())
            out.texcoords.resize(out.polygons.size() + part.polygons.size(), TexCoords{});
        else
            out.texcoords.insert(out.texcoords.end(), part.texcoords.begin(), part.texcoords.end());
    }
    std::vector<std::uint32_t> group(part.groups.size());
    for (std::size_t g = 0; g < part.groups.size(); ++g) {
        const int found = out.find_group(part.groups[g]);
        if (found >= 0) {
            group[g] = std::uint32_t(found);
        } else {
            out.groups.push_back(part.groups[g]);
            group[g] = std::uint32_t(out.groups.size() - 1);
        }
    }
    const auto first = std::uint32_t(out.polygons.size());
    for (Polygon p : part.polygons) {
        p.material += offset;
        p.group = group[p.group];
        if (p.twin != kNoTwin) p.twin += first;
        out.polygons.push_back(p);
    }
    out.cameras.insert(out.cameras.end(), part.cameras.begin(), part.cameras.end());
    out.luminaires.insert(out.luminaires.end(), part.luminaires.begin(), part.luminaires.end());
    if (part.sun && !out.sun) out.sun = part.sun; // a glTF directional light (the first)
    for (const std::string& w : part.warnings)
        if (w.rfind(kNoEmitterWarning, 0) != 0) out.warnings.push_back(w);
}

Luminaire read_luminaire(const Reader& r, const json& j, const std::string& at, std::size_t k,
                         std::vector<std::string>& warnings) {
    r.only_keys(
        j, at,
        {"name", "ies", "ldt", "candela", "spot", "position", "aim", "rotation", "multiplier"});
    Luminaire l;
    l.name = j.contains("name") ? r.string(j["name"], at + "/name") : "L" + std::to_string(k + 1);
    const int kinds = int(j.contains("ies")) + int(j.contains("ldt")) + int(j.contains("candela")) +
                      int(j.contains("spot"));
    if (kinds != 1)
        r.fail(at, kinds == 0 ? "a luminaire needs one of 'ies' or 'ldt' (a photometric file), "
                                "'candela' (an isotropic point source) or 'spot'"
                              : "a luminaire has one of 'ies', 'ldt', 'candela' and 'spot', not "
                                "several");
    if (!j.contains("position")) r.fail(at, "a luminaire needs a 'position' [x, y, z]");
    l.position = r.vec3(j["position"], at + "/position");
    if (j.contains("aim")) l.aim = r.vec3(j["aim"], at + "/aim");
    if (j.contains("rotation")) l.rotation = r.number(j["rotation"], at + "/rotation");
    if (j.contains("multiplier")) {
        l.multiplier = r.number(j["multiplier"], at + "/multiplier");
        if (!(l.multiplier >= 0) || !std::isfinite(l.multiplier))
            r.fail(at + "/multiplier",
                   "must be >= 0 (0 = off), got " + Reader::dump(j["multiplier"]));
    }
    if (j.contains("ies") || j.contains("ldt")) {
        // Either key takes either format: the file's content tells them apart.
        const std::string key = j.contains("ies") ? "ies" : "ldt";
        l.file = r.string(j[key], at + "/" + key);
        PhotometricFile f;
        try {
            f = read_photometric_file(r.resolve(l.file));
        } catch (const InputError& e) {
            r.fail(at + "/" + key, e.what());
        }
        l.kind = f.format;
        l.distribution = std::move(f.distribution);
        l.rated_lumens = f.rated_lumens * l.multiplier;
        l.opening = f.opening;
        for (std::string& w : f.warnings) warnings.push_back(std::move(w));
    } else if (j.contains("candela")) {
        l.kind = "candela";
        const double I = r.number(j["candela"], at + "/candela");
        if (!(I >= 0)) r.fail(at + "/candela", "must be >= 0, got " + Reader::dump(j["candela"]));
        l.distribution = isotropic_distribution(I);
    } else {
        l.kind = "spot";
        const std::string sp = at + "/spot";
        const json& s = j["spot"];
        r.only_keys(s, sp, {"candela", "cone", "falloff"});
        if (!s.contains("candela") || !s.contains("cone"))
            r.fail(sp, "a spot needs 'candela' and 'cone' (and optionally 'falloff'), degrees");
        const double I = r.number(s["candela"], sp + "/candela");
        if (!(I >= 0)) r.fail(sp + "/candela", "must be >= 0, got " + Reader::dump(s["candela"]));
        const double cone = r.number(s["cone"], sp + "/cone");
        const double falloff = s.contains("falloff") ? r.number(s["falloff"], sp + "/falloff") : 0;
        try {
            l.distribution = spot_distribution(I, cone, falloff);
        } catch (const InputError& e) {
            r.fail(sp, e.what());
        }
    }
    try {
        l.orient();
    } catch (const InputError&) {
        r.fail(at + "/aim", "must be a non-zero direction, got " + Reader::dump(j["aim"]));
    }
    return l;
}

Camera read_camera(const Reader& r, const json& j, const std::string& at, std::size_t k) {
    r.only_keys(j, at, {"name", "eye", "target", "up", "fov"});
    Camera c;
    c.name =
        j.contains("name") ? r.string(j["name"], at + "/name") : "camera" + std::to_string(k + 1);
    if (!j.contains("eye") || !j.contains("target"))
        r.fail(at, "a camera needs 'eye' and 'target' [x, y, z] (and optionally 'up', 'fov')");
    c.eye = r.vec3(j["eye"], at + "/eye");
    c.target = r.vec3(j["target"], at + "/target");
    if (j.contains("up")) c.up = r.vec3(j["up"], at + "/up");
    if (j.contains("fov")) {
        c.fov_y_deg = r.number(j["fov"], at + "/fov");
        if (!(c.fov_y_deg > 0 && c.fov_y_deg < 180))
            r.fail(at + "/fov", "must be in (0, 180) degrees, got " + Reader::dump(j["fov"]));
    }
    if (glm::length(c.target - c.eye) == 0) r.fail(at + "/target", "must differ from 'eye'");
    if (glm::length(glm::cross(c.target - c.eye, c.up)) == 0)
        r.fail(at + "/up", "must not be parallel to the view direction");
    return c;
}

// "up" and "north" (top level): unit, north made perpendicular to up.
SkyFrame read_sky_frame(const Reader& r, const json& doc) {
    SkyFrame f;
    if (doc.contains("up")) f.up = r.vec3(doc["up"], "/up");
    if (doc.contains("north")) f.north = r.vec3(doc["north"], "/north");
    if (!(glm::length(f.up) > 0)) r.fail("/up", "must be a non-zero direction");
    f.up = glm::normalize(f.up);
    const dvec3 level = f.north - glm::dot(f.north, f.up) * f.up;
    if (!(glm::length(level) > 1e-6 * glm::length(f.north)))
        r.fail("/north", "must be a non-zero direction not parallel to 'up'");
    f.north = glm::normalize(level);
    return f;
}

// "HH:MM" or "HH:MM:SS" -> hours; "YYYY-MM-DD" -> year, month, day.
bool parse_time(const std::string& s, double& hours) {
    int h = 0, m = 0, n = 0;
    double sec = 0;
    if (std::sscanf(s.c_str(), "%d:%d%n", &h, &m, &n) != 2) return false;
    if (s[std::size_t(n)] == ':') {
        int n2 = 0;
        if (std::sscanf(s.c_str() + n, ":%lf%n", &sec, &n2) != 1) return false;
        n += n2;
    }
    if (std::size_t(n) != s.size() || m < 0 || m > 59 || !(sec >= 0 && sec < 60)) return false;
    hours = h + m / 60.0 + sec / 3600.0;
    return h >= 0 && hours <= 24;
}
bool parse_date(const std::string& s, int& year, int& month, int& day) {
    int n = 0;
    return std::sscanf(s.c_str(), "%d-%d-%d%n", &year, &month, &day, &n) == 3 &&
           std::size_t(n) == s.size();
}

// "sun": one of "direction", "altitude" + "azimuth", or "latitude" + "longitude" + "date" +
// "time" (+ "utc_offset"), and "illuminance" (sun.h).
Sun read_sun(const Reader& r, const json& j, const SkyFrame& frame,
             std::vector<std::string>& warnings) {
    const std::string at = "/sun";
    r.only_keys(j, at,
                {"direction", "altitude", "azimuth", "latitude", "longitude", "date", "time",
                 "utc_offset", "illuminance"});
    const bool by_direction = j.contains("direction");
    const bool by_angles = j.contains("altitude") || j.contains("azimuth");
    const bool by_place = j.contains("latitude") || j.contains("longitude") || j.contains("date") ||
                          j.contains("time") || j.contains("utc_offset");
    if (int(by_direction) + int(by_angles) + int(by_place) != 1)
        r.fail(at, "the sun is given by one of 'direction'; 'altitude' and 'azimuth'; or "
                   "'latitude', 'longitude', 'date', 'time' (and 'utc_offset'), not " +
                       std::string(by_direction || by_angles || by_place ? "several" : "none"));
    if (!j.contains("illuminance"))
        r.fail(at, "the sun needs 'illuminance': its normal illuminance E_n [lux], e.g. 80000");
    Sun sun;
    sun.illuminance = r.number(j["illuminance"], at + "/illuminance");
    if (!(sun.illuminance >= 0))
        r.fail(at + "/illuminance", "must be >= 0 lux, got " + Reader::dump(j["illuminance"]));
    if (by_direction) {
        const dvec3 d = r.vec3(j["direction"], at + "/direction");
        if (!(glm::length(d) > 0)) r.fail(at + "/direction", "must be a non-zero direction");
        sun.direction = glm::normalize(d);
        frame.angles(sun.direction, sun.altitude_deg, sun.azimuth_deg);
    } else {
        if (by_angles) {
            if (!j.contains("altitude") || !j.contains("azimuth"))
                r.fail(at, "the sun needs both 'altitude' and 'azimuth' [degrees]");
            sun.altitude_deg = r.number(j["altitude"], at + "/altitude");
            sun.azimuth_deg = r.number(j["azimuth"], at + "/azimuth");
            if (!(sun.altitude_deg >= -90 && sun.altitude_deg <= 90))
                r.fail(at + "/altitude",
                       "must be in [-90, 90] degrees, got " + Reader::dump(j["altitude"]));
        } else {
            for (const char* k : {"latitude", "longitude", "date", "time"})
                if (!j.contains(k))
                    r.fail(at, std::string("the sun by place and time needs '") + k +
                                   "' (latitude, longitude [degrees, north and east positive], "
                                   "date \"YYYY-MM-DD\", time \"HH:MM\", utc_offset [h])");
            const double lat = r.number(j["latitude"], at + "/latitude");
            const double lon = r.number(j["longitude"], at + "/longitude");
            if (!(lat >= -90 && lat <= 90))
                r.fail(at + "/latitude",
                       "must be in [-90, 90], got " + Reader::dump(j["latitude"]));
            if (!(lon >= -180 && lon <= 360))
                r.fail(at + "/longitude",
                       "must be in [-180, 360], got " + Reader::dump(j["longitude"]));
            const double offset =
                j.contains("utc_offset") ? r.number(j["utc_offset"], at + "/utc_offset") : 0;
            if (!(offset >= -14 && offset <= 14))
                r.fail(at + "/utc_offset",
                       "must be in [-14, 14] hours, got " + Reader::dump(j["utc_offset"]));
            int year = 0, month = 0, day = 0;
            double hours = 0;
            if (!parse_date(r.string(j["date"], at + "/date"), year, month, day))
                r.fail(at + "/date", "expected \"YYYY-MM-DD\", got " + Reader::dump(j["date"]));
            if (!parse_time(r.string(j["time"], at + "/time"), hours))
                r.fail(at + "/time", "expected \"HH:MM\" or \"HH:MM:SS\" (local clock time), got " +
                                         Reader::dump(j["time"]));
            try {
                const SolarPosition p = solar_position(lat, lon, year, month, day, hours, offset);
                sun.altitude_deg = p.altitude_deg;
                sun.azimuth_deg = p.azimuth_deg;
            } catch (const InputError& e) {
                r.fail(at + "/date", e.what());
            }
        }
        sun.direction = frame.direction(sun.altitude_deg, sun.azimuth_deg);
    }
    if (!(sun.altitude_deg > 0)) {
        char altitude[32];
        std::snprintf(altitude, sizeof altitude, "%.2f", sun.altitude_deg);
        warnings.push_back(std::string("the sun is at or below the horizon (altitude ") + altitude +
                           " degrees): it lights nothing");
    }
    return sun;
}

// "sky": "model", "illuminance" (E_h [lux]), "ground_reflectance", "horizon_blend" (sky.h); the
// sun's position from the scene's "sun" for the models that need it.
Sky read_sky(const Reader& r, const json& j, const SkyFrame& frame, const std::optional<Sun>& sun) {
    const std::string at = "/sky";
    r.only_keys(j, at, {"model", "illuminance", "ground_reflectance", "horizon_blend"});
    const std::string models = "cie-overcast, cie-clear, cie-intermediate or uniform";
    if (!j.contains("model")) r.fail(at, "the sky needs 'model': " + models);
    SkyModel model{};
    const std::string name = r.string(j["model"], at + "/model");
    if (!parse_sky_model(name, model))
        r.fail(at + "/model", "unknown sky model '" + name + "' (expected " + models + ")");
    if (!j.contains("illuminance"))
        r.fail(at, "the sky needs 'illuminance': its unobstructed horizontal illuminance E_h "
                   "[lux], e.g. 10000");
    const double e_h = r.number(j["illuminance"], at + "/illuminance");
    if (!(e_h >= 0))
        r.fail(at + "/illuminance", "must be >= 0 lux, got " + Reader::dump(j["illuminance"]));
    double rho_g = 0;
    if (j.contains("ground_reflectance")) {
        rho_g = r.number(j["ground_reflectance"], at + "/ground_reflectance");
        if (!(rho_g >= 0 && rho_g <= 1))
            r.fail(at + "/ground_reflectance",
                   "must be in [0, 1], got " + Reader::dump(j["ground_reflectance"]));
    }
    bool blend = true;
    if (j.contains("horizon_blend")) {
        if (!j["horizon_blend"].is_boolean())
            r.fail(at + "/horizon_blend",
                   "expected true or false, got " + Reader::dump(j["horizon_blend"]));
        blend = j["horizon_blend"].get<bool>();
    }
    if (sky_needs_sun(model) && !sun)
        r.fail(at + "/model", "the " + name +
                                  " sky needs the sun's position: add \"sun\" (its "
                                  "\"illuminance\" may be 0 for the sky alone)");
    return make_sky(model, e_h, rho_g, frame.up, sun, blend);
}

/// The group names of a scene, for messages.
std::string group_list(const Scene& scene) {
    std::string names;
    for (const std::string& n : scene.groups) names += (names.empty() ? "" : ", ") + n;
    return names;
}

// "glazing": {"GROUP": tau} or {"GROUP": {"transmittance": tau, "angular": false}} (glazing.h):
// the groups' polygons leave the surfaces and become panes. Before the surfaces are finished,
// so that no pane cuts a wall (split_intersections) or gets a twin.
void read_glazing(const Reader& r, const json& j, Scene& scene) {
    const std::string at = "/glazing";
    if (!j.is_object())
        r.fail(at, "expected an object of surface groups and transmittances, e.g. \"glazing\": "
                   "{\"Glass\": 0.7}");
    std::vector<int> pane_of_group(scene.groups.size(), -1);
    std::vector<PaneTransmittance> panes;
    for (const auto& [name, value] : j.items()) {
        const std::string key = at + "/" + name;
        const int g = scene.find_group(name);
        if (g < 0)
            r.fail(key, "no surface group '" + name +
                            "' in the included files (groups: " + group_list(scene) + ")");
        const json* tau_value = &value;
        bool angular = true;
        if (value.is_object()) {
            r.only_keys(value, key, {"transmittance", "angular"});
            if (!value.contains("transmittance"))
                r.fail(key, "needs 'transmittance': the pane's at normal incidence, in [0, 1]");
            tau_value = &value["transmittance"];
            if (value.contains("angular")) {
                if (!value["angular"].is_boolean())
                    r.fail(key + "/angular",
                           "expected true or false, got " + Reader::dump(value["angular"]));
                angular = value["angular"].get<bool>();
            }
        }
        const double tau = r.number(*tau_value, key);
        if (!(tau >= 0 && tau <= 1))
            r.fail(key, "the transmittance must be in [0, 1], got " + Reader::dump(*tau_value));
        const PaneTransmittance t = make_pane_transmittance(tau, angular);
        if (angular && !t.angular && tau > 0)
            scene.warnings.push_back(
                "glazing '" + name + "': a transmittance of " + num(tau) +
                " is above what clear glass transmits at normal incidence (" +
                num(clear_glass_transmittance()) +
                "): it applies at every angle (no Fresnel fall-off towards grazing)");
        pane_of_group[std::size_t(g)] = int(panes.size());
        panes.push_back(t);
    }
    // Move the panes out, keeping the texture coordinates parallel to the polygons.
    std::size_t kept = 0;
    const bool uv = !scene.texcoords.empty();
    for (std::size_t p = 0; p < scene.polygons.size(); ++p) {
        const Polygon& poly = scene.polygons[p];
        const int pane = pane_of_group[poly.group];
        if (pane >= 0) {
            scene.glazing.push_back({poly, panes[std::size_t(pane)]});
            continue;
        }
        scene.polygons[kept] = poly;
        if (uv) scene.texcoords[kept] = scene.texcoords[p];
        ++kept;
    }
    scene.polygons.resize(kept);
    if (uv) scene.texcoords.resize(kept);
    for (std::size_t g = 0; g < pane_of_group.size(); ++g)
        if (pane_of_group[g] >= 0 &&
            std::none_of(scene.glazing.begin(), scene.glazing.end(),
                         [&](const GlazingPane& q) { return q.polygon.group == g; }))
            scene.warnings.push_back("glazing '" + scene.groups[g] +
                                     "': the group has no polygons");
}

} // namespace

bool is_scene_json(const std::string& path) {
    return lower_extension(path) == ".json";
}

Scene load_scene_json(const std::string& path, const ObjOptions& obj) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, 0, "cannot open scene file");
    std::ostringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    json doc;
    try {
        doc = json::parse(text);
    } catch (const json::exception& e) {
        // "[json.exception.parse_error.101] parse error at line 3, column 5: ...", or
        // "[json.exception.out_of_range.406] number overflow parsing '1e999'" (found by fuzzing)
        std::string m = e.what();
        const auto tag = m.find("] ");
        throw InputError(path, 0,
                         "not valid JSON: " + (tag == std::string::npos ? m : m.substr(tag + 2)));
    }
    KeyLines locator(text);
    json::sax_parse(text, &locator);
    const Reader r(path, locator.lines);
    r.only_keys(
        doc, "",
        {"include", "luminaires", "cameras", "two_sided", "glazing", "sun", "sky", "up", "north"});

    Scene scene;
    scene.source = path;
    if (!doc.contains("include") || !doc["include"].is_array() || doc["include"].empty())
        r.fail("/include", "expected a list of geometry files, e.g. \"include\": [\"room.obj\"]");
    const json& include = doc["include"];
    for (std::size_t i = 0; i < include.size(); ++i) {
        const std::string at = "/include/" + std::to_string(i);
        const std::string file = r.string(include[i], at);
        const std::string ext = lower_extension(file);
        if (ext != ".obj" && ext != ".gltf" && ext != ".glb")
            r.fail(at, "'" + file + "': expected an OBJ or glTF file (.obj, .gltf, .glb)");
        const std::string resolved = r.resolve(file);
        std::error_code ec; // a name too long for the system is an error, not an exception
        if (!fs::exists(resolved, ec))
            r.fail(at, "'" + file + "': " + (ec ? ec.message() : std::string("no such file")) +
                           " (" + resolved + ")");
        ObjOptions part = obj; // the surfaces are finished once, merged (below)
        part.finish_surfaces = false;
        merge(scene, is_gltf(resolved) ? load_gltf(resolved, part) : load_obj(resolved, part));
    }
    if (doc.contains("glazing")) read_glazing(r, doc["glazing"], scene);
    std::vector<char> pick; // per group: two-sided ("two_sided")
    if (doc.contains("two_sided")) {
        // Surface groups whose polygons are two-sided (make_two_sided).
        const json& ts = doc["two_sided"];
        if (!ts.is_array())
            r.fail("/two_sided", "expected a list of surface group names, e.g. \"two_sided\": "
                                 "[\"Glass\"]");
        pick.assign(scene.groups.size(), 0);
        for (std::size_t k = 0; k < ts.size(); ++k) {
            const std::string at = "/two_sided/" + std::to_string(k);
            const std::string name = r.string(ts[k], at);
            const int g = scene.find_group(name);
            if (g < 0)
                r.fail(at, "no surface group '" + name +
                               "' in the included files (groups: " + group_list(scene) + ")");
            pick[std::size_t(g)] = 1;
        }
    }
    if (obj.finish_surfaces)
        finish_surfaces(scene, obj, [&](std::uint32_t p) {
            return !pick.empty() && pick[scene.polygons[p].group] != 0;
        });
    if (doc.contains("luminaires")) {
        const json& ls = doc["luminaires"];
        if (!ls.is_array()) r.fail("/luminaires", "expected a list of luminaires [{...}, ...]");
        for (std::size_t k = 0; k < ls.size(); ++k)
            scene.luminaires.push_back(
                read_luminaire(r, ls[k], "/luminaires/" + std::to_string(k), k, scene.warnings));
    }
    const SkyFrame frame = read_sky_frame(r, doc);
    if (doc.contains("sun")) scene.sun = read_sun(r, doc["sun"], frame, scene.warnings);
    if (doc.contains("sky")) scene.sky = read_sky(r, doc["sky"], frame, scene.sun);
    if (doc.contains("cameras")) {
        const json& cs = doc["cameras"];
        if (!cs.is_array()) r.fail("/cameras", "expected a list of cameras [{...}, ...]");
        std::vector<Camera> cams;
        for (std::size_t k = 0; k < cs.size(); ++k)
            cams.push_back(read_camera(r, cs[k], "/cameras/" + std::to_string(k), k));
        // The file's cameras first: cameras[0] is the default view.
        scene.cameras.insert(scene.cameras.begin(), cams.begin(), cams.end());
    }
    finish_scene(scene, path);
    return scene;
}

} // namespace hemirad
