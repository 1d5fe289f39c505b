#include "roadbrdf/mixing/spectral_evaluation.h"

#include <algorithm>

#include "roadbrdf/models/hapke_imsa.h"

namespace roadbrdf::mixing {

std::vector<double> evaluate_spectral(const SpectralModel& model, const std::vector<Geometry>& geometries,
                                      const std::vector<double>& wavelengths) {
  const std::size_t n = model.model().parameter_count();
  const std::size_t sets = wavelengths.empty() ? 1 : wavelengths.size();
  std::vector<double> params(sets * n);
  for (std::size_t s = 0; s < sets; ++s) {
    const std::vector<double> p = wavelengths.empty() ? model.parameter_table() : model.parameters_at(wavelengths[s]);
    std::copy(p.begin(), p.begin() + n, params.begin() + s * n);
  }
  std::vector<double> out(geometries.size() * sets);
  model.model().evaluate_batch(geometries.data(), geometries.size(), params.data(), sets, out.data());
  return out;
}

std::vector<double> spectral_white_sky_albedo(const SpectralModel& model, const std::vector<double>& wavelengths) {
  const std::size_t n = model.model().parameter_count();
  const std::size_t sets = wavelengths.empty() ? 1 : wavelengths.size();
  std::vector<double> params(sets * n);
  for (std::size_t s = 0; s < sets; ++s) {
    const std::vector<double> p = wavelengths.empty() ? model.parameter_table() : model.parameters_at(wavelengths[s]);
    std::copy(p.begin(), p.begin() + n, params.begin() + s * n);
  }
  return white_sky_albedo(model.model(), params.data(), sets);
}

}  // namespace roadbrdf::mixing
