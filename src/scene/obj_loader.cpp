// OBJ/MTL reading by a parser of our own, so that every message names the file, the line and
// the value, and so that files as exporters write them load without hand edits.
//
// Tolerated, with one warning per kind naming the first file:line (and how many more):
//   - statements we do not use: `l`, `p` (no area), `vp`, `t` (crease tags), `vw` (skin
//     weights), free-form geometry (`cstype`, `curv`, `surf`, ...), and any unknown keyword;
//   - a Kd channel of 1 or more: set to ObjOptions::max_reflectance (one warning per material);
//   - an `mtllib` path that is not where it says: looked up relative to the OBJ's folder, then by
//     its base name next to the OBJ, then in the current folder (the warning says which);
//     further libraries of one `mtllib` statement that exist when another is missing;
//   - `usemtl` of an undefined material, faces before any `usemtl`: the 'default' material;
//   - a face that repeats an earlier face's corners on the same side (it would z-fight with it
//     in a hemicube): dropped; back-to-back coincident faces (a two-sided sheet) are kept;
//   - CR LF line ends, tabs, leading spaces, trailing comments, `\` line continuations,
//     `o`/`g` after `usemtl` (the material carries on, as OBJ says), a material without Kd
//     (reflectance 0; with a `map_Kd`, ObjOptions::max_reflectance), `d` < 1 (surfaces stay
//     opaque);
//   - `map_Kd` (texture.h: PNG, JPEG, ...) multiplied by Kd, found relative to the MTL's folder,
//     then by its base name there: a texture that is missing or cannot be decoded is a warning
//     naming the MTL file:line, and the material keeps its Kd alone; map options (`-s`, `-o`,
//     `-bm`, ...) are ignored with a warning; faces of a textured material without texture
//     coordinates (`f v` or `f v//n`) get Kd times the texture's mean, with a warning.
// Errors (InputError): a file that cannot be read, no polygons, a coordinate or colour that is
// not a finite number, a face index of 0 or outside the vertices defined so far, a face of
// fewer than 3 vertices, a negative Kd or Ke, an MTL library found nowhere.
#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <system_error>

#include "core/geometry.h"
#include "core/line_reader.h"
#include "core/parse.h"
#include "hemirad/error.h"
#include "hemirad/scene_io.h"

