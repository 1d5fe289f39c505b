#include "roadbrdf/core/quadrature.h"

#include <gtest/gtest.h>

#include <cmath>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"

namespace roadbrdf {
namespace {

TEST(GaussLegendre, ExactForPolynomialsUpToDegree2nMinus1) {
  // int_0^2 x^k dx = 2^(k+1)/(k+1).
  for (int n : {1, 2, 5, 10, 32, 64}) {
    const QuadratureRule rule = gauss_legendre(n, 0.0, 2.0);
    for (int k = 0; k <= 2 * n - 1; ++k) {
      double sum = 0.0;
      for (int i = 0; i < n; ++i) sum += rule.weights[i] * std::pow(rule.nodes[i], k);
      const double exact = std::pow(2.0, k + 1) / (k + 1);
      EXPECT_NEAR(sum, exact, 1e-13 * exact) << "n=" << n << " k=" << k;
    }
  }
}

TEST(GaussLegendre, NotExactBeyondItsDegree) {
  // x^(2n) is not integrated exactly by n nodes: the rule has degree 2n - 1, no more.
  const QuadratureRule rule = gauss_legendre(3, -1.0, 1.0);
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) sum += rule.weights[i] * std::pow(rule.nodes[i], 6);
  EXPECT_GT(std::fabs(sum - 2.0 / 7.0), 1e-3);
}

TEST(GaussLegendre, SmoothIntegrandConvergesExponentially) {
  // int_0^{pi/2} cos x dx = 1.
  const QuadratureRule rule = gauss_legendre(12, 0.0, kPi / 2);
  double sum = 0.0;
  for (int i = 0; i < 12; ++i) sum += rule.weights[i] * std::cos(rule.nodes[i]);
  EXPECT_NEAR(sum, 1.0, 1e-15);
}

TEST(GaussLegendre, NodesIncreaseInsideTheInterval) {
  const QuadratureRule rule = gauss_legendre(16, 0.0, 1.0);
  for (int i = 0; i < 16; ++i) {
    EXPECT_GT(rule.nodes[i], 0.0);
    EXPECT_LT(rule.nodes[i], 1.0);
    if (i > 0) {
      EXPECT_GT(rule.nodes[i], rule.nodes[i - 1]);
    }
  }
  EXPECT_THROW(gauss_legendre(0), InputError);
  EXPECT_THROW(gauss_legendre(4, 1.0, 0.0), InputError);
}

}  // namespace
}  // namespace roadbrdf
