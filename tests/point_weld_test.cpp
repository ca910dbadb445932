// weld_points (src/render/point_weld.h) against comparing every pair: the sorted cell grid
// must find exactly the pairs within the tolerance, including across cell walls.
#include <gtest/gtest.h>

#include <random>

#include "render/point_weld.h"

namespace hemirad {
namespace {

using glm::dvec3;

// The brute-force answer: every pair within `tol` that may join, transitively; the root of a
// set is its smallest index.
std::vector<std::uint32_t>
weld_every_pair(const std::vector<dvec3>& p, const std::vector<std::uint8_t>& candidate, double tol,
                const std::function<bool(std::uint32_t, std::uint32_t)>& ok) {
    std::vector<std::uint32_t> root(p.size());
    for (std::uint32_t i = 0; i < p.size(); ++i) root[i] = i;
    bool changed = true;
    while (changed) { // propagate the minimum over joined pairs until nothing changes
        changed = false;
        for (std::uint32_t i = 0; i < p.size(); ++i)
            for (std::uint32_t j = 0; j < i; ++j)
                if (candidate[i] && candidate[j] && glm::length(p[i] - p[j]) <= tol && ok(j, i) &&
                    root[i] != root[j]) {
                    root[i] = root[j] = std::min(root[i], root[j]);
                    changed = true;
                }
    }
    return root;
}

TEST(PointWeld, SameAsEveryPair) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const double tol = 1e-3;
    // Clusters of near-coincident points (some just inside, some just outside the tolerance),
    // many of them straddling cell walls (multiples of 2 tol), and some candidates left out.
    std::vector<dvec3> p;
    std::vector<std::uint8_t> candidate;
    for (int c = 0; c < 300; ++c) {
        dvec3 centre(u(rng), u(rng), u(rng));
        if (c % 3 == 0) centre = glm::round(centre / (2 * tol)) * (2 * tol); // on a cell corner
        const int n = 1 + c % 4;
        for (int k = 0; k < n; ++k) {
            const double r = tol * (k % 2 ? 0.45 : 0.55);
            p.push_back(centre + r * glm::normalize(dvec3(u(rng), u(rng), u(rng))));
            candidate.push_back(c % 7 != 0 || k != 0);
        }
    }
    const auto ok = [](std::uint32_t a, std::uint32_t b) { return (a + b) % 5 != 0; };
    const std::vector<std::uint32_t> got = weld_points(p, candidate, tol, ok);
    const std::vector<std::uint32_t> want = weld_every_pair(p, candidate, tol, ok);
    ASSERT_EQ(got.size(), want.size());
    std::size_t welded = 0;
    for (std::size_t i = 0; i < got.size(); ++i) {
        EXPECT_EQ(got[i], want[i]) << "point " << i;
        welded += got[i] != i;
    }
    EXPECT_GT(welded, 100u); // the case exercises welding at all
}

TEST(PointWeld, NothingWithinTheTolerance) {
    const std::vector<dvec3> p = {{0, 0, 0}, {0.0021, 0, 0}, {0, 0.0021, 0}};
    const std::vector<std::uint8_t> all(3, 1);
    const auto root = weld_points(p, all, 1e-3, [](auto, auto) { return true; });
    EXPECT_EQ(root, (std::vector<std::uint32_t>{0, 1, 2}));
}

} // namespace
} // namespace hemirad