namespace hemirad {

namespace {

namespace fs = std::filesystem;

/// "file:line", as messages name places.
std::string where(const std::string& file, int line) {
    return file + ":" + std::to_string(line);
}

/// The statements of a text file: one per line, CR LF or CR line ends removed, a line ending in
/// a backslash joined with the next (OBJ and MTL allow it). `line` is the first line's number.
struct Statement {
    std::string text;
    int line = 0;
};

/// Longest line read [bytes] (a face of kMaxFaceCorners corners "v/t/n" fits many times).
constexpr std::size_t kMaxLineBytes = std::size_t(16) << 20;
/// Most corners of one face (more is not a polygon an exporter writes; it bounds the work).
constexpr std::size_t kMaxFaceCorners = 65536;

std::vector<Statement> read_statements(const std::string& path) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw InputError(path, 0, "is a directory, not a file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, 0, std::string("cannot open file: ") + std::strerror(errno));
    std::vector<Statement> out;
    std::string line;
    int number = 0;
    bool continued = false, too_long = false, has_nul = false;
    while (read_bounded_line(in, line, kMaxLineBytes, too_long, has_nul)) {
        if (number == INT_MAX) throw InputError(path, number, "too many lines");
        ++number;
        if (too_long)
            throw InputError(path, number,
                             "line longer than " + std::to_string(kMaxLineBytes >> 20) +
                                 " MiB (not a text file?)");
        if (has_nul)
            throw InputError(path, number,
                             "NUL byte in '" + quoted_excerpt(line) + "' (not a text file?)");
        if (!line.empty() && line.back() == '\r') line.pop_back();
        // A lone CR also ends a line (old Mac files): split here.
        std::size_t start = 0;
        for (std::size_t cr; (cr = line.find('\r', start)) != std::string::npos; start = cr + 1) {
            out.push_back({line.substr(start, cr - start), number});
            continued = false;
        }
        std::string rest = line.substr(start);
        const bool continues = !rest.empty() && rest.back() == '\\';
        if (continues) rest.back() = ' ';
        if (continued) {
            if (out.back().text.size() + rest.size() > kMaxLineBytes)
                throw InputError(path, out.back().line,
                                 "statement continued with \\ over more than " +
                                     std::to_string(kMaxLineBytes >> 20) + " MiB");
            out.back().text += rest;
        } else {
            out.push_back({rest, number});
        }
        continued = continues;
    }
    if (in.bad())
        throw InputError(path, 0, std::string("cannot read file: ") + std::strerror(errno));
    return out;
}

bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\v' || c == '\f';
}

/// Whitespace-separated tokens; a token that starts with '#' ends the statement (a comment).
std::vector<std::string> tokens(const std::string& s) {
    std::vector<std::string> out;
    std::size_t i = 0;
    while (i < s.size()) {
        while (i < s.size() && is_space(s[i])) ++i;
        if (i >= s.size() || s[i] == '#') break;
        const std::size_t b = i;
        while (i < s.size() && !is_space(s[i])) ++i;
        out.push_back(s.substr(b, i - b));
    }
    return out;
}

/// A name after its keyword (groups, materials): the remaining tokens joined by one space.
std::string name_of(const std::vector<std::string>& w) {
    std::string n;
    for (std::size_t k = 1; k < w.size(); ++k) n += (k > 1 ? " " : "") + w[k];
    return n;
}

/// `mtllib` file names: separated by whitespace, "\ " is a space inside a name.
std::vector<std::string> library_names(const std::string& s, std::size_t from) {
    std::vector<std::string> out;
    std::string cur;
    for (std::size_t i = from; i < s.size(); ++i) {
        if (s[i] == '\\' && i + 1 < s.size() && is_space(s[i + 1])) {
            cur += s[++i];
        } else if (is_space(s[i])) {
            if (!cur.empty()) out.push_back(cur);
            cur.clear();
        } else if (s[i] == '#' && cur.empty()) {
            break;
        } else {
            cur += s[i];
        }
    }
    if (!cur.empty()) out.push_back(cur);
    return out;
}

/// Parses a whole token as a double (core/parse.h); false if it is not a number at all.
/// Accepts nan, inf and values out of range (read as inf or 0), which the callers reject with
/// a message of their own.
bool parse_token_double(const std::string& s, double& out) {
    const char* b = s.data();
    const NumberRead r = read_double(b, b + s.size(), out);
    return r.found(b) && r.end == b + s.size();
}

/// Warnings collected while reading: one per kind, naming the first place and the count.
class Notes {
  public:
    /// Records one occurrence of `kind` at `place`; `text` describes the first one.
    void add(const std::string& kind, const std::string& place, const std::string& text) {
        auto [it, fresh] = index_.try_emplace(kind, notes_.size());
        if (fresh) notes_.push_back({place, text, 0});
        ++notes_[it->second].count;
    }
    void append_to(std::vector<std::string>& warnings) const {
        for (const Note& n : notes_)
            warnings.push_back(n.place + ": " + n.text +
                               (n.count > 1
                                    ? " (" + std::to_string(n.count) + " times; the first is named)"
                                    : ""));
    }

