// Method "fitted": f = sum_k a_k f_k with weights fitted to the measured mixture by non-negative least
// squares, one set for all wavelengths or one per wavelength (mixing.h).
#include <algorithm>

#include "roadbrdf/mixing/method_support.h"
#include "roadbrdf/mixing/method_table.h"

namespace roadbrdf::mixing {

using namespace detail;

void mix_fitted(const MethodCall& call, MixResult& r, std::vector<std::size_t>& members) {
  const MixInputs& inputs = call.inputs;
  const MixSettings& settings = call.settings;
  std::map<std::string, double> info;
  r.formulation_weights = areal_weights(inputs, settings, members, info);
  std::vector<double> grid;
  const LinearSystem sys = fitted_system(call, members, grid);
  const std::size_t K = members.size();
  std::vector<std::vector<double>> table;
  if (settings.per_wavelength) {
    for (std::size_t m = 0; m < sys.M; ++m) table.push_back(solve_weights(sys, m, m + 1, settings.sum_to_one));
  } else {
    table.assign(sys.M, solve_weights(sys, 0, sys.M, settings.sum_to_one));
  }
  r.weights.assign(K, 0.0);
  for (const auto& row : table) {
    for (std::size_t k = 0; k < K; ++k) r.weights[k] += row[k] / table.size();
  }
  r.mixture = make_mixture(MixtureKind::kLinear, inputs, members);
  r.model = std::make_shared<const SpectralModel>(
      build_table(r.mixture, inputs, members, grid,
                  [&](std::size_t q, double* row) { std::copy(table[q].begin(), table[q].end(), row); }));
  r.settings["per_wavelength"] = settings.per_wavelength ? 1.0 : 0.0;
  r.settings["sigma_weighted"] = sys.sigma_weighted ? 1.0 : 0.0;
  r.settings["sum_to_one"] = settings.sum_to_one ? 1.0 : 0.0;
  weight_distance(r);
}

}  // namespace roadbrdf::mixing
