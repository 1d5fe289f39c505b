// Covariance of the fitted parameters (see fit.h): standard errors and correlations from
// (J^T J)^-1 s^2, s^2 = chi2/(n - k). Per wavelength from a QR of the Jacobian after a rank check; in the
// joint mode by the block (Schur) formula over all wavelengths. Internal to fitting/.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "roadbrdf/fitting/losses.h"
#include "roadbrdf/fitting/starting_points.h"

namespace roadbrdf::fitting {

// No standard errors (NaN) and no correlations, with the reason.
void no_covariance(const ParameterLayout& L, WavelengthFit& out, const std::string& why);

// Per-wavelength covariance at out.parameters (out.chi2, points and free_parameters set).
// `free_jacobian`: the residuals' Jacobian there over the free parameters (N x free, row-major) when
// the solver has it; empty: computed here.
void wavelength_covariance(const FitData& d, const ParameterLayout& L, std::size_t w, WavelengthFit& out,
                           const std::vector<double>& free_jacobian = {});

// Joint-mode covariance of every wavelength (robust function not applied): the shared parameters'
// block is the inverse of the Schur complement of the per-wavelength blocks.
void joint_covariance(const FitData& d, const ParameterLayout& L, std::vector<WavelengthFit>& fits);

}  // namespace roadbrdf::fitting
