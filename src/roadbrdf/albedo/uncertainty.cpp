#include "roadbrdf/albedo/uncertainty.h"

#include <cmath>

namespace roadbrdf::albedo {

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
