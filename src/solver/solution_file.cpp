// Solution files: the solver's complete state, for save and resume (layout in the header).
#include "hemirad/solution_file.h"

#include <bit>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <tuple>

#include "hemirad/error.h"
#include "hemirad/solver_options.h"
#include "output/atomic_file.h"

namespace hemirad {

namespace {

constexpr char kMagic[8] = {'H', 'E', 'M', 'I', 'R', 'A', 'D', '\x1a'};

std::uint64_t fnv1a(const char* data, std::size_t size) {
    std::uint64_t h = 1469598103934665603ull;
    for (std::size_t i = 0; i < size; ++i) h = (h ^ std::uint8_t(data[i])) * 1099511628211ull;
    return h;
}

// --- little-endian encoding -------------------------------------------------------------------

class Writer {
  public:
    void u8(std::uint8_t v) { out_.push_back(char(v)); }
    void u32(std::uint32_t v) {
        for (int i = 0; i < 4; ++i) out_.push_back(char((v >> (8 * i)) & 0xff));
    }
    void u64(std::uint64_t v) {
        for (int i = 0; i < 8; ++i) out_.push_back(char((v >> (8 * i)) & 0xff));
    }
    void i64(std::int64_t v) { u64(std::uint64_t(v)); }
    void f32(float v) { u32(std::bit_cast<std::uint32_t>(v)); }
    void f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }
    void vec3(const glm::vec3& v) { f32(v.x), f32(v.y), f32(v.z); }
    void dvec(const dvec3& v) { f64(v.x), f64(v.y), f64(v.z); }
    void str(const std::string& s) {
        u32(std::uint32_t(s.size()));
        out_ += s;
    }
    void raw(const char* p, std::size_t n) { out_.append(p, n); }
    std::string& bytes() { return out_; }

  private:
    std::string out_;
};

class Reader {
  public:
    Reader(const std::string& bytes, std::size_t end, const std::string& path)
        : b_(bytes), end_(end), path_(path) {}
    void need(std::size_t n, const char* what) {
        if (end_ - pos_ < n)
            throw InputError(path_, 0,
                             "truncated solution file: " + std::to_string(n) + " bytes of " + what +
                                 " expected at byte " + std::to_string(pos_) + ", " +
                                 std::to_string(end_ - pos_) + " left");
    }
    std::uint8_t u8(const char* what) {
        need(1, what);
        return std::uint8_t(b_[pos_++]);
    }
    std::uint32_t u32(const char* what) {
        need(4, what);
        std::uint32_t v = 0;
        for (int i = 0; i < 4; ++i) v |= std::uint32_t(std::uint8_t(b_[pos_ + i])) << (8 * i);
        pos_ += 4;
        return v;
    }
    std::uint64_t u64(const char* what) {
        need(8, what);
        std::uint64_t v = 0;
        for (int i = 0; i < 8; ++i) v |= std::uint64_t(std::uint8_t(b_[pos_ + i])) << (8 * i);
        pos_ += 8;
        return v;
    }
    std::int64_t i64(const char* what) { return std::int64_t(u64(what)); }
    float f32(const char* what) { return std::bit_cast<float>(u32(what)); }
    double f64(const char* what) { return std::bit_cast<double>(u64(what)); }
    glm::vec3 vec3(const char* what) {
        glm::vec3 v;
        v.x = f32(what), v.y = f32(what), v.z = f32(what);
        return v;
    }
    dvec3 dvec(const char* what) {
        dvec3 v;
        v.x = f64(what), v.y = f64(what), v.z = f64(what);
        return v;
    }
    std::string str(const char* what) {
        const std::uint32_t n = u32(what);
        need(n, what);
        std::string s = b_.substr(pos_, n);
        pos_ += n;
        return s;
    }
    /// A count of items of `item_size` bytes each that must fit in what is left.
    std::uint64_t count(std::uint64_t n, std::size_t item_size, const char* what) {
        if (item_size > 0 && n > (end_ - pos_) / item_size)
            throw InputError(path_, 0,
                             "corrupt solution file: " + std::to_string(n) + " " + what +
                                 " at byte " + std::to_string(pos_) + " do not fit in the file");
        return n;
    }
    std::size_t pos() const { return pos_; }

