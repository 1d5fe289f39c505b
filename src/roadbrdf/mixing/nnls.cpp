#include "roadbrdf/mixing/nnls.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace roadbrdf::mixing {

std::vector<double> nnls_normal(const std::vector<double>& G, const std::vector<double>& h, std::size_t K) {
  std::vector<double> x(K, 0.0);
  std::vector<bool> passive(K, false);
  double scale = 0.0;
  for (std::size_t a = 0; a < K; ++a) scale = std::max(scale, std::fabs(h[a]));
  const double tol = 1e-13 * std::max(scale, 1e-300);
  auto gradient = [&](std::size_t j) {
    double g = h[j];
    for (std::size_t b = 0; b < K; ++b) g -= G[j * K + b] * x[b];
    return g;
  };
  auto solve_passive = [&](std::vector<double>& z) {
    std::vector<std::size_t> idx;
    for (std::size_t a = 0; a < K; ++a) {
      if (passive[a]) idx.push_back(a);
    }
    Eigen::MatrixXd A(idx.size(), idx.size());
    Eigen::VectorXd b(idx.size());
    for (std::size_t i = 0; i < idx.size(); ++i) {
      b(i) = h[idx[i]];
      for (std::size_t j = 0; j < idx.size(); ++j) A(i, j) = G[idx[i] * K + idx[j]];
    }
    const Eigen::VectorXd sol = A.completeOrthogonalDecomposition().solve(b);
    std::fill(z.begin(), z.end(), 0.0);
    for (std::size_t i = 0; i < idx.size(); ++i) z[idx[i]] = sol(i);
  };
  std::vector<double> z(K);
  for (std::size_t outer = 0; outer < 3 * K + 10; ++outer) {
    std::size_t best = K;
    double best_gradient = tol;
    for (std::size_t j = 0; j < K; ++j) {
      if (passive[j]) continue;
      const double g = gradient(j);
      if (g > best_gradient) {
        best_gradient = g;
        best = j;
      }
    }
    if (best == K) break;
    passive[best] = true;
    for (std::size_t inner = 0; inner < 3 * K + 10; ++inner) {
      solve_passive(z);
      bool feasible = true;
      for (std::size_t a = 0; a < K; ++a) feasible = feasible && (!passive[a] || z[a] > 0.0);
      if (feasible) {
        x = z;
        break;
      }
      double alpha = 1.0;
      for (std::size_t a = 0; a < K; ++a) {
        if (passive[a] && z[a] <= 0.0) alpha = std::min(alpha, x[a] / (x[a] - z[a]));
      }
      for (std::size_t a = 0; a < K; ++a) {
        x[a] += alpha * (z[a] - x[a]);
        if (passive[a] && x[a] <= 1e-15 * std::max(1.0, scale)) {
          passive[a] = false;
          x[a] = 0.0;
        }
      }
    }
  }
  return x;
}

}  // namespace roadbrdf::mixing
