// Per-wavelength mode: one small nonlinear least-squares problem per wavelength. Internal to fitting/.
#pragma once

#include "roadbrdf/fitting/losses.h"
#include "roadbrdf/fitting/starting_points.h"

namespace roadbrdf::fitting {

// Fills result.wavelengths (parameters, statistics, covariance; wavelength values not set).
void fit_per_wavelength(const FitData& d, const ParameterLayout& L, const FitOptions& o, FitResult& result);

}  // namespace roadbrdf::fitting
