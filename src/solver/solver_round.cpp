// A parallel round of progressive shooting (docs/scaling.md): with N ranks, the N strongest
// shooters are chosen identically on every rank, each rank shoots one, and every rank applies
// every rank's shot, in rank order, from the links all-gathered. The operations (and so the
// float sums) are the same on every rank: all hold the bit-identical solution after a round.
#include <algorithm>
#include <cstring>
#include <type_traits>

#include "hemirad/error.h"
#include "hemirad/solver.h"
#include "solver/light_layers.h"
#include "solver/solver_detail.h"

namespace hemirad {

namespace {

using solver_detail::Clock;
using solver_detail::since;
using solver_detail::sum;

/// What a rank tells the others about its shot (fixed size, then the links and view codes).
struct ShotHeader {
    std::int32_t kind = 0; ///< 0 nothing shot, 1 a patch, 2 a luminaire
    std::int32_t luminaire = -1;
    PatchAddress shooter;
    std::int32_t refined = 0;
    double dB[3] = {0, 0, 0}; ///< unshot radiosity shot (a luminaire: its power)
    double area = 0;          ///< shooter area (a luminaire: 1)
    double shooter_power = 0;
    double parallax = -1;
    double t_select = 0, t_push_pull = 0, t_form_factors = 0;
    double seconds = 0; ///< the sender's solve time when it sent
    std::uint64_t links = 0, learned = 0, provider = 0;
};
static_assert(std::is_trivially_copyable_v<ShotHeader>);

struct WireLink {
    PatchAddress receiver;
    float ff;
};
struct WireView {
    std::uint64_t node;
    std::uint64_t code;
};

template <class T> void put(std::vector<std::uint8_t>& out, const T* v, std::size_t n) {
    const auto* p = reinterpret_cast<const std::uint8_t*>(v);
    out.insert(out.end(), p, p + n * sizeof(T));
}

class Reader {
  public:
    explicit Reader(const std::vector<std::uint8_t>& b) : b_(b) {}
    template <class T> void get(T* v, std::size_t n) {
        HEMIRAD_CHECK(n <= (b_.size() - at_) / sizeof(T));
        if (n == 0) return; // v may be null (an empty vector's data()): memcpy must not see it
        std::memcpy(static_cast<void*>(v), b_.data() + at_, n * sizeof(T));
        at_ += n * sizeof(T);
    }
    bool done() const { return at_ == b_.size(); }

