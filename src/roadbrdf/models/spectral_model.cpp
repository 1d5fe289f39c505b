#include "roadbrdf/models/spectral_model.h"

#include <algorithm>
#include <optional>
#include <string>

#include "roadbrdf/core/error.h"
#include "roadbrdf/spectra/interpolation.h"

namespace roadbrdf {

SpectralModel::SpectralModel(std::shared_ptr<const Model> model, std::vector<double> parameters)
    : model_(std::move(model)), parameters_(std::move(parameters)) {
  if (parameters_.size() != model_->parameter_count()) {
    throw InputError("model '" + model_->name() + "' needs " + std::to_string(model_->parameter_count()) +
                     " parameters, got " + std::to_string(parameters_.size()));
  }
}

SpectralModel::SpectralModel(std::shared_ptr<const Model> model, std::vector<double> wavelengths,
                             std::vector<double> parameters)
    : model_(std::move(model)), wavelengths_(std::move(wavelengths)), parameters_(std::move(parameters)) {
  if (wavelengths_.empty()) throw InputError("spectral model without wavelengths");
  if (parameters_.size() != wavelengths_.size() * model_->parameter_count()) {
    throw InputError("parameter table of model '" + model_->name() + "' does not match its wavelengths");
  }
  for (std::size_t k = 1; k < wavelengths_.size(); ++k) {
    if (!(wavelengths_[k] > wavelengths_[k - 1])) throw InputError("wavelengths must be strictly increasing");
  }
}

std::vector<std::pair<std::size_t, double>> SpectralModel::interpolation_weights(double wavelength_nm) const {
  if (wavelengths_.empty()) return {{0, 1.0}};  // one parameter set for every wavelength
  const std::optional<spectra::LinearStencil> s = spectra::linear_stencil(
      wavelengths_, wavelength_nm, spectra::Extrapolation::kRefuse, "the spectral model's wavelengths");
  if (s->upper == s->lower) return {{0, 1.0}};
  return {{s->lower, 1.0 - s->t}, {s->upper, s->t}};
}

std::vector<double> SpectralModel::parameters_at(double wavelength_nm) const {
  const std::size_t n = model_->parameter_count();
  if (wavelengths_.empty()) return parameters_;
  const auto weights = interpolation_weights(wavelength_nm);
  if (weights.size() == 1) return parameters_;
  const auto [j, a] = weights[0];
  const auto [k, t] = weights[1];
  std::vector<double> p(n);
  for (std::size_t q = 0; q < n; ++q) {
    p[q] = a * parameters_[j * n + q] + t * parameters_[k * n + q];
  }
  return p;
}

void SpectralModel::set_parameter_covariance(std::vector<double> covariance) {
  const std::size_t p = model_->parameter_count();
  if (!covariance.empty() && covariance.size() != wavelengths_.size() * p * p) {
    throw InputError("parameter covariance: " + std::to_string(covariance.size()) + " values, expected " +
                     std::to_string(wavelengths_.size() * p * p) + " (wavelengths x parameters^2)");
  }
  covariance_ = std::move(covariance);
}

std::string shared_parameters_note(const SpectralModel& model) {
  std::string names;
  for (const std::string& n : model.shared_parameters()) names += (names.empty() ? "" : ", ") + n;
  return "joint fit: the errors of the parameters shared across wavelengths (" + names +
         ") are fully correlated between wavelengths, which the per-wavelength covariance does not carry: "
         "the uncertainties at each wavelength hold, those of values combined over wavelengths understate "
         "the shared parameters' part as 'independent' and bound it as 'correlated'";
}

}  // namespace roadbrdf
