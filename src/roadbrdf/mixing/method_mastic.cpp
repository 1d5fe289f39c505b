// Method "mastic": the measured mastic plus the coarse aggregate classes, areal mixing (mixing.h).
#include <algorithm>

#include "roadbrdf/core/error.h"
#include "roadbrdf/mixing/method_support.h"
#include "roadbrdf/mixing/method_table.h"

namespace roadbrdf::mixing {

using namespace detail;

void mix_mastic(const MethodCall& call, MixResult& r, std::vector<std::size_t>& members) {
  const MixInputs& inputs = call.inputs;
  if (!inputs.formulation.mastic) {
    throw InputError("method 'mastic' needs the formulation key \"mastic\" (the fit of the measured mastic)");
  }
  const std::vector<double> weights = mastic_weights(inputs, call.settings, members, r.settings, r.notes);
  const std::vector<double> grid = output_grid(inputs, members, call.settings, call.data);
  r.mixture = make_mixture(MixtureKind::kLinear, inputs, members);
  r.model = std::make_shared<const SpectralModel>(
      build_table(r.mixture, inputs, members, grid,
                  [&](std::size_t, double* row) { std::copy(weights.begin(), weights.end(), row); }));
  r.weights = weights;
}

}  // namespace roadbrdf::mixing
