// White-sky albedo of a mixing result from its end-members' albedos (mixing.h mixture_white_sky_albedo).
#include <algorithm>

#include "roadbrdf/mixing/mixing.h"
#include "roadbrdf/models/hapke_imsa.h"

namespace roadbrdf::mixing {

std::vector<double> mixture_white_sky_albedo(const MixInputs& inputs, const MixResult& result,
                                             const std::vector<double>& wavelengths) {
  const MixtureModel& mixture = *result.mixture;
  const SpectralModel& model = *result.model;
  const std::size_t K = mixture.component_count();
  if (mixture.kind() == MixtureKind::kShadowed || result.end_members.size() != K) {
    return spectral_white_sky_albedo(model, wavelengths);
  }
  // The end-member of each mixture component (by name).
  std::vector<const SpectralModel*> members(K, nullptr);
  for (std::size_t k = 0; k < K; ++k) {
    for (const EndMember& e : inputs.end_members) {
      if (e.name == result.end_members[k]) members[k] = e.model.get();
    }
    if (!members[k]) return spectral_white_sky_albedo(model, wavelengths);
  }
  const std::size_t sets = wavelengths.empty() ? 1 : wavelengths.size();
  std::vector<std::vector<double>> rows(sets);
  for (std::size_t q = 0; q < sets; ++q) {
    rows[q] = wavelengths.empty() ? model.parameter_table() : model.parameters_at(wavelengths[q]);
    for (std::size_t k = 0; k < K; ++k) {
      const std::vector<double> own =
          wavelengths.empty() ? members[k]->parameter_table() : members[k]->parameters_at(wavelengths[q]);
      const std::size_t offset = mixture.component_offset(k);
      if (own.size() != mixture.component(k).parameter_count() ||
          !std::equal(own.begin(), own.end(), rows[q].begin() + offset)) {
        return spectral_white_sky_albedo(model, wavelengths);
      }
    }
  }
  std::vector<std::vector<double>> member_albedo(K);
  for (std::size_t k = 0; k < K; ++k) member_albedo[k] = inputs.albedo_cache->white_sky(*members[k], wavelengths);
  const HemisphereRule& rule = white_sky_rule();
  const std::vector<double> zero(K, 0.0);
  std::vector<double> albedo(sets, 0.0);
  for (std::size_t q = 0; q < sets; ++q) {
    const double* p = rows[q].data();
    double total = 0.0;
    for (std::size_t k = 0; k < K; ++k) total += p[k];
    for (std::size_t k = 0; k < K; ++k) {
      const double e = mixture.kind() == MixtureKind::kHapke ? p[k] / total : p[k];
      albedo[q] += e * member_albedo[k][q];
    }
    if (mixture.kind() == MixtureKind::kHapke) {
      for (std::size_t n = 0; n < rule.geometries.size(); ++n) {
        albedo[q] += rule.weights[n] * mixture.combine(p, rule.geometries[n], zero.data(), nullptr);
      }
    }
  }
  return albedo;
}

}  // namespace roadbrdf::mixing
