// Ambartsumian-Chandrasekhar H-function for isotropic scattering, H(x, w), and Hapke's closed-form
// approximations of it. Internal helper of the "hapke" model (models/hapke.h); templated on the
// scalar so that the fitter can differentiate with respect to the single-scattering albedo w.
//
// H solves H(x) = 1 + (w/2) x H(x) int_0^1 H(x')/(x + x') dx'   (Chandrasekhar, "Radiative Transfer",
// 1950/1960, ch. V; x = cosine of the incidence or emergence angle, 0 <= x <= 1, 0 <= w <= 1).
//
// * hapke1981: H1(x) = (1 + 2x) / (1 + 2x gamma), gamma = sqrt(1 - w)
//   (Hapke, JGR 86(B4):3039-3054, 1981; report section 3.8). Relative error up to ~4% (w -> 1).
// * hapke2002: 1/H2(x) = 1 - w x [r0 + (1 - 2 r0 x)/2 ln((1 + x)/x)], r0 = (1 - gamma)/(1 + gamma)
//   (Hapke, Icarus 157:523-534, 2002, eq. 13). Relative error below 1%. H2(0) = 1 (limit x -> 0).
// * exact: the closed-form integral representation of H for isotropic scattering (characteristic
//   function Psi = w/2; Chandrasekhar 1960, ch. V; evaluated with Gauss-Legendre quadrature as in
//   Kawabata & Limaye, arXiv:1010.4839):
//       ln H(x) = -(x/pi) int_0^inf ln(1 - w arctan(k)/k) / (1 + x^2 k^2) dk.
//   Substituting k = tan(psi)/x gives a finite interval and no weight function:
//       ln H(x) = -(1/pi) int_0^{pi/2} ln(1 - w a(psi)) dpsi,   a = arctan(t)/t,  t = tan(psi)/x.
//   The integrand is analytic on (0, pi/2]; its only difficulty is at psi -> 0, where
//   1 - w a ~ (1 - w) + w t^2/3: a near-singularity of width ~ x sqrt(1 - w) (a log singularity at
//   w = 1), and the branch points of arctan(t)/t at psi = +-i artanh(x). The interval is therefore split
//   into panels graded geometrically towards 0 (breakpoints (pi/2) 2^-k, Gauss-Legendre on each),
//   down to a panel width below that scale; the last panel [0, b] then holds a function analytic in a
//   neighbourhood of several widths (or, at w = 1 exactly, an integrable log singularity whose
//   whole contribution is O(b ln b), b < 1e-8 x). Measured accuracy against a much finer rule
//   (ratio 0.8 panels, 30 nodes each): relative error < 1e-15 for 0 <= w <= 1 - 1e-5 and < 2e-11 for
//   w -> 1 (tests/models/hapke_test.cpp checks a table, an independent Nystrom solution and the moment
//   identities). About 40-120 logarithms per call for w <= 0.99, ~300 at w = 1. The node choice
//   depends on the value of w only, so derivatives are those of the quadrature, accurate to the same
//   order.
//   w -> 1: H stays finite (H(1, 1) = 2.9078), but dH/dw ~ 1/sqrt(1 - w) diverges; at w = 1 the
//   returned derivative is that of the finite quadrature (large, finite), and for the closed forms
//   gamma = sqrt(1 - w) has derivative 0 at w = 1 by convention (safe_sqrt), not -infinity.
// * The model does not call h_exact directly: it uses hapke::h_tabulated (models/hapke_h_table.h), a
//   process-wide table of piecewise tensor Chebyshev interpolants of h_exact in log2(x) (octaves, 12
//   nodes each, x down to 2^-40) and gamma = sqrt(1 - w) (panels of width 1/8, 10 nodes each), built
//   lazily per block (~0.5 ms each, ~150 ms for all 320). In these variables H is analytic around
//   each panel (the x ln x term at x -> 0 and the sqrt(1 - w) branch point at w = 1 are absorbed by
//   the change of variables). Measured relative difference to h_exact on a dense grid not aligned with
//   the nodes (tests/models/hapke_h_table_test.cpp, ~725 x 200 points, x in [1e-14, 1], both sides of
//   every panel boundary): <= 2.6e-14 for 0 <= w <= 1 - 1e-5; <= 1.1e-11 for 1 - 1e-5 < w <= 1, which
//   is the quadrature's own error there (the interpolant is smoother than the quadrature's
//   w-dependent node choice). dH/dw is the exact derivative of the interpolant, within ~1e-9
//   relative of the quadrature's derivative; 0 at w = 1 by convention, as for the closed forms.
//   Cost: ~35 ns per H (value) and ~45 ns (with dH/dw) against ~0.8 us for h_exact.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "roadbrdf/core/math.h"
#include "roadbrdf/core/quadrature.h"

