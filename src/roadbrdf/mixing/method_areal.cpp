// Method "areal": f = sum_k a_k f_k with area fractions from the formulation (mixing.h).
#include <algorithm>

#include "roadbrdf/mixing/method_support.h"
#include "roadbrdf/mixing/method_table.h"

namespace roadbrdf::mixing {

using namespace detail;

void mix_areal(const MethodCall& call, MixResult& r, std::vector<std::size_t>& members) {
  const MixInputs& inputs = call.inputs;
  const std::vector<double> weights = areal_weights(inputs, call.settings, members, r.settings);
  const std::vector<double> grid = output_grid(inputs, members, call.settings, call.data);
  r.mixture = make_mixture(MixtureKind::kLinear, inputs, members);
  r.model = std::make_shared<const SpectralModel>(
      build_table(r.mixture, inputs, members, grid,
                  [&](std::size_t, double* row) { std::copy(weights.begin(), weights.end(), row); }));
  r.weights = weights;
}

}  // namespace roadbrdf::mixing
