// White-sky albedos of end-member fits, computed once per (fit, wavelength) and shared by every
// mixing method and the comparison of one `mix` run. The quadrature of hapke_imsa.h costs ~14k model
// evaluations per wavelength (a fitted Hapke end-member: ~2 us each), and the same end-member albedos
// are needed by the Hapke inversion and by the albedo summary of every method (mixing.h).
#pragma once

#include <map>
#include <mutex>
#include <utility>
#include <vector>

#include "roadbrdf/models/spectral_model.h"

namespace roadbrdf::mixing {

class AlbedoCache {
 public:
  // spectral_white_sky_albedo(model, wavelengths) (spectral_evaluation.h), from the cache where
  // possible. The model is identified by its address: use it only for models that outlive the cache
  // (the end-members of a MixInputs, which owns its cache).
  std::vector<double> white_sky(const SpectralModel& model, const std::vector<double>& wavelengths);

 private:
  std::mutex mutex_;
  std::map<std::pair<const SpectralModel*, double>, double> values_;  // (model, wavelength or -1) -> albedo
};

}  // namespace roadbrdf::mixing
