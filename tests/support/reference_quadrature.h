// Test support: a Gauss-Legendre rule written independently of the library's (core/quadrature.h),
// for reference integrals in tests.
#pragma once

#include <cmath>
#include <vector>

namespace roadbrdf::test {

// n-point Gauss-Legendre nodes x and weights w on [0, 1] (Newton iteration on P_n).
inline void gauss_legendre_01(int n, std::vector<double>& x, std::vector<double>& w) {
  const double pi = 3.14159265358979323846;
  x.assign(n, 0.0);
  w.assign(n, 0.0);
  for (int k = 0; k < n; ++k) {
    double z = std::cos(pi * (k + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int it = 0; it < 100; ++it) {
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
    x[k] = 0.5 * (z + 1.0);
    w[k] = 1.0 / ((1.0 - z * z) * dp * dp);
  }
}

}  // namespace roadbrdf::test
