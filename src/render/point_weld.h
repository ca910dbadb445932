// Welding coincident points (the renderer's shared leaf-grid vertices, solution_renderer.cpp).
// Internal header.
//
// Two points weld when they are within `tolerance` of each other (Euclidean) and `may_join`
// accepts the pair; welding is transitive (union-find). Candidates are bucketed in a sorted
// grid of cells 2 x tolerance wide, so that a point's neighbours within the tolerance lie in
// at most 2 cells per axis (one, away from cell walls): O(n log n) for n points, with no
// allocation per cell; the result is the same as comparing every pair.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

namespace hemirad {

/// For every point, the smallest index of the points it is welded to (itself if none).
/// Points with candidate[i] == 0 are never welded. `tolerance` > 0 [scene units].
std::vector<std::uint32_t>
weld_points(const std::vector<glm::dvec3>& points, const std::vector<std::uint8_t>& candidate,
            double tolerance, const std::function<bool(std::uint32_t, std::uint32_t)>& may_join);

} // namespace hemirad