  private:
    const std::vector<std::uint8_t>& b_;
    std::size_t at_ = 0;
};

struct Candidate {
    double power;
    int luminaire; ///< -1: a polygon
    std::uint32_t polygon;
};

} // namespace

bool Solver::step_round() {
    const auto t_start = Clock::now();
    // Parallel rounds keep no light layers (light_layers.h): an edit after them is shot.
    layers_.reset();
    const int me = collective_->rank();
    ShotRecord mine;

    // 1. Select, identically on every rank: the strongest polygons and luminaires by unshot
    // power (a luminaire before a polygon of equal power, as in step()), one per rank, no more
    // than the shots left.
    auto t0 = Clock::now();
    std::vector<Candidate> cands;
    for (std::size_t k = 0; k < luminaire_unshot_.size(); ++k) {
        const double u = solver_detail::magnitude(luminaire_unshot_[k]);
        if (u > 0) cands.push_back({u, int(k), 0});
    }
    for (std::uint32_t p = 0; p < scene_->polygons.size(); ++p) {
        const double u = solver_detail::magnitude(hierarchy_.unshot_power(p));
        if (u > 0) cands.push_back({u, -1, p});
    }
    const std::size_t k = std::min<std::size_t>(
        {cands.size(), std::size_t(collective_->size()), std::size_t(options_.max_shots - shots_)});
    std::partial_sort(cands.begin(), cands.begin() + std::ptrdiff_t(k), cands.end(),
                      [](const Candidate& a, const Candidate& b) {
                          if (a.power != b.power) return a.power > b.power;
                          if ((a.luminaire >= 0) != (b.luminaire >= 0)) return a.luminaire >= 0;
                          return a.luminaire >= 0 ? a.luminaire < b.luminaire
                                                  : a.polygon < b.polygon;
                      });
    cands.resize(k);
    mine.t_select = since(t0);
    // Every rank pushes every chosen polygon, in the same order: the hierarchies stay equal.
    t0 = Clock::now();
    for (const Candidate& c : cands)
        if (c.luminaire < 0 && hierarchy_.needs_push_pull(c.polygon))
            hierarchy_.push_pull(c.polygon);
    mine.t_push_pull = since(t0);

    // 2. Shoot this rank's shooter.
    ShotHeader h;
    learned_.clear();
    links_.clear();
    if (std::size_t(me) < k) {
        const Candidate& c = cands[std::size_t(me)];
        if (c.luminaire >= 0) {
            h.kind = 2;
            h.luminaire = c.luminaire;
            const dvec3 power = luminaire_unshot_[std::size_t(c.luminaire)];
            t0 = Clock::now();
            Luminaire spare;
            provider_->shoot_point(solver_detail::shooting_luminaire(
                                       scene_->luminaires[std::size_t(c.luminaire)], spare),
                                   links_);
            attenuate_through_glazing(scene_->luminaires[std::size_t(c.luminaire)].position);
            mine.t_form_factors = since(t0);
            mine.shooter_power = solver_detail::magnitude(power);
            h.dB[0] = power.x, h.dB[1] = power.y, h.dB[2] = power.z;
            h.area = 1.0;
        } else {
            h.kind = 1;
            dvec3 dB;
            h.shooter = shoot_patch(c.polygon, mine, dB, h.area);
            h.dB[0] = dB.x, h.dB[1] = dB.y, h.dB[2] = dB.z;
            h.refined = mine.refined;
            h.parallax = mine.parallax;
        }
        if (h.kind != 1) mine.ff_phases = provider_->last_timings(); // shoot_patch sums its own
    }
    h.shooter_power = mine.shooter_power;
    h.t_select = mine.t_select;
    h.t_push_pull = mine.t_push_pull;
    h.t_form_factors = mine.t_form_factors;
    h.seconds = seconds_ + apply_seconds_ + since(t_start);
    const std::vector<double> provider_state = provider_->save_state();
    h.links = links_.size();
    h.learned = learned_.size();
    h.provider = provider_state.size();
    std::vector<std::uint8_t> out;
    out.reserve(sizeof h + links_.size() * sizeof(WireLink));
    put(out, &h, 1);
    for (const Link& l : links_) {
        const WireLink w{l.receiver, l.ff};
        put(out, &w, 1);
    }
    for (const auto& [node, code] : learned_) {
        const WireView w{node, code};
        put(out, &w, 1);
    }
    put(out, provider_state.data(), provider_state.size());

    // 3. Exchange: every rank gets every rank's shot.
    t0 = Clock::now();
    const std::vector<std::vector<std::uint8_t>> all = collective_->all_gather(out);
    const auto t_exchanged = Clock::now();
    ++parallel_.rounds;
    parallel_.seconds += since(t0);
    parallel_.transfer_seconds += collective_->last_transfer_seconds();
    double bytes = 0;
    for (const auto& b : all) bytes += double(b.size());
    parallel_.bytes += bytes;
    parallel_.max_bytes = std::max(parallel_.max_bytes, bytes);

    // 4. Apply, in rank order. First what the shooters learned (view codes; the provider's
    // state, whose only content so far is a running maximum: FormFactorProvider::save_state)
    // and the shooters' power taken away, then the deliveries: an earlier rank's light that
    // reaches a later rank's shooter stays unshot there.
    struct Shot {
        ShotHeader h;
        std::vector<Link> links;
    };
    std::vector<Shot> shots(all.size());
    std::vector<double> merged = provider_state;
    double seconds = 0;
    for (std::size_t r = 0; r < all.size(); ++r) {
        Reader in(all[r]);
        Shot& s = shots[r];
        in.get(&s.h, 1);
        s.links.resize(s.h.links);
        for (Link& l : s.links) {
            WireLink w;
            in.get(&w, 1);
            l.receiver = w.receiver;
            l.ff = w.ff;
        }
        for (std::uint64_t i = 0; i < s.h.learned; ++i) {
            WireView w;
            in.get(&w, 1);
            HEMIRAD_CHECK(w.node < view_.size());
            view_[w.node] = std::uint8_t(w.code);
        }
        std::vector<double> state(s.h.provider);
        in.get(state.data(), state.size());
        HEMIRAD_CHECK(in.done() && state.size() == merged.size());
        for (std::size_t i = 0; i < state.size(); ++i) merged[i] = std::max(merged[i], state[i]);
        seconds = std::max(seconds, s.h.seconds);
    }
    provider_->restore_state(merged);
    for (const Shot& s : shots) {
        if (s.h.kind == 2) luminaire_unshot_[std::size_t(s.h.luminaire)] = dvec3(0.0);
        if (s.h.kind == 1) hierarchy_.clear_unshot(s.h.shooter);
    }
    for (std::size_t r = 0; r < shots.size(); ++r) {
        const Shot& s = shots[r];
        if (s.h.kind == 0) continue;
        ShotRecord rec = int(r) == me ? mine : ShotRecord{};
        rec.shot = shots_ + 1;
        rec.rank = int(r);
        rec.round = parallel_.rounds;
        rec.luminaire = s.h.kind == 2 ? s.h.luminaire : -1;
        rec.shooter = s.h.kind == 2 ? PatchAddress{0xFFFFFFFFu, 0, 0} : s.h.shooter;
        rec.shooter_power = s.h.shooter_power;
        rec.refined = s.h.refined;
        rec.parallax = s.h.parallax;
        rec.t_select = s.h.t_select;
        rec.t_push_pull = s.h.t_push_pull;
        rec.t_form_factors = s.h.t_form_factors;
        rec.links = s.links.size();
        links_ = s.links;
        deliver(dvec3(s.h.dB[0], s.h.dB[1], s.h.dB[2]), s.h.area, rec);
        if (s.h.kind == 1) last_polygon_ = s.h.shooter.polygon;
        row_min_ = std::min(row_min_, rec.row_sum);
        row_max_ = std::max(row_max_, rec.row_sum);
        row_total_ += rec.row_sum;
        if (rec.luminaire < 0) {
            landed_ += std::min(rec.row_sum, 1.0) * rec.shooter_power;
            shot_ += rec.shooter_power;
        }
        ++shots_;
        rec.unshot = unshot_power();
        rec.unshot_fraction = unshot_fraction();
        rec.error_bound = error_bound();
        round_.push_back(std::move(rec));
    }
    // The solve time is the slowest rank's (the same number on every rank: the time limit
    // stops every rank at the same round); this rank's apply time joins the next round's.
    seconds_ = std::max(seconds_, seconds);
    apply_seconds_ = since(t_exchanged);
    if (!round_.empty()) last_ = round_.back();
    return true;
}

namespace {
struct Fnv {
    std::uint64_t h = 1469598103934665603ull;
    template <class T> void add(const T* v, std::size_t n) {
        static_assert(std::is_trivially_copyable_v<T>);
        const auto* p = reinterpret_cast<const std::uint8_t*>(v);
        for (std::size_t i = 0; i < n * sizeof(T); ++i) h = (h ^ p[i]) * 1099511628211ull;
    }
};
} // namespace

std::uint64_t Solver::state_checksum() const {
    Fnv f;
    for (const Hierarchy::Node& n : hierarchy_.nodes()) {
        f.add(&n.H, 1);
        f.add(&n.dB, 1);
        f.add(&n.dI, 1);
    }
    f.add(hierarchy_.unshot_powers().data(), hierarchy_.unshot_powers().size());
    f.add(hierarchy_.dirty_flags().data(), hierarchy_.dirty_flags().size());
    f.add(view_.data(), view_.size());
    f.add(luminaire_unshot_.data(), luminaire_unshot_.size());
    const std::vector<double> provider = provider_->save_state();
    f.add(provider.data(), provider.size());
    const double counters[] = {
        double(shots_), absorbed_.x, absorbed_.y,          absorbed_.z,
        escaped_.x,     escaped_.y,  escaped_.z,           row_min_,
        row_max_,       row_total_,  double(row_guarded_), double(last_polygon_),
        landed_,        shot_};
    f.add(counters, std::size(counters));
    return f.h;
}

} // namespace hemirad
