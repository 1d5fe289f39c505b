#include "roadbrdf/albedo/uncertainty.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace roadbrdf::albedo {

GradientPlan gradient_plan(const std::vector<double>& covariance, std::size_t n_sets, std::size_t P, double tolerance) {
  GradientPlan plan;
  plan.scale.assign(n_sets * P, 0.0);
  plan.undefined.assign(n_sets, false);
  for (std::size_t s = 0; s < n_sets; ++s) {
    const auto block = covariance.begin() + static_cast<std::ptrdiff_t>(s * P * P);
    if (std::any_of(block, block + static_cast<std::ptrdiff_t>(P * P), [](double c) { return std::isnan(c); })) {
      plan.undefined[s] = true;
      ++plan.undefined_sets;
      continue;
    }
    for (std::size_t k = 0; k < P; ++k) {
      const double variance = covariance[(s * P + k) * P + k];
      if (variance > 0.0) plan.scale[s * P + k] = std::sqrt(variance);
    }
  }
  plan.settings.tolerance = tolerance;
  return plan;
}

std::vector<double> GradientPlan::with_nans(std::vector<double> gradient) const {
  const std::size_t P = undefined.empty() ? 0 : gradient.size() / undefined.size();
  for (std::size_t s = 0; s < undefined.size(); ++s) {
    if (!undefined[s]) continue;
    std::fill(gradient.begin() + static_cast<std::ptrdiff_t>(s * P),
              gradient.begin() + static_cast<std::ptrdiff_t>((s + 1) * P), std::numeric_limits<double>::quiet_NaN());
  }
  return gradient;
}

BroadbandUncertainty broadband_uncertainty(const std::vector<const std::vector<double>*>& gradients,
                                           const std::vector<const std::vector<double>*>& coefficients,
                                           const std::vector<double>& covariance, std::size_t n_sets, std::size_t P) {
  std::vector<double> h(n_sets * P, 0.0);
  for (std::size_t t = 0; t < gradients.size(); ++t) {
    for (std::size_t s = 0; s < n_sets; ++s) {
      for (std::size_t k = 0; k < P; ++k) h[s * P + k] += (*coefficients[t])[s] * (*gradients[t])[s * P + k];
    }
  }
  BroadbandUncertainty b;
  double sum_squares = 0.0;
  for (double u : propagate(h, covariance, n_sets, P)) {
    sum_squares += u * u;  // NaN propagates
    b.correlated += u;
  }
  b.independent = std::sqrt(sum_squares);
  return b;
}

}  // namespace roadbrdf::albedo
