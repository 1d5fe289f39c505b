// Standard uncertainties of albedos from the covariance of the fitted parameters (issue 17,
// "uncertainty all the way to albedo").
//
// Linearised propagation (GUM, JCGM 100:2008, eq. 10): u^2(A) = g^T Sigma g with g_k = dA/dp_k, per
// wavelength, Sigma the fit's parameter covariance there. Why linearised rather than sampled: a fit's
// standard errors already rest on the same linearisation (the covariance is (J^T J)^-1 s^2), the
// albedo is a smooth integral of a smooth model, and the linear form costs 2P integrals per sun zenith
// instead of thousands; tests/albedo/uncertainty_test.cpp checks it against brute-force sampling of
// the parameter distribution. g is a central difference of the integral with step h_k = 0.01 u(p_k)
// (one-sided at a physical bound), the integral taken to kDerivativeTolerance, so that its error
// (below 1e-11 / h_k) is negligible against the derivative.
//
// Wavelengths are treated as independent (per-wavelength fits share no parameter); a joint fit's
// shared parameters correlate wavelengths, which this per-wavelength uncertainty does not carry.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "roadbrdf/models/model.h"

namespace roadbrdf::albedo {

constexpr double kDerivativeTolerance = 1e-11;

// One value per parameter set of `n_sets` sets (n_sets x P values, row-major), e.g. a black-sky
// albedo at one sun zenith for every wavelength.
using SetIntegral = std::function<std::vector<double>(const std::vector<double>& params, std::size_t n_sets)>;

// g = dA/dp per set (n_sets x P), by the central differences above; 0 for a parameter whose variance
// is 0 (fixed) or undefined. Each parameter costs two calls of `integral` over all sets at once.
std::vector<double> albedo_gradient(const Model& model, const std::vector<double>& params, std::size_t n_sets,
                                    const std::vector<double>& covariance, const SetIntegral& integral);

// u = sqrt(g^T Sigma g) per set; NaN where Sigma is undefined (NaN) for a parameter that matters.
std::vector<double> propagate(const std::vector<double>& gradient, const std::vector<double>& covariance,
                              std::size_t n_sets, std::size_t parameter_count);

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
