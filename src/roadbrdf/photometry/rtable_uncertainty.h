// Standard uncertainties of an r-table's summary figures Q0, S1, S2, Qd from the covariance of the
// fitted parameters, and the probabilities of the road classes they imply.
//
// Propagation (GUM, JCGM 100:2008, eq. 10; core/propagation.h): the r-table of a fit is the
// weighted BRDF f = sum_l w_l f(p(l)) over the weighting's wavelengths l (1 nm grid for the
// photometric weighting), p(l) interpolated linearly between the fit's wavelengths j (weights a_lj,
// SpectralModel::interpolation_weights). A figure Y (Q0, S1, S2, Qd) then depends on the fitted
// parameter p_jk through every l next to j, and its gradient is
//   dY/dp_jk  from  dT/dp_jk = sum_l w_l a_lj df/dp_k(p(l)),
// the model's analytic (or Jet) parameter gradient at the table's geometries, evaluated once per set
// l for all parameters. Q0 and Qd are linear in the table, so q0(dT), qd(dT) are their derivatives;
// S1 = T(8,0)/T(0,0) and S2 = Q0/r(0,0) are ratios, whose derivatives follow by the quotient rule.
// Fits at different wavelengths are independent (per-wavelength fits share no parameter), so
//   u^2(Y) = sum_j g_j^T Sigma_j g_j,
// Sigma_j the fit's covariance at wavelength j. A per-wavelength covariance cannot tell whether
// errors are correlated across wavelengths (e.g. a reference-panel calibration common to every band);
// for that case sum_j sqrt(g_j^T Sigma_j g_j) is given as well, the bound for fully correlated errors
// (as the albedo's broadband values do, albedo/uncertainty.h). Cost: one evaluation with gradient
// per set, instead of the 4 P evaluations per set of central differences (P parameters). Fixed
// parameters (variance 0) contribute nothing;
// an undefined covariance (NaN) of a parameter that matters makes the uncertainty undefined (NaN).
//
// Class: with S1 ~ Normal(S1, u(S1)) the probability of the class [lower, upper) is
// Phi((upper - S1)/u) - Phi((lower - S1)/u); the classes of a system tile the S1 axis, so the
// probabilities sum to 1. A normal S1 can be negative, which the first class (no lower limit)
// absorbs.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "roadbrdf/models/spectral_model.h"
#include "roadbrdf/photometry/rtable.h"

namespace roadbrdf::photometry {

// Standard uncertainties (Q0, Qd in sr^-1; S1, S2 1); NaN where undefined.
struct SummaryUncertainty {
  double q0 = 0.0, s1 = 0.0, s2 = 0.0, qd = 0.0;
};

struct RTableUncertainty {
  SummaryUncertainty independent;  // sqrt(sum_j u_j^2): the fit's wavelengths independent (the value)
  SummaryUncertainty correlated;   // sum_j u_j: the bound for errors fully correlated across them
};

// The uncertainties of summarize(table, region) for `table` = compute_rtable(model, weighting,
// alpha_deg), from model.parameter_covariance() (a fit's, or a mixture's, mixing/mixture_covariance.h);
// nullopt when the model has none (a model given by its parameters). Throws InputError as compute_rtable.
std::optional<RTableUncertainty> summary_uncertainty(const SpectralModel& model, const SpectralWeighting& weighting,
                                                     const RTable& table, Q0Region region = Q0Region::standard);

struct ClassProbability {
  std::string name;  // "R3"...
  double probability = 0.0;
};
// Probability of each class of `system` (in increasing S1) for S1 ~ Normal(s1, u_s1); u_s1 = 0 gives 1
// for classify(s1). Throws InputError if s1 is not finite or u_s1 is negative or NaN.
std::vector<ClassProbability> class_probabilities(double s1, double u_s1, ClassSystem system = ClassSystem::R);

// Classes reported with a class: those of probability >= this (1 %).
inline constexpr double kReportedClassProbability = 0.01;

}  // namespace roadbrdf::photometry
