// Goodness-of-fit statistics of one wavelength (see fit.h) and the parameters ending on a bound.
// Internal to fitting/.
#pragma once

#include <cstddef>

#include "roadbrdf/fitting/losses.h"
#include "roadbrdf/fitting/starting_points.h"

namespace roadbrdf::fitting {

// points, rmse, relative_rmse, max_relative_error, r_squared, chi2, aic, bic of wavelength w at
// out.parameters (out.free_parameters must be set).
void fill_statistics(const FitData& d, std::size_t w, WavelengthFit& out);

// out.at_bounds: "name=lower" / "name=upper" for the free parameters within 1e-7 (relative to the
// bound interval, capped at 1e3) of a bound.
void flag_bounds(const ParameterLayout& L, WavelengthFit& out);

}  // namespace roadbrdf::fitting
