// Standard uncertainties of albedos from the covariance of the fitted parameters.
//
// The per-wavelength propagation u^2(A) = g^T Sigma g (GUM, JCGM 100:2008, eq. 10) is
// core/propagation.h (propagate), shared with the r-tables; the gradient g = dA/dp is integrated
// with the albedo itself (albedo/gradient_integrals.h: the integral of the BRDF's analytic
// parameter gradient by the same adaptive rule). The albedo's own parts are the choice of what to
// integrate (GradientPlan) and the broadband (solar-weighted) combination below.
// tests/albedo/uncertainty_test.cpp checks the linearised values against brute-force sampling of the
// parameter distribution, and against central differences of whole integrals.
//
// Wavelengths are treated as independent (per-wavelength fits share no parameter); a joint fit's
// shared parameters correlate wavelengths, which this per-wavelength uncertainty does not carry.
#pragma once

#include <cstddef>
#include <vector>

#include "roadbrdf/albedo/gradient_integrals.h"
#include "roadbrdf/albedo/hemisphere.h"
#include "roadbrdf/core/propagation.h"

namespace roadbrdf::albedo {

// The gradient components the uncertainties need, from the covariance (n_sets x P x P): at a set
// whose covariance is defined (no NaN entry), scale = u(p_k) for every parameter of positive variance
// (a fixed parameter contributes nothing); a set with an undefined covariance (a parameter on its
// bound, a singular fit) has an undefined u whatever its gradient, so nothing of it is integrated and
// its gradient is NaN. The scaled components u(p_k) dA/dp_k are integrated on the nodes the albedo's
// own integral converges on at its tolerance (GradientNodes::value_nodes, gradient_integrals.h): u
// needs ~1 % only, and refining each component to the albedo's tolerance took two to four times the
// geometries. On the bench's 2151-band Hapke fit (bench/report_bench.sh's data) no u differs by more
// than 0.2 % from a reference with every component integrated to 1e-7 (docs/albedo.md, Uncertainty).
struct GradientPlan {
  std::vector<double> scale;  // n_sets x P
  std::vector<bool> undefined;
  std::size_t undefined_sets = 0;
  QuadratureSettings settings;
  GradientNodes nodes = GradientNodes::value_nodes;
  // `gradient` with NaN at the undefined sets.
  std::vector<double> with_nans(std::vector<double> gradient) const;
};
GradientPlan gradient_plan(const std::vector<double>& covariance, std::size_t n_sets, std::size_t parameter_count,
                           double tolerance);

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