  private:
    const std::string& b_;
    std::size_t end_;
    std::size_t pos_ = 0;
    const std::string& path_;
};

std::string hash_text(std::uint64_t h) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%016" PRIx64, h);
    return buf;
}

} // namespace

std::vector<SolutionOption> solution_options(const SolverOptions& o) {
    std::vector<SolutionOption> out;
    for (const SolverOption& opt : solver_option_table())
        if (opt.saved) out.emplace_back(opt.flag, opt.text(o));
    return out;
}

void apply_solution_option(SolverOptions& o, const SolutionOption& option,
                           const std::string& file) {
    const std::string& name = option.first;
    const SolverOption* opt = find_solver_option(name);
    if (!opt || name != opt->flag || !opt->saved)
        throw InputError(file, 0,
                         "unknown saved option '" + name + "' (saved by a newer hemirad?)");
    if (!opt->set_text(o, option.second))
        throw InputError(file, 0,
                         "saved option " + name + " has a malformed value '" + option.second + "'");
}

std::string solution_bytes(const Solver& solver) {
    const Solver::State st = solver.save_state();
    const Scene& scene = solver.scene();
    Writer w;
    w.raw(kMagic, sizeof kMagic);
    w.u32(kSolutionFileVersion);
    w.u64(scene.content_hash());
    w.str(scene.source);
    const std::vector<SolutionOption> options = solution_options(solver.options());
    w.u32(std::uint32_t(options.size()));
    for (const SolutionOption& o : options) w.str(o.first), w.str(o.second);
    const Solver::Counters& c = st.counters;
    w.i64(c.shots);
    w.dvec(c.absorbed);
    w.dvec(c.escaped);
    w.f64(c.row_min);
    w.f64(c.row_max);
    w.f64(c.row_total);
    w.i64(c.row_guarded);
    w.i64(c.last_polygon);
    w.f64(c.seconds);
    w.u32(std::uint32_t(st.unshot.size()));
    w.u64(st.nodes.size());
    for (const Hierarchy::Node& n : st.nodes) w.vec3(n.H), w.vec3(n.dB), w.vec3(n.dI);
    for (std::size_t p = 0; p < st.unshot.size(); ++p) w.dvec(st.unshot[p]), w.u8(st.dirty[p]);
    for (std::uint8_t e : st.enclosed) w.u8(e);
    w.u32(std::uint32_t(st.provider.size()));
    for (double v : st.provider) w.f64(v);
    w.u32(std::uint32_t(st.luminaires.size()));
    for (const dvec3& u : st.luminaires) w.dvec(u);
    w.u64(st.clusters.size());
    for (std::uint8_t e : st.clusters) w.u8(e);
    w.f64(c.landed);
    w.f64(c.shot);
    // Version 4: the geometry apart from the photometry (resuming an edited scene).
    w.u64(scene.geometry_hash());
    const Photometry ph = photometry(scene);
    for (std::size_t p = 0; p < ph.rho.size(); ++p) w.dvec(ph.rho[p]), w.dvec(ph.exitance[p]);
    w.u32(std::uint32_t(ph.luminaires.size()));
    for (const dvec3& power : ph.luminaires) w.dvec(power);
    // Version 5: the luminaires' light layers (light_layers.h), or none.
    w.u32(std::uint32_t(st.layers.size()));
    for (const Solver::State::Layer& l : st.layers) {
        for (const Hierarchy::Node& n : l.nodes) w.vec3(n.H), w.vec3(n.dB), w.vec3(n.dI);
        for (std::size_t p = 0; p < l.unshot.size(); ++p) w.dvec(l.unshot[p]), w.u8(l.dirty[p]);
        w.dvec(l.absorbed);
        w.dvec(l.escaped);
    }
    w.u64(fnv1a(w.bytes().data(), w.bytes().size()));
    return std::move(w.bytes());
}

void save_solution(const std::string& path, const Solver& solver) {
    write_file_atomically(path, solution_bytes(solver));
}

