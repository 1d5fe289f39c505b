#include "roadbrdf/models/microfacet.h"

#include <map>
#include <memory>
#include <mutex>

namespace roadbrdf {
namespace microfacet {

namespace {

// Nodes of the n-point Gauss-Legendre rule on [-1, 1] by Newton iteration on P_n (standard
// three-term recurrence; Abramowitz & Stegun 25.4.29), mapped to [0, 1].
QuadratureRule compute_gauss_legendre_01(int n) {
  QuadratureRule rule;
  rule.x.resize(static_cast<std::size_t>(n));
  rule.w.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double z = std::cos(kPi * (i + 0.75) / (n + 0.5));
    double dp = 0.0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1.0, p1 = 0.0;
      for (int j = 1; j <= n; ++j) {
        const double p2 = p1;
        p1 = p0;
        p0 = ((2.0 * j - 1.0) * z * p1 - (j - 1.0) * p2) / j;
      }
      dp = n * (z * p0 - p1) / (z * z - 1.0);
      const double dz = p0 / dp;
      z -= dz;
      if (std::fabs(dz) < 1e-16) break;
    }
    // recompute derivative at the converged node
    {
      double p0 = 1.0, p1 = 0.0;
      for (int j = 1; j <= n; ++j) {
        const double p2 = p1;
        p1 = p0;
        p0 = ((2.0 * j - 1.0) * z * p1 - (j - 1.0) * p2) / j;
      }
      dp = n * (z * p0 - p1) / (z * z - 1.0);
    }
    const double w = 2.0 / ((1.0 - z * z) * dp * dp);
    const auto lo = static_cast<std::size_t>(i);
    const auto hi = static_cast<std::size_t>(n - 1 - i);
    rule.x[lo] = 0.5 * (1.0 - z);
    rule.x[hi] = 0.5 * (1.0 + z);
    rule.w[lo] = 0.5 * w;
    rule.w[hi] = 0.5 * w;
  }
  return rule;
}

}  // namespace

const QuadratureRule& gauss_legendre_01(int n) {
  static std::mutex mutex;
  static std::map<int, std::unique_ptr<QuadratureRule>> cache;
  // Fast path for the rule used in inner loops.
  static const QuadratureRule rule64 = compute_gauss_legendre_01(64);
  if (n == 64) return rule64;
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = cache[n];
  if (!slot) slot = std::make_unique<QuadratureRule>(compute_gauss_legendre_01(n));
  return *slot;
}

}  // namespace microfacet
}  // namespace roadbrdf
