// Standard uncertainties of albedos from the covariance of the fitted parameters.
//
// The per-wavelength propagation u^2(A) = g^T Sigma g (GUM, JCGM 100:2008, eq. 10) and its step rule
// are core/propagation.h (parameter_gradient, propagate), shared with the r-tables; the albedo's own
// part is the integral tolerance of the derivatives and the broadband (solar-weighted) combination
// below. tests/albedo/uncertainty_test.cpp checks the linearised values against brute-force sampling
// of the parameter distribution. The integral is taken to kDerivativeTolerance so that its error
// (below 1e-11 / h_k, h_k = 0.01 u(p_k)) is negligible against the derivative.
//
// Wavelengths are treated as independent (per-wavelength fits share no parameter); a joint fit's
// shared parameters correlate wavelengths, which this per-wavelength uncertainty does not carry.
#pragma once

#include <cstddef>
#include <vector>

#include "roadbrdf/core/propagation.h"

namespace roadbrdf::albedo {

constexpr double kDerivativeTolerance = 1e-11;

// A broadband (solar-weighted) value B = sum_t sum_k c_t[k] A_t[k] of per-wavelength albedos A_t
// (one term, or SPECTRL2's blue-sky: direct-weighted black-sky plus diffuse-weighted white-sky), c_t
// the weighted mean's coefficients (WeightedValue::first/second), g_t the gradients of A_t (n_sets x
// P). Per wavelength h_k = sum_t c_t[k] g_t[k] and u_k = sqrt(h_k^T Sigma_k h_k). `independent` is
// sqrt(sum u_k^2): per-wavelength fits of separate measurements are independent. `correlated` is
// sum u_k, the bound for errors fully correlated across wavelengths (e.g. a reference-panel
// calibration common to every band), which a per-wavelength covariance cannot tell apart. NaN when a
// contributing u_k is undefined.
struct BroadbandUncertainty {
  double independent = 0.0;
  double correlated = 0.0;
};
BroadbandUncertainty broadband_uncertainty(const std::vector<const std::vector<double>*>& gradients,
                                           const std::vector<const std::vector<double>*>& coefficients,
                                           const std::vector<double>& covariance, std::size_t n_sets,
                                           std::size_t parameter_count);

}  // namespace roadbrdf::albedo
