// The bright leaves of a solution: leaf patches whose reflected radiosity is many times the
// scene's mean, the secondary light sources (the ceiling above an uplight, a desk lamp's shade,
// a wall beside a spot). The final gather samples points on them as it samples emitters, by
// multiple importance sampling with its cosine rays (gather.h): a small bright patch seen from
// a point, which only a few of the cosine rays hit, is what makes the indirect light noisy.
// Internal header.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "hemirad/hierarchy.h"

namespace hemirad {

class BrightLeaves {
  public:
    /// A leaf is bright when its reflected radiosity rho*H (summed over RGB) exceeds
    /// `factor` times the area-weighted mean over every leaf of the scene; at most `max_leaves`
    /// of them, the brightest (none for a factor of 0). Each is sampled in proportion to its
    /// reflected power.
    BrightLeaves(const Hierarchy& h, double factor, std::size_t max_leaves);

    bool empty() const { return leaves_.empty(); }
    std::size_t size() const { return leaves_.size(); }

    /// A point drawn on the bright leaves from (pick, u1, u2, u3) in [0,1)^4: the leaf by
    /// power, the point uniformly by area. Its density per unit area, and its polygon.
    struct Sample {
        dvec3 point{0.0};
        std::uint32_t polygon = 0;
        double density = 0; ///< [unit^-2]
    };
    Sample sample(double pick, double u1, double u2, double u3) const;

    /// The density per unit area with which sample() draws parameter point (u, v) of
    /// `polygon` (0 off the bright leaves).
    double density(std::uint32_t polygon, double u, double v) const;

  private:
    struct Leaf {
        std::uint32_t polygon = 0, index = 0;
        double area = 0;
    };
    const Hierarchy* h_;
    std::vector<Leaf> leaves_;
    std::vector<double> cdf_;  ///< cumulative probability of leaves_[0..k]
    std::vector<double> prob_; ///< probability of each leaf
    std::unordered_map<std::uint64_t, std::uint32_t> by_node_; ///< node id -> leaves_ index
};

} // namespace hemirad
