// Gauss-Legendre quadrature rules, shared by every numerical integral of the library.
#pragma once

#include <vector>

namespace roadbrdf {

struct QuadratureRule {
  std::vector<double> nodes;
  std::vector<double> weights;
};

// n-point Gauss-Legendre rule on [a, b]: exact for polynomials of degree <= 2n - 1 (Abramowitz &
// Stegun 25.4.29). Nodes by Newton iteration on the three-term recurrence of P_n, to ~1e-15.
// Nodes are in increasing order. Throws InputError for n < 1 or a >= b.
QuadratureRule gauss_legendre(int n, double a = -1.0, double b = 1.0);

}  // namespace roadbrdf
