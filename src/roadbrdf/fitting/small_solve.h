// Low-overhead solve of one wavelength's problem: a dense bounded Levenberg-Marquardt over the free
// parameters (Eigen, sizes fixed at compile time up to 6). Internal to fitting/.
#pragma once

#include <ceres/ceres.h>

#include <cstddef>
#include <vector>

#include "roadbrdf/fitting/losses.h"
#include "roadbrdf/fitting/starting_points.h"

namespace roadbrdf::fitting {

// Solves wavelength w over the free parameters `free` (indices of the full vector x, which holds
// the start and receives the solution) with the plain loss (r = m (f - y), no robust function)
// inside the parameters' bounds, by a projected Levenberg-Marquardt with an active set (see the
// definition). Returns false, leaving x unchanged, when the full Ceres solve is needed instead: the
// start cannot be evaluated. On success `summary` holds the initial and final cost, the iteration
// count, the termination message and CONVERGENCE (NO_CONVERGENCE at the iteration limit), and
// `free_jacobian` the residuals' Jacobian over the free parameters at the solution (N x free,
// row-major) for the covariance.
bool solve_small(const FitData& d, const ParameterLayout& L, const FitOptions& o, std::size_t w,
                 const std::vector<std::size_t>& free, std::vector<double>& x, ceres::Solver::Summary& summary,
                 std::vector<double>& free_jacobian);

}  // namespace roadbrdf::fitting
