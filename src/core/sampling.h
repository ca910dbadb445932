// Monte-Carlo sampling shared by the CPU estimators (the sr provider, the final gather at
// points, the path-traced reference): a small reproducible generator, an orthonormal basis,
// cosine-weighted directions and area-uniform points on patches. Internal header.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>

#include "hemirad/patch.h"

namespace hemirad {

/// splitmix64 finaliser: a bijective mix of 64 bits, for seeding from addresses and indices.
constexpr std::uint64_t splitmix64(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

/// A reproducible generator (splitmix64 stream): the same seed gives the same numbers on
/// every platform and compiler, unlike std::uniform_real_distribution.
class Rng {
  public:
    explicit Rng(std::uint64_t seed) : state_(seed) {}
    std::uint64_t next() { return splitmix64(state_ += 0x9e3779b97f4a7c15ull); }
    /// Uniform in [0, 1), from the top 53 bits.
    double uniform() { return double(next() >> 11) * 0x1.0p-53; }

  private:
    std::uint64_t state_;
};

/// Orthonormal basis (t, b) around the unit vector n (Duff et al., "Building an Orthonormal
/// Basis, Revisited", 2017).
inline void orthonormal_basis(const dvec3& n, dvec3& t, dvec3& b) {
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z);
    const double bb = n.x * n.y * a;
    t = dvec3(1.0 + sign * n.x * n.x * a, sign * bb, -sign * n.x);
    b = dvec3(bb, sign + n.y * n.y * a, -n.y);
}

/// Cosine-distributed direction about n (pdf cos(theta)/pi) from (u1, u2) in [0,1)^2: the disk
/// point (sqrt(u1), 2 pi u2) lifted to the hemisphere. t, b: orthonormal_basis(n).
inline dvec3 cosine_direction(const dvec3& n, const dvec3& t, const dvec3& b, double u1,
                              double u2) {
    const double r = std::sqrt(u1);
    const double phi = 2.0 * std::numbers::pi * u2;
    const double z = std::sqrt(std::max(0.0, 1.0 - u1));
    return r * std::cos(phi) * t + r * std::sin(phi) * b + z * n;
}

/// A point uniformly distributed by area on a triangle or quad (a quad as two triangles chosen
/// by area) from (pick, u1, u2) in [0,1)^3.
inline dvec3 area_point(const dvec3* corners, int count, double pick, double u1, double u2) {
    dvec3 a = corners[0], b = corners[1], c = corners[2];
    if (count == 4) {
        const double a1 = glm::length(glm::cross(b - a, c - a));
        const double a2 = glm::length(glm::cross(c - a, corners[3] - a));
        if (pick * (a1 + a2) >= a1) {
            b = c;
            c = corners[3];
        }
    }
    const double r1 = std::sqrt(u1);
    return a + r1 * (1 - u2) * (b - a) + r1 * u2 * (c - a);
}

} // namespace hemirad