SolutionFile parse_solution(const std::string& bytes, const std::string& path) {
    if (bytes.size() < sizeof kMagic + 4 + 8 ||
        std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
        throw InputError(path, 0, "not a hemirad solution file (no HEMIRAD magic header)");
    Reader head(bytes, bytes.size(), path);
    for (std::size_t i = 0; i < sizeof kMagic; ++i) head.u8("magic");
    const std::uint32_t version = head.u32("version");
    if (version < 1 || version > kSolutionFileVersion)
        throw InputError(path, 0,
                         "solution file format version " + std::to_string(version) +
                             " is not supported (this hemirad reads versions 1 to " +
                             std::to_string(kSolutionFileVersion) + ")");
    const std::size_t body = bytes.size() - 8;
    std::uint64_t stored = 0;
    for (int i = 0; i < 8; ++i) stored |= std::uint64_t(std::uint8_t(bytes[body + i])) << (8 * i);
    if (stored != fnv1a(bytes.data(), body))
        throw InputError(path, 0,
                         "corrupt solution file: checksum mismatch (the file was "
                         "truncated or changed after it was written)");

    Reader r(bytes, body, path);
    for (std::size_t i = 0; i < sizeof kMagic; ++i) r.u8("magic");
    r.u32("version");
    SolutionFile f;
    f.scene_hash = r.u64("scene hash");
    f.scene_source = r.str("scene source");
    const std::uint64_t n_options = r.count(r.u32("option count"), 8, "options");
    for (std::uint64_t i = 0; i < n_options; ++i) {
        std::string name = r.str("option name");
        std::string value = r.str("option value");
        f.options.emplace_back(std::move(name), std::move(value));
    }
    Solver::Counters& c = f.state.counters;
    c.shots = r.i64("shots");
    c.absorbed = r.dvec("absorbed power");
    c.escaped = r.dvec("escaped power");
    c.row_min = r.f64("row sum min");
    c.row_max = r.f64("row sum max");
    c.row_total = r.f64("row sum total");
    c.row_guarded = r.i64("guarded rows");
    c.last_polygon = r.i64("last polygon");
    c.seconds = r.f64("seconds");
    const std::uint32_t polygons = r.u32("polygon count");
    const std::uint64_t nodes = r.u64("node count");
    r.count(nodes, 37, "nodes");
    r.count(polygons, 25, "polygons");
    f.state.nodes.resize(nodes);
    for (Hierarchy::Node& n : f.state.nodes) {
        n.H = r.vec3("node H");
        n.dB = r.vec3("node dB");
        n.dI = r.vec3("node dI");
    }
    f.state.unshot.resize(polygons);
    f.state.dirty.resize(polygons);
    for (std::uint32_t p = 0; p < polygons; ++p) {
        f.state.unshot[p] = r.dvec("unshot power");
        f.state.dirty[p] = r.u8("dirty flag");
    }
    f.state.enclosed.resize(nodes);
    for (std::uint8_t& e : f.state.enclosed) e = r.u8("enclosed flags");
    const std::uint64_t n_provider = r.count(r.u32("provider state count"), 8, "provider values");
    f.state.provider.resize(n_provider);
    for (double& v : f.state.provider) v = r.f64("provider state");
    if (version >= 2) { // version 1 had no luminaires
        const std::uint64_t n_lum = r.count(r.u32("luminaire count"), 24, "luminaires");
        f.state.luminaires.resize(n_lum);
        for (dvec3& u : f.state.luminaires) u = r.dvec("luminaire unshot power");
    }
    if (version >= 3) { // version 3: the cluster tree's view codes
        const std::uint64_t n_clusters = r.count(r.u64("cluster count"), 1, "cluster view codes");
        f.state.clusters.resize(n_clusters);
        for (std::uint8_t& e : f.state.clusters) e = r.u8("cluster view code");
        c.landed = r.f64("landed power");
        c.shot = r.f64("shot power");
    }
    if (version >= 4) { // version 4: the geometry hash and the photometry apart
        f.geometry_hash = r.u64("geometry hash");
        r.count(polygons, 48, "polygons' photometry");
        f.photometry.rho.resize(polygons);
        f.photometry.exitance.resize(polygons);
        for (std::uint32_t p = 0; p < polygons; ++p) {
            f.photometry.rho[p] = r.dvec("polygon reflectance");
            f.photometry.exitance[p] = r.dvec("polygon exitance");
        }
        const std::uint64_t n_lum = r.count(r.u32("luminaire count"), 24, "luminaire powers");
        f.photometry.luminaires.resize(n_lum);
        for (dvec3& power : f.photometry.luminaires) power = r.dvec("luminaire power");
        f.has_photometry = true;
    }
    if (version >= 5) { // version 5: the luminaires' light layers
        const std::uint64_t n_layers = r.u32("light layer count");
        r.count(n_layers, 36 * nodes + 25 * std::uint64_t(polygons) + 48, "light layers");
        f.state.layers.resize(n_layers);
        for (Solver::State::Layer& l : f.state.layers) {
            l.nodes.resize(nodes);
            for (Hierarchy::Node& n : l.nodes) {
                n.H = r.vec3("light layer H");
                n.dB = r.vec3("light layer dB");
                n.dI = r.vec3("light layer dI");
            }
            l.unshot.resize(polygons);
            l.dirty.resize(polygons);
            for (std::uint32_t p = 0; p < polygons; ++p) {
                l.unshot[p] = r.dvec("light layer unshot power");
                l.dirty[p] = r.u8("light layer dirty flag");
            }
            l.absorbed = r.dvec("light layer absorbed power");
            l.escaped = r.dvec("light layer escaped power");
        }
    }
    if (version < 3) { // versions 1 and 2 coded parallax 16 steps to an octave from 2 up to 255
        for (std::uint8_t& e : f.state.enclosed)
            if (e >= 2) e = std::uint8_t(2 + (e - 2) / 2 > 125 ? 125 : 2 + (e - 2) / 2);
    }
    if (r.pos() != body)
        throw InputError(path, 0,
                         "corrupt solution file: " + std::to_string(body - r.pos()) +
                             " unexpected bytes before the checksum");
    return f;
}

SolutionFile read_solution(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw InputError(path, 0, "is a directory, not a solution file");
    if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
        throw InputError(path, 0, "is not a regular file (a solution file is read whole)");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, 0, "cannot open solution file");
    std::ostringstream s;
    s << in.rdbuf();
    if (in.bad()) throw InputError(path, 0, "error reading solution file");
    return parse_solution(s.str(), path);
}

