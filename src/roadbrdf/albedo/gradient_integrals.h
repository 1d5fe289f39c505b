// Parameter gradients of the hemispherical integrals (black-sky, white-sky), for the standard
// uncertainties of albedo/uncertainty.h.
//
// d/dp_k of an integral of f(p, w) is the integral of df/dp_k (the integrands are smooth in p and
// the domains do not depend on p), and the models give df/dp analytically or by ceres::Jet
// (Model::evaluate_prepared_with_gradient). The gradient is therefore integrated, not differenced:
// each geometry of the quadrature is prepared once (Model::prepare: the geometry-only work and a
// model's SharedTerms) and evaluated with its gradient once per parameter set, which gives every
// derivative of that set at the cost of one gradient evaluation.
//
// The quadrature is the adaptive rule of hemisphere.h applied to a vector-valued integrand: one
// component per (parameter set s, parameter k) wanted, of value scale_sk df(p_s)/dp_k with scale_sk
// the standard uncertainty u(p_k) at s. The rule refines until every component meets the tolerance,
// so the geometries are chosen for all of them at once and each component's error is that of its
// contribution to the propagated uncertainty: with d_k the component errors and R the parameters'
// correlation matrix, |du| <= sqrt(d^T R d) <= sum_k |d_k| (Cauchy-Schwarz, |R_ab| <= 1): the
// tolerance bounds each parameter's contribution (albedo/uncertainty.h GradientPlan says which is used).
//
// The integrator's geometries do not depend on the parameters, and each is prepared once for all
// sets (black_sky_integrator.h evaluate_sets); the value integrals take the same path.
//
// At grazing sun zeniths black_sky() cross-checks the (mu, dphi) rule with the mirror-polar rule, in
// case a narrow lobe falls between the first nodes (hemisphere.cpp). A lobe's parameter derivatives
// are concentrated where the lobe is: where the value integral's check found the (mu, dphi) rule
// resolving every set (SpectralIntegral::lobes_checked), the gradient's nodes start from the same
// first nodes and see the lobe's derivatives there, so the caller may turn the gradient's check off
// (QuadratureSettings::grazing_check): the mirror-polar rule, graded towards the mirror direction,
// is the costlier of the two there.
//
// Which nodes (GradientNodes): by default the rule refines until every component meets the
// tolerance. The uncertainty needs u to ~1 % only, yet its components, four or more per wavelength
// with derivatives less smooth than the value (Hapke's opposition width h), made the rule choose two to
// four times the value's geometries. With `value_nodes` the value f(p_s) of every set is integrated
// alongside as the first components, and these steer the refinement at the tolerance, while the
// components are held to 3 times it only (QuadratureSettings::steering_sets, follower_factor): the
// gradient is integrated on the nodes the value integral itself converges on (the same decisions, the
// values being equal to rounding), refined further only where a component's estimate is far off (at
// normal incidence on the opposition peak, whose derivative in h the value's nodes resolve to ~1 %
// only). tests/albedo/gradient_integral_test.cpp checks u and every u(p_k) dA/dp_k so integrated
// against the gradient refined to a tolerance 100 times tighter, for every bundled model (within 1 %
// of u).
//
// Why not central differences of whole integrals: a difference quotient with
// step h = 0.01 u(p) needs the two integrals to ~1e-11 for the quotient to be accurate, 2 P such
// integrals per value; the integrated gradient needs one pass at the albedo's own tolerance.
#pragma once

#include <cstddef>
#include <vector>

#include "roadbrdf/albedo/hemisphere.h"
#include "roadbrdf/models/model.h"

namespace roadbrdf::albedo {

// The components of a gradient integral: `scale` holds n_sets x parameter_count() standard
// uncertainties (row-major); a component is integrated where its scale is > 0, and its derivative
// is reported as 0 elsewhere (a fixed parameter, or a set the caller leaves out).
struct GradientIntegral {
  std::vector<double> gradient;  // n_sets x P: dA_s / dp_k
  bool converged = true;
  std::size_t geometries = 0;  // distinct geometries evaluated (each for every component)
  // GradientNodes::value_nodes: the integral of the values themselves, which steered the nodes (value,
  // error estimate and convergence per set; the albedo in the same pass as its gradient). Empty otherwise.
  SpectralIntegral values;
};

// The nodes a gradient integral is evaluated on (see above).
enum class GradientNodes {
  own_tolerance,  // refined until every component meets settings.tolerance
  value_nodes,    // those the value integral with `settings` converges on
};

// Gradient of black_sky() at sun zenith theta_s and azimuth phi_s [rad], or (azimuth_mean) of
// black_sky_azimuth_mean(). `settings.tolerance` bounds each component scale_sk dA_s/dp_k
// (own_tolerance) or the values whose nodes are taken (value_nodes).
GradientIntegral black_sky_gradient(const Model& model, const double* params, std::size_t n_sets,
                                    const std::vector<double>& scale, double theta_s, double phi_s, bool azimuth_mean,
                                    const QuadratureSettings& settings,
                                    GradientNodes nodes = GradientNodes::own_tolerance);

// Gradient of white_sky(), with the same reciprocity decision as white_sky() for the model itself.
GradientIntegral white_sky_gradient(const Model& model, const double* params, std::size_t n_sets,
                                    const std::vector<double>& scale, const QuadratureSettings& settings,
                                    GradientNodes nodes = GradientNodes::own_tolerance);

namespace detail {
// white_sky() with the reciprocity check of the BRDF done by the caller: `reciprocal` says whether
// the inner integrals may run over the lower triangle mu_r < mu_i only (isotropic and reciprocal).
SpectralIntegral white_sky_integral(const Model& model, const double* params, std::size_t n_sets,
                                    const QuadratureSettings& settings, bool reciprocal);
// Whether white_sky() takes the lower-triangle rule for this model and these parameter sets.
bool white_sky_reciprocal(const Model& model, const double* params, std::size_t n_sets);
}  // namespace detail

}  // namespace roadbrdf::albedo
