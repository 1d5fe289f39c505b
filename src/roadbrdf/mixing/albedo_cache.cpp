#include "roadbrdf/mixing/albedo_cache.h"

#include "roadbrdf/mixing/spectral_evaluation.h"

namespace roadbrdf::mixing {

std::vector<double> AlbedoCache::white_sky(const SpectralModel& model, const std::vector<double>& wavelengths) {
  const std::vector<double> keys = wavelengths.empty() ? std::vector<double>{-1.0} : wavelengths;
  std::vector<double> missing;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (double w : keys) {
      if (!values_.count({&model, w})) missing.push_back(w);
    }
  }
  if (!missing.empty()) {
    const std::vector<double> computed =
        spectral_white_sky_albedo(model, wavelengths.empty() ? std::vector<double>{} : missing);
    std::lock_guard<std::mutex> lock(mutex_);
    for (std::size_t i = 0; i < missing.size(); ++i) values_[{&model, missing[i]}] = computed[i];
  }
  std::vector<double> out;
  out.reserve(keys.size());
  std::lock_guard<std::mutex> lock(mutex_);
  for (double w : keys) out.push_back(values_.at({&model, w}));
  return out;
}

}  // namespace roadbrdf::mixing
