// The matrix (gathering) radiosity solver for small scenes (paper 003): the full form-factor
// matrix at leaf level from a provider, then Gauss-Seidel on B = E + rho F B to a residual
// tolerance. It is the reference the progressive solver is tested against.
#pragma once

#include <vector>

#include "hemirad/form_factors.h"
#include "hemirad/hierarchy.h"
#include "hemirad/scene.h"

namespace hemirad {

struct MatrixSolution {
    std::vector<PatchAddress> leaves; ///< every leaf patch, polygon by polygon
    std::vector<dvec3> B;             ///< radiosity per leaf [W unit^-2]
    std::vector<dvec3> H;             ///< irradiance per leaf [W unit^-2]
    int iterations = 0;
    double residual = 0; ///< max |B - E - rho F B| / max B after the last sweep
};

/// Builds F(j -> i) between all leaves with `provider` (linked at leaves) and solves.
/// Memory and time grow with the square of the leaf count: meant for up to a few thousand.
MatrixSolution solve_matrix(const Scene& scene, const Discretisation& disc,
                            FormFactorProvider& provider, double tolerance = 1e-10,
                            int max_iterations = 10000);

} // namespace hemirad
