// Joint spectral mode: one problem holding the shared parameters once and one block of the other
// parameters per wavelength. Internal to fitting/.
#pragma once

#include "roadbrdf/fitting/losses.h"
#include "roadbrdf/fitting/starting_points.h"

namespace roadbrdf::fitting {

// Fills result.wavelengths (wavelength values not set), joint_iterations and joint_status.
void fit_joint(const FitData& d, const ParameterLayout& L, const FitOptions& o, FitResult& result);

}  // namespace roadbrdf::fitting
