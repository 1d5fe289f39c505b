// Propagation of the fitted parameters' covariance to a derived quantity (an albedo, Q0), shared by
// albedo (albedo/uncertainty.h) and r-tables (photometry/rtable_uncertainty.h).
//
// Linearised propagation (GUM, JCGM 100:2008, eq. 10): u^2(Y) = g^T Sigma g with g_k = dY/dp_k, per
// parameter set (one per wavelength of a fit), Sigma the fit's parameter covariance there. Why
// linearised rather than sampled: a fit's standard errors already rest on the same linearisation
// (the covariance is (J^T J)^-1 s^2), the derived quantities are smooth functionals of a smooth
// model, and the linear form costs 2 evaluations per parameter instead of thousands; the albedo and
// r-table tests check it against brute-force sampling of the parameter distribution.
//
// The albedo integrates g with the albedo itself (albedo/gradient_integrals.h) and uses propagate()
// only, and so do r-tables (photometry/rtable_uncertainty.h: the model's gradient at the table's
// geometries; derivative_step only decides which parameters propagate); the step rule below serves
// a quantity without a gradient (a mixture's single-scattering albedo inversion, parameter_gradient).
//
// Step rule: g is a central difference with step h_k = 0.01 u(p_k), one-sided where p_k +- h_k
// would leave the parameter's physical range (ModelDescription::physical_range); a parameter whose
// variance is 0 (fixed) or undefined (NaN) gets no step and contributes nothing (0) resp. NaN.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "roadbrdf/core/parameters.h"

namespace roadbrdf {

// h_k = kDerivativeStepFraction u(p_k).
inline constexpr double kDerivativeStepFraction = 0.01;

// The two points of a difference quotient for one parameter: (f(up) - f(down)) / span().
struct DerivativeStep {
  double down = 0.0, up = 0.0;
  double span() const { return up - down; }
};
// The step for a parameter of value p with `variance` inside [lower, upper]: span() 0 when the
// variance is not positive (fixed or undefined) or the range leaves no room.
DerivativeStep derivative_step(double p, double variance, double lower, double upper);

// One value per parameter set of `n_sets` sets (n_sets x P values, row-major), e.g. a black-sky
// albedo at one sun zenith for every wavelength. The sets must be independent: a set's value
// depends on that set's parameters only.
using SetIntegral = std::function<std::vector<double>(const std::vector<double>& params, std::size_t n_sets)>;

// g = dY/dp per set (n_sets x P), by the step rule above; 0 for a parameter whose variance is 0
// (fixed) or undefined. Each parameter costs two calls of `integral` over all sets at once.
// `covariance` is n_sets x P x P (row-major), `model` gives P and the physical ranges.
std::vector<double> parameter_gradient(const ModelDescription& model, const std::vector<double>& params,
                                       std::size_t n_sets, const std::vector<double>& covariance,
                                       const SetIntegral& integral);

// u = sqrt(g^T Sigma g) per set; NaN where Sigma is undefined (NaN) for a parameter that matters
// (a parameter with zero covariance entries is skipped, whatever its derivative).
std::vector<double> propagate(const std::vector<double>& gradient, const std::vector<double>& covariance,
                              std::size_t n_sets, std::size_t parameter_count);

}  // namespace roadbrdf