void check_solution_scene(const SolutionFile& file, const std::string& path, const Scene& scene,
                          const std::string& scene_path) {
    const std::uint64_t h = scene.content_hash();
    if (file.scene_hash == h) return;
    if (!file.has_photometry)
        throw InputError(path + ": the solution was saved for another scene: " + file.scene_source +
                         " (content hash " + hash_text(file.scene_hash) + "), but " + scene_path +
                         " has content hash " + hash_text(h) +
                         " (geometry or materials differ; a solution file of format version 4 "
                         "or later resumes across an edit of materials or luminaire multipliers)");
    const std::uint64_t g = scene.geometry_hash();
    if (file.geometry_hash != g)
        throw InputError(path + ": the solution was saved for another scene: " + file.scene_source +
                         " (geometry hash " + hash_text(file.geometry_hash) + "), but " +
                         scene_path + " has geometry hash " + hash_text(g) +
                         " (its geometry differs: polygons, groups, textures or the luminaires' "
                         "placement or distributions; only materials' reflectance and emission "
                         "and luminaires' multipliers may change on resume)");
}

ResumeEdits resume_solution(Solver& solver, const SolutionFile& file, const std::string& path) {
    const std::vector<SolutionOption> now = solution_options(solver.options());
    for (const SolutionOption& saved : file.options) {
        for (const SolutionOption& o : now)
            if (o.first == saved.first && o.second != saved.second)
                throw InputError(path, 0,
                                 "saved with " + saved.first + " " + saved.second +
                                     ", but this solver has " + o.second);
    }
    ResumeEdits edits;
    try {
        solver.restore_state(file.state);
        // The scene's photometry now against the saved one: the differences become unshot
        // power (incremental re-solving; nothing when they are equal).
        if (file.has_photometry) {
            const long rescaled = solver.rescaled_luminaires();
            std::tie(edits.luminaires, edits.polygons) = solver.apply_photometry(file.photometry);
            edits.rescaled = std::size_t(solver.rescaled_luminaires() - rescaled);
        }
    } catch (const InputError& e) {
        throw InputError(path, 0, e.what());
    }
    return edits;
}

} // namespace hemirad