  private:
    struct Note {
        std::string place, text;
        long count = 0;
    };
    std::map<std::string, std::size_t> index_;
    std::vector<Note> notes_;
};

// --- MTL ---------------------------------------------------------------------------------

struct MtlMaterial {
    Material m;
    std::string place;          ///< file:line of its newmtl
    std::string map_kd{};       ///< the texture file named by map_Kd, resolved; "" = none
    std::string map_kd_place{}; ///< file:line of the map_Kd
    bool has_kd = false;
};

/// The file name of a `map_Kd` statement: the words after its options (`-s u v w`, `-o ...`,
/// `-clamp on`, ...; options are skipped, `options` lists them). Backslashes become slashes.
std::string map_file_name(const std::vector<std::string>& w, std::string& options) {
    static const std::map<std::string, int> arity = {
        {"-blendu", 1},  {"-blendv", 1}, {"-boost", 1},  {"-mm", 2},    {"-o", 3},
        {"-s", 3},       {"-t", 3},      {"-texres", 1}, {"-clamp", 1}, {"-bm", 1},
        {"-imfchan", 1}, {"-type", 1},   {"-cc", 1}};
    std::size_t i = 1;
    while (i < w.size()) {
        const auto it = arity.find(w[i]);
        if (it == arity.end()) break;
        options += (options.empty() ? "" : " ") + w[i];
        ++i;
        // -o, -s, -t take 1 to 3 numbers.
        for (int k = 0; k < it->second && i + 1 < w.size(); ++k) {
            double x;
            if (k > 0 && !parse_token_double(w[i], x)) break;
            ++i;
        }
    }
    std::string name;
    for (; i < w.size(); ++i) name += (name.empty() ? "" : " ") + w[i];
    std::replace(name.begin(), name.end(), '\\', '/');
    return name;
}

/// Reads "Kd r [g b]" / "Ke r [g b]": one value means grey (g = b = r).
dvec3 parse_colour(const std::vector<std::string>& w, const std::string& file, int line) {
    if (w.size() != 2 && w.size() < 4) throw InputError(file, line, w[0] + " needs 1 or 3 values");
    dvec3 c(0.0);
    for (int k = 0; k < 3; ++k) {
        const std::string& t = w.size() == 2 ? w[1] : w[std::size_t(k) + 1];
        double x;
        if (!parse_token_double(t, x))
            throw InputError(file, line,
                             "cannot parse " + w[0] + " value '" + quoted_excerpt(t) + "'");
        if (!std::isfinite(x))
            throw InputError(file, line, w[0] + " value " + quoted_excerpt(t) + " is not finite");
        c[k] = x;
    }
    return c;
}

std::string colour_text(const std::vector<std::string>& w) {
    std::string s = w[0];
    for (std::size_t k = 1; k < w.size() && k < 4; ++k) s += " " + w[k];
    return s;
}

void read_mtl(const std::string& path, const ObjOptions& options,
              std::vector<MtlMaterial>& materials, std::map<std::string, std::size_t>& by_name,
              Notes& notes) {
    std::size_t current = materials.size(); // index of the material being defined; none yet
    const auto close = [&] {
        if (current < materials.size() && !materials[current].has_kd &&
            materials[current].map_kd.empty() && materials[current].m.Ke == dvec3(0.0))
            notes.add("mtl no Kd", materials[current].place,
                      "material '" + materials[current].m.name +
                          "' has no Kd: reflectance 0 (black)");
    };
    for (const Statement& st : read_statements(path)) {
        const std::vector<std::string> w = tokens(st.text);
        if (w.empty()) continue;
        const std::string& key = w[0];
        const std::string place = where(path, st.line);
        if (key == "newmtl") {
            close();
            const std::string name = name_of(w);
            const auto [it, fresh] = by_name.try_emplace(name, materials.size());
            if (fresh) {
                materials.push_back({Material{name, dvec3(0.0), dvec3(0.0)}, place});
            } else {
                notes.add("mtl redefined " + name, place,
                          "material '" + name + "' is defined again (first at " +
                              materials[it->second].place + "): this definition is used");
                materials[it->second] = {Material{name, dvec3(0.0), dvec3(0.0)}, place};
            }
            current = it->second;
            continue;
        }
        if (key == "Kd" || key == "Ke") {
            const dvec3 c = parse_colour(w, path, st.line);
            if (current >= materials.size()) {
                notes.add("mtl before newmtl", place, key + " before any newmtl: ignored");
                continue;
            }
            Material& m = materials[current].m;
            const std::string name = m.name;
            for (int k = 0; k < 3; ++k)
                if (c[k] < 0)
                    throw InputError(path, st.line,
                                     (key == "Kd" ? "diffuse reflectance Kd " : "emission Ke ") +
                                         num(c[k]) + " of material '" + name + "' is negative");
            if (key == "Ke") {
                m.Ke = c;
                continue;
            }
            dvec3 rho = c;
            bool clamped = false;
            for (int k = 0; k < 3; ++k)
                if (rho[k] >= 1) rho[k] = options.max_reflectance, clamped = true;
            if (clamped)
                notes.add("mtl Kd clamp " + name, place,
                          colour_text(w) + " of material '" + name +
                              "' is 1 or more (a surface can't reflect all the light it "
                              "receives): reflectance " +
                              num(options.max_reflectance) + " used there (--max-reflectance)");
            m.rho = rho;
            materials[current].has_kd = true;
            continue;
        }
        if (current >= materials.size()) continue;
        if (key == "map_Kd") {
            MtlMaterial& mm = materials[current];
            std::string options;
            const std::string name = map_file_name(w, options);
            if (!options.empty())
                notes.add("mtl map options", place,
                          "map_Kd options (" + options + ") are not supported: ignored");
            if (name.empty()) {
                notes.add("mtl map_Kd empty", place,
                          "map_Kd names no file: material '" + mm.m.name + "' uses its Kd");
                continue;
            }
            const fs::path dir = fs::path(path).parent_path();
            fs::path found = dir / name;
            std::error_code ec;
            if (!fs::is_regular_file(found, ec) &&
                fs::is_regular_file(dir / fs::path(name).filename(), ec))
                found = dir / fs::path(name).filename();
            mm.map_kd = found.lexically_normal().string();
            mm.map_kd_place = place;
            continue;
        }
        if (key == "d" && w.size() > 1) {
            double d;
            if (parse_token_double(w.back(), d) && d < 1)
                notes.add("mtl transparency", place,
                          "transparency (d " + w.back() + ") of material '" +
                              materials[current].m.name +
                              "' is not modelled: every surface is opaque");
        }
        // Everything else (Ka, Ks, Ns, Ni, illum, other maps, PBR extensions) describes what
        // a diffuse radiosity solution does not use.
    }
    close();
}

/// Where `name` (from `mtllib` in `obj`) is: relative to the OBJ's folder, its base name next
/// to the OBJ, then the current folder (as written, then by base name). Empty if nowhere;
/// `looked` lists the places tried.
fs::path find_library(const std::string& obj, const std::string& name, std::string& looked,
                      std::string& how) {
    const fs::path dir = fs::path(obj).parent_path();
    const fs::path written(name);
    const fs::path base = written.filename();
    const std::vector<std::pair<fs::path, const char*>> candidates = {
        {dir / written, ""},
        {dir / base, "its base name next to the OBJ"},
        {written, "the current folder"},
        {base, "its base name in the current folder"},
    };
    std::set<fs::path> tried;
    for (const auto& [p, what] : candidates) {
        if (!tried.insert(p.lexically_normal()).second) continue;
        looked += (looked.empty() ? "" : ", ") + p.string();
        std::error_code ec;
        if (fs::is_regular_file(p, ec)) {
            how = what;
            return p.lexically_normal();
        }
    }
    return {};
}

// --- OBJ ---------------------------------------------------------------------------------

struct Face {
    std::vector<std::uint32_t> v; ///< 0-based vertex indices
    std::vector<long> t;          ///< 0-based texture coordinate indices, -1 where none
    int line = 0;
    int material = -1;            ///< usemtl index into `usemtl_names`, -1 before any usemtl
    std::uint32_t group_name = 0; ///< index into `group_names` (g/o in effect, may be "")
};

/// Parses one face corner "v", "v/t", "v//n" or "v/t/n"; returns the 0-based vertex index. A
/// texture or normal index outside those defined is only noted: they are not used.
std::uint32_t face_corner(const std::string& token, long vertices, long texcoords, long normals,
                          const std::string& file, int line, Notes& notes, long& texcoord) {
    texcoord = -1;
    const long counts[3] = {vertices, texcoords, normals};
    const char* what[3] = {"vertex", "texture coordinate", "normal"};
    std::uint32_t result = 0;
    std::size_t start = 0;
    for (int part = 0; part < 3 && start <= token.size(); ++part) {
        std::size_t slash = token.find('/', start);
        if (slash == std::string::npos) slash = token.size();
        const std::string idx = token.substr(start, slash - start);
        start = slash + 1;
        if (idx.empty() && part > 0) continue; // "v//n": no texture coordinate
        long long i = 0;                       // out of range: the limit, which refers to no vertex
        const NumberRead r = read_integer(idx.data(), idx.data() + idx.size(), i);
        if (!r.found(idx.data()) || r.end != idx.data() + idx.size() || i == 0)
            throw InputError(file, line,
                             "cannot parse face " + std::string(what[part]) + " index '" +
                                 quoted_excerpt(token) + "'");
        const long resolved = i > 0 ? i : counts[part] + 1 + i;
        if (resolved < 1 || resolved > counts[part]) {
            const std::string text = "face " + std::string(what[part]) + " index " +
                                     quoted_excerpt(idx) + " refers to no " + what[part] + " (" +
                                     std::to_string(counts[part]) + " defined so far)";
            if (part == 0) throw InputError(file, line, text);
            notes.add(std::string("index ") + what[part], where(file, line),
                      text + ": ignored (normals are not used; a face without texture "
                             "coordinates has none)");
        } else if (part == 1) {
            texcoord = resolved - 1;
        }
        if (part == 0) result = std::uint32_t(resolved - 1);
        if (slash == token.size()) break;
    }
    return result;
}

/// What an ignored statement is, for its warning.
std::string ignored_reason(const std::string& key) {
    if (key == "l" || key == "p") return "lines and points have no area";
    if (key == "t") return "crease tags of subdivision surfaces";
    if (key == "vw") return "skin weights";
    if (key == "vp") return "parameter-space vertices of free-form geometry";
    static const std::set<std::string> freeform = {
        "cstype", "deg", "bmat", "step",  "curv",  "curv2", "surf", "parm", "trim", "hole", "scrv",
        "sp",     "end", "con",  "ctech", "stech", "bsp",   "bzp",  "cdc",  "cdp",  "res"};
    if (freeform.count(key)) return "free-form curves and surfaces are not supported";
    static const std::set<std::string> display = {"mg",       "bevel",      "c_interp",
                                                  "d_interp", "lod",        "usemap",
                                                  "maplib",   "shadow_obj", "trace_obj"};
    if (display.count(key)) return "a display or rendering attribute";
    return "unknown statement";
}

/// The distinct corners of a face, sorted (the identity of coincident faces).
std::vector<dvec3> corner_set(const std::vector<dvec3>& vertices, const Face& f) {
    std::vector<dvec3> c;
    for (std::uint32_t v : f.v) {
        dvec3 p = vertices[v];
        for (int i = 0; i < 3; ++i)
            if (p[i] == 0) p[i] = 0.0; // -0 and +0 alike
        c.push_back(p);
    }
    std::sort(c.begin(), c.end(), [](const dvec3& a, const dvec3& b) {
        return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
    });
    c.erase(std::unique(c.begin(), c.end()), c.end());
    return c;
}

std::uint64_t hash_corners(const std::vector<dvec3>& c) {
    std::uint64_t h = 1469598103934665603ull;
    for (const dvec3& p : c)
        for (int i = 0; i < 3; ++i) {
            std::uint64_t b;
            std::memcpy(&b, &p[i], sizeof b);
            h = (h ^ b) * 1099511628211ull;
        }
    return h;
}

} // namespace

