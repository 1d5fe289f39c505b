#include "roadbrdf/albedo/uncertainty.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace roadbrdf::albedo {

std::vector<double> albedo_gradient(const Model& model, const std::vector<double>& params, std::size_t n_sets,
                                    const std::vector<double>& covariance, const SetIntegral& integral) {
  const std::size_t P = model.parameter_count();
  const ModelDescription& d = model.description();
  // gradient[s * P + k] = dA_s / dp_k
  std::vector<double> gradient(n_sets * P, 0.0);
  for (std::size_t k = 0; k < P; ++k) {
    const auto [lower, upper] = d.physical_range(k);
    std::vector<double> up = params, down = params;
    std::vector<double> span(n_sets, 0.0);  // (p + h_up) - (p - h_down) as stored
    bool any = false;
    for (std::size_t s = 0; s < n_sets; ++s) {
      const double variance = covariance[(s * P + k) * P + k];
      const double p = params[s * P + k];
      if (!(variance > 0.0)) continue;  // fixed (0) or undefined (NaN): no derivative needed
      const double h = 0.01 * std::sqrt(variance);
      up[s * P + k] = std::min(p + h, upper);
      down[s * P + k] = std::max(p - h, lower);
      span[s] = up[s * P + k] - down[s * P + k];
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
