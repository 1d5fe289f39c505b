// Starting points of a fit: the parameter layout (fixed, shared, free linear and nonlinear
// parameters), moving a start off its bounds, the bounded linear least-squares solve of the free
// amplitudes, and the Latin hypercube of the multi-start. Internal to fitting/.
#pragma once

#include <cstddef>
#include <vector>

#include "roadbrdf/core/parameters.h"
#include "roadbrdf/fitting/losses.h"

namespace roadbrdf::fitting {

struct ParameterLayout {
  std::vector<ParameterInfo> info;
  std::vector<bool> fixed;
  std::vector<bool> shared;
  std::vector<double> start;
  std::vector<std::size_t> free_linear;     // free (not fixed), linear amplitudes, not shared
  std::vector<std::size_t> free_nonlinear;  // free, not linear (shared or not)
};

// Moves free nonlinear parameters sitting on a bound slightly inside (a start on a bound can keep
// the projected trust-region steps stuck there).
void nudge_off_bounds(const ParameterLayout& L, std::vector<double>& x);

// Bounded linear least squares for the free linear amplitudes of wavelength w, the other
// parameters held: minimise sum q^2 (f0 + G a - y)^2, a in bounds (projected coordinate descent on
// the normal equations). Keeps the result only if it lowers the true objective.
void solve_amplitudes(const FitData& d, const ParameterLayout& L, std::size_t w, std::vector<double>& x);

// Latin hypercube points (count x p, full vectors based on `base`) over the free nonlinear
// parameters, seeded; very wide bounds are sampled up to 10x the start.
std::vector<std::vector<double>> latin_hypercube(const ParameterLayout& L, const std::vector<double>& base, int count,
                                                 unsigned seed);

}  // namespace roadbrdf::fitting
