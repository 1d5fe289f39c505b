// A model whose parameters depend on wavelength: what a fit produces, and what every command
// that takes "MODEL -p ..." also accepts as FIT.json (albedo, r-tables, mixing, figures).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "roadbrdf/core/coverage.h"
#include "roadbrdf/models/model.h"

namespace roadbrdf {

class SpectralModel {
 public:
  // Parameters independent of wavelength.
  SpectralModel(std::shared_ptr<const Model> model, std::vector<double> parameters);
  // One parameter set per wavelength: parameters is wavelengths.size() x parameter_count(), row-major.
  SpectralModel(std::shared_ptr<const Model> model, std::vector<double> wavelengths, std::vector<double> parameters);

  const Model& model() const { return *model_; }
  std::shared_ptr<const Model> model_ptr() const { return model_; }
  bool is_spectral() const { return !wavelengths_.empty(); }
  const std::vector<double>& wavelengths() const { return wavelengths_; }  // nm; empty if not spectral
  const std::vector<double>& parameter_table() const { return parameters_; }

  // Parameters at a wavelength [nm], linearly interpolated between tabulated wavelengths.
  // Throws InputError outside the tabulated range (no extrapolation).
  std::vector<double> parameters_at(double wavelength_nm) const;
  // The tabulated wavelengths parameters_at() combines and their weights: {(j, 1 - t), (j + 1, t)}
  // (one entry {(0, 1)} for a single tabulated wavelength or none). Throws InputError as parameters_at().
  // Uncertainties need it: a parameter at wavelength j moves every interpolated set with weight w_j.
  std::vector<std::pair<std::size_t, double>> interpolation_weights(double wavelength_nm) const;

  // The angular coverage of the data a fit was fitted to (from the fit file), if known: albedo
  // and r-tables report how much of their result lies outside it.
  const std::optional<AngularCoverage>& coverage() const { return coverage_; }
  void set_coverage(std::optional<AngularCoverage> coverage) { coverage_ = std::move(coverage); }

  // The covariance of the fitted parameters at each tabulated wavelength (from the fit file's
  // standard errors and correlations): wavelengths() x P x P, row-major; NaN where undefined, 0 for
  // fixed parameters; empty when unknown (a model given by its parameters). A mixture's comes from its
  // end-members' fits (mixing/mixture_covariance.h). Albedo and r-table uncertainties are propagated
  // from it (albedo/uncertainty.h, photometry/rtable_uncertainty.h).
  const std::vector<double>& parameter_covariance() const { return covariance_; }
  // Throws InputError unless `covariance` has wavelengths() x P x P values (or is empty).
  void set_parameter_covariance(std::vector<double> covariance);

  // The parameters a joint fit shared across wavelengths (fit --shared; empty otherwise). A shared
  // parameter has one value and one error for every wavelength, so its error is fully correlated
  // between wavelengths, and through it those of the other parameters: the per-wavelength covariance
  // above holds each wavelength's marginal block only, and the propagated uncertainties say so.
  const std::vector<std::string>& shared_parameters() const { return shared_; }
  void set_shared_parameters(std::vector<std::string> names) { shared_ = std::move(names); }

 private:
  std::optional<AngularCoverage> coverage_;
  std::vector<double> covariance_;
  std::vector<std::string> shared_;
  std::shared_ptr<const Model> model_;
  std::vector<double> wavelengths_;
  std::vector<double> parameters_;
};

// The note that goes with uncertainties propagated from a joint fit's covariance (shared parameters).
std::string shared_parameters_note(const SpectralModel& model);

}  // namespace roadbrdf
