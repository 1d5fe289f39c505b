// The parameter covariance of a mixture from its end-members' fits, so that the albedo, Q0, S1 and
// road class of a mixture carry standard uncertainties as those of a fit do.
//
// A mixture's parameter table (mixture_model.h) is a function of its end-members' fitted parameters:
// at each output wavelength l it holds the mixing parameters m(l) and every end-member's parameters
// p_k(l) = sum_j a_lj p_kj, linearly interpolated between that end-member's fit wavelengths j
// (SpectralModel::interpolation_weights). Linearised (GUM, JCGM 100:2008, eq. 13 with independent
// inputs), the table's covariance at l is J Sigma J^T with J the Jacobian of the table row in the
// fitted parameters. The end-members are separate measurements, so their fits are independent
// (no covariance between blocks), and each end-member's fit wavelengths are independent (as for a
// fit, core/propagation.h), which gives per output wavelength:
//   Sigma_pk(l)        = sum_j a_lj^2 Sigma_kj                  (the interpolated set's covariance)
//   weights            variance 0: the formulation's area or cross-section fractions are exact
//   ssa_k (hapke)      w_k = W(A_k(p_k(l))), W the IMSA-H1 inversion of the white-sky albedo A_k
//                      (hapke_imsa.h): var(w_k) = g^T Sigma_pk g, cov(w_k, p_k) = g^T Sigma_pk,
//                      g = dw_k/dp_k by the central difference of core/propagation.h
// Every command that propagates a fit's covariance (albedo/uncertainty.h, photometry/rtable_uncertainty.h)
// then takes the mixture as it takes a fit: u^2(Y) = g_mix^T (J Sigma J^T) g_mix = (J^T g_mix)^T Sigma
// (J^T g_mix), the chain rule through the mixing.
//
// Limits, each said in the result's notes:
//  - an end-member fit interpolated between its wavelengths (grids that differ) correlates the
//    neighbouring output wavelengths, which a per-wavelength covariance does not carry: the
//    "independent" broadband / r-table values are then approximate, the "correlated" ones (sum of
//    the per-wavelength uncertainties) remain an upper bound for any correlation;
//  - methods fitted to the measured mixture (fitted, shadowed) get none: their weights have an
//    uncertainty of their own (from the mixture's data), which is not propagated;
//  - calibrated cross-section factors (hapke, calibration.h) are taken as exact;
//  - an end-member without a covariance (a model given by its parameters, a fit made without
//    standard errors, a non-spectral fit) leaves the mixture without one.
#pragma once

#include "roadbrdf/mixing/mixing.h"

namespace roadbrdf::mixing {

// Sets the parameter covariance of result.model (wavelengths() x P x P, SpectralModel::parameter_covariance)
// from the end-members' fits in `inputs` (found by result.end_member_fits), or leaves it empty with a
// note in result.notes saying why. Hapke: costs 2 white-sky albedos (hapke_imsa.h quadrature) per
// parameter of each end-member at every output wavelength.
void attach_parameter_covariance(const MixInputs& inputs, MixResult& result);

}  // namespace roadbrdf::mixing
