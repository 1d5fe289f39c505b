#include "roadbrdf/core/quadrature.h"

#include <cmath>
#include <string>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"

namespace roadbrdf {

QuadratureRule gauss_legendre(int n, double a, double b) {
  if (n < 1) throw InputError("Gauss-Legendre rule needs at least one node, got " + std::to_string(n));
  if (!(a < b)) throw InputError("Gauss-Legendre rule needs a < b");
  QuadratureRule rule;
  rule.nodes.resize(n);
  rule.weights.resize(n);
  const double half = 0.5 * (b - a);
  const double mid = 0.5 * (a + b);
  for (int i = 0; i < n; ++i) {
    // Root i of P_n (descending from near 1), refined by Newton's method.
    double z = std::cos(kPi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1.0;  // P_j(z)
      double p1 = 0.0;  // P_{j-1}(z)
      for (int j = 1; j <= n; ++j) {
        const double p2 = p1;
        p1 = p0;
        p0 = ((2.0 * j - 1.0) * z * p1 - (j - 1.0) * p2) / j;
      }
      dp = n * (z * p0 - p1) / (z * z - 1.0);  // P_n'(z)
      const double step = p0 / dp;
      z -= step;
      if (std::fabs(step) < 1e-16) break;
    }
    // Store in increasing order of the node.
    rule.nodes[n - 1 - i] = mid + half * z;
    rule.weights[n - 1 - i] = half * 2.0 / ((1.0 - z * z) * dp * dp);
  }
  return rule;
}

}  // namespace roadbrdf