namespace roadbrdf::hapke {

// gamma = sqrt(1 - w) (Hapke 1981). Derivative 0 at w = 1 (see above).
template <typename T>
inline T albedo_factor(const T& w) {
  return safe_sqrt(T(1.0 - w));
}

// Hapke (1981) approximation H1.
template <typename T>
inline T h_hapke1981(double x, const T& w) {
  const T gamma = albedo_factor(w);
  return (1.0 + 2.0 * x) / (1.0 + 2.0 * x * gamma);
}

// Hapke (2002) eq. 13 approximation H2.
template <typename T>
inline T h_hapke2002(double x, const T& w) {
  if (x < std::numeric_limits<double>::min()) return T(1.0);  // x ln((1+x)/x) -> 0
  const T gamma = albedo_factor(w);
  const T r0 = (1.0 - gamma) / (1.0 + gamma);
  const double log_term = std::log1p(1.0 / x);  // ln((1 + x)/x)
  return 1.0 / (1.0 - w * x * (r0 + (1.0 - 2.0 * r0 * x) * (0.5 * log_term)));
}

namespace detail {

inline constexpr int kExactNodes = 10;      // Gauss-Legendre nodes per panel
inline constexpr int kExactMaxLevels = 64;  // smallest breakpoint (pi/2) 2^-64 ~ 8.5e-20

// Graded composite Gauss-Legendre rule on [0, pi/2]: panel k (k = 0..kExactMaxLevels-1) is
// [b_{k+1}, b_k] with b_k = (pi/2) 2^-k; bottom[L] is the panel [0, b_L]. Only tan(psi) is needed.
struct ExactHRule {
  std::array<std::array<double, kExactNodes>, kExactMaxLevels> panel_tan{};
  std::array<std::array<double, kExactNodes>, kExactMaxLevels> panel_weight{};
  std::array<std::array<double, kExactNodes>, kExactMaxLevels + 1> bottom_tan{};
  std::array<std::array<double, kExactNodes>, kExactMaxLevels + 1> bottom_weight{};
  std::array<double, kExactMaxLevels + 1> breakpoint{};
};

inline const ExactHRule& exact_h_rule() {
  static const ExactHRule rule = [] {
    ExactHRule r;
    const QuadratureRule unit = gauss_legendre(kExactNodes);  // on [-1, 1]
    const std::vector<double>& z = unit.nodes;
    const std::vector<double>& wz = unit.weights;
    for (int k = 0; k <= kExactMaxLevels; ++k) r.breakpoint[k] = std::ldexp(0.5 * kPi, -k);
    for (int k = 0; k < kExactMaxLevels; ++k) {
      const double lo = r.breakpoint[k + 1], hi = r.breakpoint[k];
      for (int i = 0; i < kExactNodes; ++i) {
        const double psi = 0.5 * (hi + lo) + 0.5 * (hi - lo) * z[i];
        r.panel_tan[k][i] = std::tan(psi);
        r.panel_weight[k][i] = 0.5 * (hi - lo) * wz[i];
      }
    }
    for (int k = 0; k <= kExactMaxLevels; ++k) {
      const double hi = r.breakpoint[k];
      for (int i = 0; i < kExactNodes; ++i) {
        const double psi = 0.5 * hi * (1.0 + z[i]);
        r.bottom_tan[k][i] = std::tan(psi);
        r.bottom_weight[k][i] = 0.5 * hi * wz[i];
      }
    }
    return r;
  }();
  return rule;
}

// 1 - arctan(t)/t for t > 0, without cancellation for small t (alternating series
// t^2/3 - t^4/5 + ..., truncation error < t^16/17 relative to t^2/3 ~ 1e-19 at t = 0.05).
inline double one_minus_atan_ratio(double t) {
  if (t < 0.05) {
    const double t2 = t * t;
    double sum = 0.0;
    double power = t2;
    for (int k = 1; k <= 7; ++k) {
      const double term = power / (2.0 * k + 1.0);
      sum += (k % 2 == 1) ? term : -term;
      power *= t2;
    }
    return sum;
  }
  return 1.0 - std::atan(t) / t;
}

// Adds weight * ln((1 - w) + w d) over the panel's nodes, d = 1 - a(psi).
template <typename T>
inline void add_panel(const std::array<double, kExactNodes>& tan_psi, const std::array<double, kExactNodes>& weight,
                      double x, const T& w, const T& one_minus_w, T& sum) {
  using std::log;
  for (int i = 0; i < kExactNodes; ++i) {
    const double d = one_minus_atan_ratio(tan_psi[i] / x);
    sum += weight[i] * log(one_minus_w + w * d);
  }
}

}  // namespace detail

// Exact H(x, w) for isotropic scattering (see the header comment). Requires 0 <= w <= 1.
template <typename T>
inline T h_exact(double x, const T& w) {
  using std::exp;
  if (x <= 0.0) return T(1.0);
  const detail::ExactHRule& rule = detail::exact_h_rule();
  // Width of the near-singular feature at psi -> 0 (w = 1: a floor well below every panel that
  // matters; the remaining panel then contributes O(b ln b) with b < 1e-8 x).
  const double one_minus_w_value = std::max(1.0 - scalar_value(w), 1e-16);
  const double scale = std::atan(x) * std::sqrt(one_minus_w_value);
  int levels = 0;
  while (levels < detail::kExactMaxLevels && rule.breakpoint[levels] > 0.5 * scale) ++levels;
  const T one_minus_w = 1.0 - w;
  T sum(0.0);
  for (int k = 0; k < levels; ++k) detail::add_panel(rule.panel_tan[k], rule.panel_weight[k], x, w, one_minus_w, sum);
  detail::add_panel(rule.bottom_tan[levels], rule.bottom_weight[levels], x, w, one_minus_w, sum);
  return exp(-kInvPi * sum);
}

}  // namespace roadbrdf::hapke
