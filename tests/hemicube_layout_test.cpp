// Hemicube delta form factors (Cohen & Greenberg 1985): no GL needed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "gpu/acos_table.h"
#include "gpu/hemicube.h"
#include "gpu/pixel_runs.h"

using namespace hemirad;

// The delta form factors of the five faces sum to the whole hemisphere, 1, up to the
// midpoint rule's O(1/res^2) error.
TEST(HemicubeLayout, DeltaFormFactorsSumToOne) {
    double previous_error = 1;
    for (int res : {32, 64, 128, 256}) {
        const gpu::HemicubeLayout L = gpu::make_hemicube_layout(res);
        EXPECT_EQ(L.width * L.height, 3 * res * res);
        double sum = 0;
        for (float w : L.delta_ff) sum += w;
        const double error = std::abs(sum - 1);
        EXPECT_LT(error, 2.0 / (res * res)) << "res " << res;
        EXPECT_LT(error, previous_error) << "res " << res;
        previous_error = error;
    }
}

// The top face alone: the form factor of a 90-degree square cone, 4 * B-3(1,1,1) seen from
// a point at distance 1 under a 2x2 square = 0.5541264 (docs/references.md §1(c1), element
// under the centre of a square: 4 B-3(a/2, b/2, c)).
TEST(HemicubeLayout, TopFaceIsTheCentredSquare) {
    const gpu::HemicubeLayout L = gpu::make_hemicube_layout(256);
    double top = 0;
    for (int y = 0; y < L.faces[0].h; ++y)
        for (int x = 0; x < L.faces[0].w; ++x) top += L.delta_ff[std::size_t(y) * L.width + x];
    const auto b3 = [](double X, double Y) {
        return (X / std::sqrt(1 + X * X) * std::atan(Y / std::sqrt(1 + X * X)) +
                Y / std::sqrt(1 + Y * Y) * std::atan(X / std::sqrt(1 + Y * Y))) /
               (2 * M_PI);
    };
    EXPECT_NEAR(top, 4 * b3(1, 1), 1e-5);
}

// The arccos table as the shader uses it (indexed by the chord between unit vectors): its
// error over all angles, and relative to the angle for small ones (far or small shooters).
TEST(AcosTable, ErrorIsSmallAndRelativelySmallForSmallAngles) {
    const std::vector<float> table = gpu::make_acos_table();
    ASSERT_EQ(table.size(), 2048u);
    double worst = 0, worst_small = 0;
    for (int i = 0; i <= 100000; ++i) {
        const double angle = M_PI * i / 100000;
        const float a[3] = {1, 0, 0};
        const float b[3] = {float(std::cos(angle)), float(std::sin(angle)), 0};
        // The angle of the float vectors, in double.
        const double exact = std::atan2(double(b[1]), double(b[0]));
        const double e = std::abs(double(gpu::table_angle(table, a, b)) - exact);
        worst = std::max(worst, e);
        if (angle > 1e-4 && angle < 0.05) worst_small = std::max(worst_small, e / exact);
    }
    EXPECT_LT(worst, 1e-5) << "absolute error [rad] over [0, pi]";
    EXPECT_LT(worst_small, 1e-5) << "relative error for angles under 3 degrees";
}

// The runs of equal patch IDs (gpu::for_each_pixel_run) are those a plain scan finds: one
// call per maximal run, in order, covering every pixel once, across the blocks of 64 pixels
// its masks work in (runs that end at a block's edge, span blocks, or fill one).
TEST(PixelRuns, MatchAPlainScan) {
    for (std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(63), std::size_t(64),
                          std::size_t(65), std::size_t(200), std::size_t(1000)}) {
        std::vector<float> rgba(4 * n);
        std::uint64_t state = 12345 + n;
        float channels[3] = {0, 0, 1};
        for (std::size_t i = 0; i < n; ++i) {
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            const unsigned r = unsigned(state >> 60); // 0..15
            // Often one channel alone changes (each must be compared); within every third
            // stretch of 100 pixels none does (runs across blocks).
            if (r < 6 && (i / 100) % 3 != 1) channels[r % 3] += 1;
            for (int c = 0; c < 3; ++c) rgba[4 * i + std::size_t(c)] = channels[c];
            rgba[4 * i + 3] = float(i); // alpha differs from pixel to pixel: not compared
        }
        std::vector<std::pair<std::size_t, std::size_t>> expected, found;
        for (std::size_t i = 0; i < n;) {
            std::size_t j = i + 1;
            while (j < n && rgba[4 * j] == rgba[4 * i] && rgba[4 * j + 1] == rgba[4 * i + 1] &&
                   rgba[4 * j + 2] == rgba[4 * i + 2])
                ++j;
            expected.emplace_back(i, j - i);
            i = j;
        }
        gpu::for_each_pixel_run(rgba.data(), n, [&](std::size_t first, std::size_t count) {
            found.emplace_back(first, count);
        });
        EXPECT_EQ(found, expected) << "n " << n;
        if (n >= 200) { // the case is one: some runs cross a block's edge
            bool crosses = false;
            for (const auto& [first, count] : expected)
                crosses |= first / 64 != (first + count - 1) / 64;
            EXPECT_TRUE(crosses) << "n " << n;
        }
    }
}