Scene load_obj(const std::string& path, const ObjOptions& options) {
    if (!(options.max_reflectance > 0 && options.max_reflectance < 1))
        throw InputError("--max-reflectance " + num(options.max_reflectance) +
                         " must be in (0, 1)");
    std::error_code ec; // a name too long for the system is an error, not an exception
    if (!fs::exists(path, ec)) throw InputError(path, 0, ec ? ec.message() : "no such file");
    if (fs::is_directory(path, ec)) throw InputError(path, 0, "is a directory, not an OBJ file");

    Notes notes;
    std::vector<dvec3> vertices;
    std::vector<glm::dvec2> texcoords; // (u, 1 - v): texture.h's convention, t down
    long normals = 0;
    std::vector<Face> faces;
    std::vector<std::string> usemtl_names;  // as written, in order of first use
    std::vector<std::string> usemtl_places; // file:line of the first usemtl of each
    std::map<std::string, int> usemtl_index;
    std::vector<std::string> group_names{""}; // g/o names in effect; "" = none given
    std::map<std::string, std::uint32_t> group_name_index{{"", 0}};
    std::vector<MtlMaterial> mtl;
    std::map<std::string, std::size_t> mtl_by_name;
    std::set<fs::path> libraries_read;
    int material = -1;
    std::uint32_t group = 0;
    std::string ignored; // the keywords of ignored statements, for an empty scene's error

    for (const Statement& st : read_statements(path)) {
        const std::vector<std::string> w = tokens(st.text);
        if (w.empty()) continue;
        const std::string& key = w[0];
        const int line = st.line;
        if (key == "v") {
            if (w.size() < 4)
                throw InputError(path, line,
                                 "vertex needs 3 coordinates: '" + quoted_excerpt(st.text) + "'");
            dvec3 p;
            for (int k = 0; k < 3; ++k) {
                const std::string& t = w[std::size_t(k) + 1];
                if (!parse_token_double(t, p[k]))
                    throw InputError(path, line,
                                     "cannot parse vertex coordinate '" + quoted_excerpt(t) + "'");
                if (!std::isfinite(p[k]))
                    throw InputError(path, line,
                                     "vertex coordinate " + quoted_excerpt(t) +
                                         " is not a finite number");
            }
            vertices.push_back(p); // a 4th value (w) or vertex colours are not used
        } else if (key == "vt") {
            glm::dvec2 t(0.0);
            for (std::size_t k = 0; k < 2 && k + 1 < w.size(); ++k) {
                if (!parse_token_double(w[k + 1], t[int(k)]) || !std::isfinite(t[int(k)]))
                    throw InputError(path, line,
                                     "texture coordinate '" + quoted_excerpt(w[k + 1]) +
                                         "' is not a finite number");
            }
            if (w.size() < 2) throw InputError(path, line, "vt needs at least 1 value");
            texcoords.emplace_back(t.x, 1.0 - t.y);
        } else if (key == "vn") {
            ++normals;
        } else if (key == "f" || key == "fo") {
            if (w.size() < 4)
                throw InputError(path, line,
                                 "face needs at least 3 vertices: '" + quoted_excerpt(st.text) +
                                     "'");
            if (w.size() - 1 > kMaxFaceCorners)
                throw InputError(path, line,
                                 "face has " + std::to_string(w.size() - 1) +
                                     " corners, more than " + std::to_string(kMaxFaceCorners));
            Face f;
            f.line = line;
            f.material = material;
            f.group_name = group;
            for (std::size_t k = 1; k < w.size(); ++k) {
                long t = -1;
                f.v.push_back(face_corner(w[k], long(vertices.size()), long(texcoords.size()),
                                          normals, path, line, notes, t));
                f.t.push_back(t);
            }
            faces.push_back(std::move(f));
        } else if (key == "g" || key == "o") {
            const std::string name = name_of(w);
            const auto [it, fresh] = group_name_index.try_emplace(name, group_names.size());
            if (fresh) group_names.push_back(name);
            group = it->second;
        } else if (key == "usemtl") {
            const std::string name = name_of(w);
            const auto [it, fresh] = usemtl_index.try_emplace(name, int(usemtl_names.size()));
            if (fresh) {
                usemtl_names.push_back(name);
                usemtl_places.push_back(where(path, line));
            }
            material = it->second;
        } else if (key == "mtllib") {
            const std::vector<std::string> names =
                library_names(st.text, st.text.find("mtllib") + 6);
            std::vector<std::pair<std::string, std::string>> missing; // name, places looked
            bool found_any = false;
            for (const std::string& name : names) {
                std::string looked, how;
                const fs::path p = find_library(path, name, looked, how);
                if (p.empty()) {
                    missing.emplace_back(name, looked);
                    continue;
                }
                found_any = true;
                if (!how.empty())
                    notes.add("mtllib found " + name, where(path, line),
                              "material library '" + name + "' is not at " +
                                  (fs::path(path).parent_path() / name).string() + ": using " +
                                  p.string() + " (" + how + ")");
                if (libraries_read.insert(fs::weakly_canonical(p)).second)
                    read_mtl(p.string(), options, mtl, mtl_by_name, notes);
            }
            for (const auto& [name, looked] : missing) {
                if (!found_any)
                    throw InputError(path, line,
                                     "material library '" + name + "' not found (looked for " +
                                         looked + ")");
                notes.add("mtllib missing " + name, where(path, line),
                          "material library '" + name + "' not found (looked for " + looked +
                              "): skipped, the other libraries of this line were read");
            }
        } else if (key == "s") {
            // Smoothing groups: shading normals, not used by a radiosity solution.
        } else {
            if (ignored.find("'" + key + "'") == std::string::npos)
                ignored += (ignored.empty() ? "'" : ", '") + key + "'";
            notes.add("statement " + key, where(path, line),
                      "'" + key + "' statements ignored (" + ignored_reason(key) + ")");
        }
    }

    Scene scene;
    scene.source = path;
    // Materials: every MTL material in the order read; 'default' last, only if a face uses it.
    for (const MtlMaterial& m : mtl) scene.materials.push_back(m.m);
    // Textures: each file once; a missing or undecodable one leaves its material with Kd.
    {
        std::map<std::string, int> texture_index;
        for (std::size_t i = 0; i < mtl.size(); ++i) {
            const MtlMaterial& mm = mtl[i];
            if (mm.map_kd.empty()) continue;
            Material& m = scene.materials[i];
            if (!mm.has_kd) m.rho = dvec3(options.max_reflectance); // Kd 1, as clamped
            auto it = texture_index.find(mm.map_kd);
            if (it == texture_index.end()) {
                int index = -1;
                try {
                    scene.textures.push_back(load_texture(mm.map_kd));
                    index = int(scene.textures.size()) - 1;
                } catch (const InputError& e) {
                    notes.add("mtl map_Kd " + mm.map_kd, mm.map_kd_place,
                              std::string("texture not read (") + e.what() +
                                  "): its materials use their Kd alone");
                }
                it = texture_index.emplace(mm.map_kd, index).first;
            }
            m.texture = it->second;
        }
    }
    std::vector<int> material_of_usemtl(usemtl_names.size(), -1);
    for (std::size_t i = 0; i < usemtl_names.size(); ++i) {
        const auto it = mtl_by_name.find(usemtl_names[i]);
        if (it != mtl_by_name.end()) material_of_usemtl[i] = int(it->second);
    }
    std::uint32_t default_material = 0;
    bool default_used = false;
    const auto use_default = [&] {
        if (!default_used) {
            default_material = std::uint32_t(scene.materials.size());
            scene.materials.push_back(Material{"default", dvec3(0.5), dvec3(0.0)});
            default_used = true;
        }
        return default_material;
    };

    std::map<std::string, std::uint32_t> group_index;
    const auto group_of = [&](const std::string& name) {
        const auto [it, fresh] = group_index.try_emplace(name, std::uint32_t(scene.groups.size()));
        if (fresh) scene.groups.push_back(name);
        return it->second;
    };

    // Coincident faces, before any polygon is made: of two faces with the same distinct corners
    // facing the same side, the later is dropped, or the earlier where only the later emits (a
    // lamp's face laid on a ceiling's); back to back, both stay. Faces are grouped by a hash
    // of their sorted corners (16 bytes a face), then compared exactly.
    std::vector<std::uint8_t> dropped(faces.size(), 0);
    long duplicates = 0;
    std::string first_duplicate, first_sheet;
    {
        std::vector<std::pair<std::uint64_t, std::uint32_t>> keys;
        keys.reserve(faces.size());
        for (std::uint32_t i = 0; i < faces.size(); ++i) {
            const std::vector<dvec3> c = corner_set(vertices, faces[i]);
            if (c.size() >= 3) keys.emplace_back(hash_corners(c), i);
        }
        std::sort(keys.begin(), keys.end());
        std::size_t first_dup = faces.size(), first_sh = faces.size();
        int dup_of = 0, sheet_of = 0;
        std::vector<dvec3> corners;
        const auto emits = [&](const Face& f) {
            const int m = f.material < 0 ? -1 : material_of_usemtl[std::size_t(f.material)];
            return m >= 0 && scene.materials[std::size_t(m)].emits();
        };
        const auto normal_of = [&](const Face& f) {
            corners.clear();
            for (std::uint32_t v : f.v) corners.push_back(vertices[v]);
            return newell_normal(corners);
        };
        for (std::size_t b = 0, e; b < keys.size(); b = e) {
            for (e = b + 1; e < keys.size() && keys[e].first == keys[b].first; ++e) {}
            for (std::size_t j = b + 1; j < e; ++j) {
                const Face& fj = faces[keys[j].second];
                const std::vector<dvec3> cj = corner_set(vertices, fj);
                const dvec3 nj = normal_of(fj);
                if (!(glm::length(nj) > 0)) continue;
                for (std::size_t k = b; k < j; ++k) {
                    const Face& fk = faces[keys[k].second];
                    if (dropped[keys[k].second] || corner_set(vertices, fk) != cj) continue;
                    if (glm::dot(nj, normal_of(fk)) > 0) {
                        const bool keep_later = emits(fj) && !emits(fk);
                        const std::uint32_t drop = keep_later ? keys[k].second : keys[j].second;
                        dropped[drop] = 1;
                        ++duplicates;
                        if (drop < first_dup)
                            first_dup = drop, dup_of = (keep_later ? fj : fk).line;
                    } else if (keys[j].second < first_sh) {
                        first_sh = keys[j].second, sheet_of = fk.line;
                    }
                    break;
                }
            }
        }
        if (duplicates)
            first_duplicate = where(path, faces[first_dup].line) +
                              ": face repeats the corners of the face at line " +
                              std::to_string(dup_of) +
                              " on the same side (the two would z-fight in a hemicube): dropped";
        if (first_sh < faces.size())
            first_sheet = where(path, faces[first_sh].line) +
                          ": face lies back to back on the face at line " +
                          std::to_string(sheet_of) + " (a two-sided sheet): both kept";
    }

    long degenerate = 0, split_quads = 0, fans = 0;
    std::string first_degenerate, first_split, first_fan;
    std::vector<dvec3> corners;
    std::vector<glm::dvec2> corner_uv;
    std::map<std::uint32_t, std::uint32_t> untextured_variant; // textured material -> its mean
    for (std::size_t i = 0; i < faces.size(); ++i) {
        if (dropped[i]) continue;
        const Face& f = faces[i];
        corners.clear();
        for (std::uint32_t v : f.v) corners.push_back(vertices[v]);
        corner_uv.clear();
        if (std::all_of(f.t.begin(), f.t.end(), [](long t) { return t >= 0; }))
            for (long t : f.t) corner_uv.push_back(texcoords[std::size_t(t)]);
        const std::string place = where(path, f.line);

        std::uint32_t m;
        std::string material_name;
        if (f.material < 0) {
            m = use_default();
            material_name = "default";
            notes.add("no usemtl", place,
                      "faces without a material use 'default' (rho 0.5, no emission)");
        } else if (material_of_usemtl[std::size_t(f.material)] < 0) {
            m = use_default();
            material_name = usemtl_names[std::size_t(f.material)];
            notes.add("usemtl undefined " + material_name, usemtl_places[std::size_t(f.material)],
                      "usemtl '" + material_name +
                          "' names no material of the material libraries: its faces use "
                          "'default' (rho 0.5, no emission)");
        } else {
            m = std::uint32_t(material_of_usemtl[std::size_t(f.material)]);
            material_name = scene.materials[m].name;
        }
        const std::string& gname = group_names[f.group_name];
        const std::uint32_t g = group_of(!gname.empty() ? gname : material_name);
        const bool textured = scene.materials[m].texture >= 0;
        if (textured && corner_uv.empty()) {
            // No texture coordinates: a copy of the material with Kd times the texture's mean.
            notes.add("face no vt", place,
                      "faces of textured material '" + material_name +
                          "' without texture coordinates: Kd times the texture's mean");
            m = untextured_material(scene, m, untextured_variant);
        }
        const AddResult r = add_polygon(scene, corners, m, g, 1e-6,
                                        textured && !corner_uv.empty() ? &corner_uv : nullptr);
        if (r.degenerate && degenerate++ == 0) first_degenerate = place;
        if (r.split && corners.size() == 4 && split_quads++ == 0)
            first_split = place + ": face of group '" + scene.groups[g] +
                          "' is a non-planar or concave quad: split into 2 triangles";
        if (r.split && corners.size() > 4 && fans++ == 0)
            first_fan = place + ": face of group '" + scene.groups[g] + "' has " +
                        std::to_string(corners.size()) + " corners: fan-triangulated";
    }
    notes.append_to(scene.warnings);
    if (scene.polygons.empty() && !ignored.empty())
        throw InputError(path, 0,
                         "the scene has no polygons (nothing to solve; ignored: " + ignored + ")");
    const auto times = [](long n) {
        return n > 1 ? " (" + std::to_string(n) + " faces like it; the first is named)"
                     : std::string();
    };
    if (split_quads) scene.warnings.push_back(first_split + times(split_quads));
    if (fans) scene.warnings.push_back(first_fan + times(fans));
    if (duplicates) scene.warnings.push_back(first_duplicate + times(duplicates));
    if (!first_sheet.empty()) scene.warnings.push_back(first_sheet);
    if (degenerate > 0)
        scene.warnings.push_back(first_degenerate + ": dropped " + std::to_string(degenerate) +
                                 " degenerate polygon(s) (zero area or repeated vertices; the "
                                 "first is named)");
    if (options.finish_surfaces) finish_surfaces(scene, options);
    finish_scene(scene, path);
    return scene;
}

