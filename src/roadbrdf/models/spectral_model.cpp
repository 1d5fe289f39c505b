#include "roadbrdf/models/spectral_model.h"

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>

#include "roadbrdf/core/error.h"
#include "roadbrdf/models/registry.h"

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

std::vector<double> SpectralModel::parameters_at(double wavelength_nm) const {
  const std::size_t n = model_->parameter_count();
  if (wavelengths_.empty()) return parameters_;
  const double lo = wavelengths_.front();
  const double hi = wavelengths_.back();
  if (!(wavelength_nm >= lo && wavelength_nm <= hi)) {
    throw InputError("wavelength " + std::to_string(wavelength_nm) + " nm is outside the model's range [" +
                     std::to_string(lo) + ", " + std::to_string(hi) + "] nm (no extrapolation)");
  }
  if (wavelengths_.size() == 1) return parameters_;
  const auto it = std::upper_bound(wavelengths_.begin(), wavelengths_.end(), wavelength_nm);
  std::size_t k = static_cast<std::size_t>(it - wavelengths_.begin());
  if (k == wavelengths_.size()) k = wavelengths_.size() - 1;
  const std::size_t j = k - 1;
  const double t = (wavelength_nm - wavelengths_[j]) / (wavelengths_[k] - wavelengths_[j]);
  std::vector<double> p(n);
  for (std::size_t q = 0; q < n; ++q) {
    p[q] = (1.0 - t) * parameters_[j * n + q] + t * parameters_[k * n + q];
  }
  return p;
}

bool is_fit_file_argument(const std::string& argument) {
  return argument.size() > 5 && argument.compare(argument.size() - 5, 5, ".json") == 0;
}

SpectralModel read_fit_file(const std::string& path, const std::string& model_name) {
  std::ifstream in(path);
  if (!in) throw FileError(path, 0, 0, "cannot open fit file");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw FileError(path, 0, 0, std::string("not valid JSON: ") + e.what());
  }
  try {
    if (j.value("format", "") != "roadbrdf-fit") throw FileError(path, 0, 0, "not a roadbrdf fit file (format key)");
    const std::string wanted = model_name.empty() ? j.at("best").get<std::string>() : model_name;
    for (const auto& fit : j.at("fits")) {
      if (fit.at("model").get<std::string>() != wanted) continue;
      OptionSet options;
      // Keep the options object alive: iterating items() of a temporary would dangle.
      const nlohmann::json fit_options = fit.value("options", nlohmann::json::object());
      for (const auto& [key, value] : fit_options.items()) options[key] = value.get<std::string>();
      std::shared_ptr<const Model> model = make_model(wanted, options);
      const auto wavelengths = fit.at("wavelengths").get<std::vector<double>>();
      const auto& parameters = fit.at("parameters");
      const std::size_t n = model->parameter_count();
      std::vector<double> table(wavelengths.size() * n);
      for (std::size_t q = 0; q < n; ++q) {
        const std::string& name = model->description().parameters[q].name;
        if (!parameters.contains(name)) throw FileError(path, 0, 0, "fit of '" + wanted + "' lacks parameter '" + name + "'");
        const auto values = parameters.at(name).get<std::vector<double>>();
        if (values.size() != wavelengths.size()) {
          throw FileError(path, 0, 0, "parameter '" + name + "' has " + std::to_string(values.size()) +
                                          " values for " + std::to_string(wavelengths.size()) + " wavelengths");
        }
        for (std::size_t w = 0; w < wavelengths.size(); ++w) table[w * n + q] = values[w];
      }
      return SpectralModel(model, wavelengths, table);
    }
    throw FileError(path, 0, 0, "no fit of model '" + wanted + "' in this file");
  } catch (const nlohmann::json::exception& e) {
    throw FileError(path, 0, 0, std::string("malformed fit file: ") + e.what());
  }
}

}  // namespace roadbrdf
