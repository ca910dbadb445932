// "sr" provider: paper 000's shooting method with random sample points (§4): `sr_points`
// points uniformly distributed by area on the shooter patch, `sr_rays` cosine-distributed rays
// from each; the nearest hit of each ray is credited to the receiving node that contains it.
//   F(S->j) = hits_j / (sr_points * sr_rays),   F(j->S) = F(S->j) A_S / A_j   (reciprocity).
// Linking: always at the leaves (level disc.depth of the polygon hit), whatever
// set_link_at_leaves says: a hit can only be credited to the node that contains it, and
// choosing a coarser node by its distance would need the hits first. F(j->S) is not clamped
// to 1 (a small node can draw more than its share of hits by chance); this keeps the estimator
// unbiased and the row sum sum_j F(j->S) A_j / A_S = (rays that hit a receiver) / (rays) <= 1.
// Sample points are drawn in fixed chunks of kChunk points, each chunk with its own
// std::mt19937_64 seeded from options.seed, the shooter address and the chunk's index, so
// results do not depend on the number of threads.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "core/parallel.h"
#include "core/sampling.h"
#include "ff/cpu_linking.h"

namespace hemirad::cpu {

namespace {

constexpr int kChunk = 64; // sample points per generator

class SrProvider final : public CpuProvider {
  public:
    using CpuProvider::CpuProvider;
    std::string name() const override { return "sr"; }

    void shoot(const Shooter& s, std::vector<Link>& links) override {
        const auto start = SteadyClock::now();
        begin_shot(s, links);
        const int points = options_.sr_points, rays = options_.sr_rays;
        const std::uint64_t base =
            mix64(options_.seed ^ mix64((std::uint64_t(s.address.polygon) << 36) ^
                                        (std::uint64_t(s.address.level) << 32) ^ s.address.index));
        dvec3 t, b;
        orthonormal_basis(s.normal, t, b);
        // Hit keys: (polygon << 32) | patch index at the polygon's leaf level.
        const int chunks = (points + kChunk - 1) / kChunk;
        std::vector<std::vector<std::uint64_t>> keys(static_cast<std::size_t>(chunks)); // per chunk
        parallel_for(std::size_t(chunks), threads_, [&](std::size_t chunk) {
            const int c = int(chunk);
            std::vector<std::uint64_t>& out = keys[chunk];
            std::mt19937_64 rng(mix64(base + std::uint64_t(c)));
            const auto uniform01 = [&rng] { return double(rng() >> 11) * 0x1.0p-53; };
            for (int p = c * kChunk; p < std::min(points, (c + 1) * kChunk); ++p) {
                const double pick = uniform01(), u1 = uniform01(), u2 = uniform01();
                const dvec3 origin =
                    area_point(s.geometry.corners.data(), s.geometry.count, pick, u1, u2);
                for (int k = 0; k < rays; ++k) {
                    const double r1 = uniform01(), r2 = uniform01();
                    const dvec3 dir = cosine_direction(s.normal, t, b, r1, r2);
                    Hit hit;
                    if (!bvh_->intersect(origin, dir, 1e300, hit, s.address.polygon)) continue;
                    if (!hit.front) continue; // absorbed by the back of a one-sided polygon
                    const Polygon& q = scene_.polygons[hit.polygon];
                    const std::uint32_t level = std::uint32_t(depth_of(hit.polygon));
                    out.push_back((std::uint64_t(hit.polygon) << 32) |
                                  patch_at(q, level, hit.u, hit.v));
                }
            }
        });
        std::vector<std::uint64_t> all;
        for (const auto& k : keys) all.insert(all.end(), k.begin(), k.end());
        std::sort(all.begin(), all.end());
        const double total = double(points) * double(rays);
        for (std::size_t i = 0; i < all.size();) {
            std::size_t j = i;
            while (j < all.size() && all[j] == all[i]) ++j;
            const std::uint32_t poly = std::uint32_t(all[i] >> 32);
            const std::uint32_t index = std::uint32_t(all[i] & 0xffffffffu);
            const std::uint32_t level = std::uint32_t(depth_of(poly));
            const Polygon& q = scene_.polygons[poly];
            const PatchGeometry g = patch_geometry(q, level, index);
            Link link;
            link.receiver = {poly, level, index};
            link.ff = float(double(j - i) / total * s.geometry.area / g.area);
            link.ff_analytic = float(point_to_polygon_ff(
                g.centre, q.normal, s.geometry.corners.data(), s.geometry.count));
            links.push_back(link);
            i = j;
        }
        timings_ = {{"form_factors", seconds_since(start)}};
    }
};

} // namespace

std::unique_ptr<FormFactorProvider> make_sr_provider(const Scene& scene, const Discretisation& disc,
                                                     const CpuProviderOptions& o,
                                                     std::shared_ptr<const Bvh> bvh) {
    return std::make_unique<SrProvider>(scene, disc, o, std::move(bvh));
}

} // namespace hemirad::cpu