void finish_surfaces(Scene& scene, const ObjOptions& options,
                     const std::function<bool(std::uint32_t)>& also) {
    std::uint32_t group = 0;
    if (const std::size_t n = drop_coincident_polygons(scene, &group); n > 0)
        scene.warnings.push_back(
            scene.source + ": dropped " + std::to_string(n) +
            " polygon(s) that repeat the corners of another on the same side (the first in "
            "group '" +
            (group < scene.groups.size() ? scene.groups[group] : std::string("?")) +
            "'): the two would z-fight in a hemicube, and the surface would take its light twice");
    if (options.split_intersections) {
        const SplitStats s = split_intersections(scene);
        if (s.polygons_cut > 0)
            scene.warnings.push_back(
                scene.source + ": cut " + std::to_string(s.polygons_cut) +
                " polygon(s) that other polygons pass through, along where they meet, into " +
                std::to_string(s.pieces) +
                " pieces (so that no patch lies on both sides of a surface; "
                "--split-intersections off keeps them whole)");
    }
    std::size_t paired = 0;
    make_two_sided(
        scene,
        [&](std::uint32_t p) {
            return options.two_sided_surfaces || scene.material_of(scene.polygons[p]).two_sided ||
                   (also && also(p));
        },
        &paired);
    if (paired > 0)
        scene.warnings.push_back(scene.source + ": " + std::to_string(paired) +
                                 " two-sided polygon(s) have their back face in the model "
                                 "already (the same corners, facing the other way): each is "
                                 "paired with that face, and no twin is added on it");
}

Scene load_scene(const std::string& name_or_path, const BuiltinOptions& builtin,
                 const ObjOptions& obj) {
    if (is_builtin(name_or_path)) return make_builtin(name_or_path, builtin);
    std::error_code ec;
    if (!fs::exists(name_or_path, ec))
        throw InputError(name_or_path, 0,
                         (ec ? ec.message() : std::string("no such file")) +
                             ", and not a built-in scene (" + builtin_names() + ")");
    if (is_scene_json(name_or_path)) return load_scene_json(name_or_path, obj);
    if (is_gltf(name_or_path)) return load_gltf(name_or_path, obj);
    return load_obj(name_or_path, obj);
}

} // namespace hemirad
