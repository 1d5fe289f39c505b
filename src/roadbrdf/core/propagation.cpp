#include "roadbrdf/core/propagation.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace roadbrdf {

DerivativeStep derivative_step(double p, double variance, double lower, double upper) {
  if (!(variance > 0.0)) return {p, p};  // fixed (0) or undefined (NaN): no derivative needed
  const double h = kDerivativeStepFraction * std::sqrt(variance);
  return {std::max(p - h, lower), std::min(p + h, upper)};
}

std::vector<double> parameter_gradient(const ModelDescription& model, const std::vector<double>& params,
                                       std::size_t n_sets, const std::vector<double>& covariance,
                                       const SetIntegral& integral) {
  const std::size_t P = model.parameters.size();
  // gradient[s * P + k] = dY_s / dp_k
  std::vector<double> gradient(n_sets * P, 0.0);
  for (std::size_t k = 0; k < P; ++k) {
    const auto [lower, upper] = model.physical_range(k);
    std::vector<double> up = params, down = params;
    std::vector<double> span(n_sets, 0.0);  // (p + h_up) - (p - h_down) as stored
    bool any = false;
    for (std::size_t s = 0; s < n_sets; ++s) {
      const DerivativeStep step = derivative_step(params[s * P + k], covariance[(s * P + k) * P + k], lower, upper);
      up[s * P + k] = step.up;
      down[s * P + k] = step.down;
      span[s] = step.span();
      any = any || span[s] > 0.0;
    }
    if (!any) continue;
    const std::vector<double> a_up = integral(up, n_sets), a_down = integral(down, n_sets);
    for (std::size_t s = 0; s < n_sets; ++s) {
      if (span[s] > 0.0) gradient[s * P + k] = (a_up[s] - a_down[s]) / span[s];
    }
  }
  return gradient;
}

std::vector<double> propagate(const std::vector<double>& gradient, const std::vector<double>& covariance,
                              std::size_t n_sets, std::size_t P) {
  std::vector<double> u(n_sets, 0.0);
  for (std::size_t s = 0; s < n_sets; ++s) {
    double sum = 0.0;
    for (std::size_t a = 0; a < P; ++a) {
      for (std::size_t b = 0; b < P; ++b) {
        const double c = covariance[(s * P + a) * P + b];
        const double ga = gradient[s * P + a], gb = gradient[s * P + b];
        if (c == 0.0) continue;  // a fixed parameter (its derivative was not needed)
        sum += ga * c * gb;      // NaN when the covariance is undefined there
      }
    }
    u[s] = std::isnan(sum) ? std::numeric_limits<double>::quiet_NaN() : std::sqrt(std::max(sum, 0.0));
  }
  return u;
}

}  // namespace roadbrdf
