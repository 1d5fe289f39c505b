// The stages of compute_albedo (report.cpp), one concept per stage, in the order they run:
// parameter sets -> hemispherical integrals -> sky (diffuse fraction, blue-sky) -> broadband and
// luminous weighting -> uncertainty. Internal to the albedo module: the public interface is
// report.h; these types only carry one stage's results to the next and to the JSON writer.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "roadbrdf/albedo/hemisphere.h"
#include "roadbrdf/albedo/report.h"
#include "roadbrdf/albedo/solar.h"
#include "roadbrdf/albedo/uncertainty.h"

namespace roadbrdf::albedo::detail {

// The parameter sets integrated at once: one per wavelength of a fit (or of request.wavelengths,
// interpolated), or the single set of a model given by its parameters (not spectral).
struct ParameterSets {
  bool spectral = false;
  std::vector<double> wavelengths;  // [nm], empty when not spectral
  std::vector<double> params;       // n_sets x parameter_count, row-major
  std::size_t n_sets = 0;
};
ParameterSets parameter_sets(const SpectralModel& model, const AlbedoRequest& request);

// How the black-sky integral treats the sun azimuth: anisotropic models are integrated at the given
// azimuth, or averaged over it (AlbedoRequest::azimuth_mean).
struct SunAzimuth {
  bool mean = false;
  double phi_s = 0.0;  // [rad]
};
SpectralIntegral black_sky_at(const Model& model, const std::vector<double>& params, std::size_t n_sets, double theta_s,
                              const SunAzimuth& azimuth, const QuadratureSettings& settings);

// Which standard uncertainties the request gets (albedo/uncertainty.h), decided before the integrals so
// that an integral and its parameter gradient can be integrated in one pass: `gradients` is empty where
// none are computed (no covariance, values only requested, requested wavelengths); `notes` say why, or at
// how many wavelengths the covariance is undefined (albedo_uncertainty adds them to the document's).
struct UncertaintyPlan {
  std::optional<GradientPlan> gradients;
  std::vector<std::string> notes;
};
UncertaintyPlan uncertainty_plan(const SpectralModel& model, const ParameterSets& sets, const AlbedoRequest& request);

// Black-sky per sun zenith and white-sky, each for every parameter set.
struct Hemispherical {
  std::vector<std::vector<double>> black, black_error;  // [zenith][set]
  std::vector<bool> black_lobes_checked;                // [zenith]: SpectralIntegral::lobes_checked
  SpectralIntegral white;
  bool converged = true;
  // With a plan of gradients: those integrated in the same pass as their values (n_sets x P, NaN at
  // the sets whose covariance is undefined), empty where the uncertainty stage integrates them itself
  // (see hemispherical_albedos).
  std::vector<std::vector<double>> black_gradient;  // [zenith]
  std::vector<double> white_gradient;
};
// With `plan` (null: values only), each integral the quadrature of hemisphere.h computes without a
// grazing cross-check (grazing_check_applies) is integrated with its gradient in one pass: the values
// steer the nodes and the gradient follows (gradient_integrals.h, GradientNodes::value_nodes), so the
// model is evaluated once per node, value and gradient together. The values are then those of that
// pass, which may refine beyond the value's own nodes for the gradient's sake: they differ from a
// values-only request by less than their error estimates. Integrals from other `integrals` (a linear
// mixture's) and cross-checked ones keep two passes.
Hemispherical hemispherical_albedos(const Model& model, const ParameterSets& sets,
                                    const std::vector<double>& zeniths_deg, const SunAzimuth& azimuth,
                                    const QuadratureSettings& settings, const HemisphericalIntegrals& integrals,
                                    const GradientPlan* plan, ProgressCounter& progress);

// The sky: diffuse fraction D per sun zenith and set (a constant, a table or SPECTRL2), SPECTRL2's
// spectra per zenith, and blue-sky = (1 - D) black + D white (report eq. 2.19). All empty without a
// diffuse fraction or atmosphere.
struct Sky {
  std::optional<Spectrl2Input> atmosphere;
  std::vector<Spectrl2Output> spectra;                // [zenith], with an atmosphere
  std::vector<std::vector<double>> diffuse;           // [zenith][set]
  std::vector<std::vector<double>> blue, blue_error;  // [zenith][set]
};
Sky sky_conditions(const ParameterSets& sets, const AlbedoRequest& request, const Hemispherical& albedos);

// Solar-weighted (broadband) values; `formed` false for a single band (nothing to weigh).
struct Broadband {
  bool formed = true;
  std::string weighting;
  std::vector<double> black, black_error, blue, blue_error;  // [zenith]
  double white = 0.0, white_error = 0.0, outside = 0.0;
  // The weighted means with their coefficients (WeightedValue::first/second), for the uncertainties;
  // empty when not spectral.
  std::vector<WeightedValue> black_means, blue_means;
  WeightedValue white_mean;
};
Broadband broadband_albedos(const ParameterSets& sets, const AlbedoRequest& request, const Hemispherical& albedos,
                            const Sky& sky, std::vector<std::string>& notes);

// The luminous (V(lambda) x illuminant weighted) values, JSON null without an illuminant or when the
// wavelengths cannot form them (with a note).
nlohmann::json luminous_albedos(const ParameterSets& sets, const AlbedoRequest& request, const Hemispherical& albedos,
                                std::vector<std::string>& notes);

// Standard uncertainties from the fit's parameter covariance (albedo/uncertainty.h), JSON "uncertainty";
// null where `plan` has no gradients (its notes say why). The gradients `albedos` does not hold are
// integrated here; `albedos` says at which zeniths the values passed the grazing cross-check (their
// gradients then skip it, gradient_integrals.h).
nlohmann::json albedo_uncertainty(const SpectralModel& model, const ParameterSets& sets, const AlbedoRequest& request,
                                  const UncertaintyPlan& plan, const SunAzimuth& azimuth, const Hemispherical& albedos,
                                  const Sky& sky, const Broadband& broadband, ProgressCounter& progress,
                                  std::vector<std::string>& notes);

}  // namespace roadbrdf::albedo::detail
