// A model whose parameters depend on wavelength: what a fit produces, and what every command
// that takes "MODEL -p ..." also accepts as FIT.json (albedo, r-tables, mixing, figures).
#pragma once

#include <memory>
#include <string>
#include <vector>

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

 private:
  std::shared_ptr<const Model> model_;
  std::vector<double> wavelengths_;
  std::vector<double> parameters_;
};

// Fit file (JSON, written by `roadbrdf fit`), the parts needed to use it as a model:
// {
//   "format": "roadbrdf-fit", "version": 1,
//   "best": "<model name of the best-ranked fit>",
//   "fits": [ { "model": "oren-nayar+torrance-sparrow",
//               "options": { "name": "value", ... },
//               "wavelengths": [nm, ...],
//               "parameters": { "<parameter name>": [value per wavelength], ... },
//               ...statistics (stderr, rmse, rmse_total, ...) } ]
// }
// Reads the fit named `model_name` (default: "best"). Throws FileError / InputError.
SpectralModel read_fit_file(const std::string& path, const std::string& model_name = "");

// True if `argument` names a fit file rather than a model (ends in ".json").
bool is_fit_file_argument(const std::string& argument);

}  // namespace roadbrdf
