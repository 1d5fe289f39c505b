// Fast exact H(x, w): a process-wide table of piecewise two-dimensional Chebyshev interpolants of the
// direct quadrature hapke::h_exact (models/hapke_h_function.h). Used by the "hapke" model with
// h_function = exact on every path (single, batch, prepared, with gradient), so all paths give the
// same values bit for bit; the direct quadrature remains the reference and the fallback (see below).
//
// Variables (chosen so that H is analytic, with singularities far from each panel):
//   - u = -log2(x): H(x) has a branch cut on x in [-1, 0] (Chandrasekhar 1960, ch. V), hence an
//     x ln x term at x -> 0; in ln x the cut lies on Im(ln x) = +-pi, a fixed distance from every
//     panel. Panels are the octaves x in [2^-(k+1), 2^-k], k = 0..kHTableOctaves-1, the local variable
//     t = 2 log2(x 2^k) + 1 in [-1, 1] (x = m 2^e by frexp, so only log2 of m in [1/2, 1) is needed).
//   - gamma = sqrt(1 - w): ln H = -(1/pi) int ln(1 - w a) dpsi is analytic in w off [1, inf), with a
//     square-root branch point at w = 1 (dH/dw ~ 1/sqrt(1 - w)); as a function of gamma it is
//     analytic on [0, 1] (checked: its Chebyshev coefficients on [0, 1] decay geometrically, ~1e-14
//     by degree 21 at x = 1). Panels gamma in [j/8, (j+1)/8], local variable s = 16 gamma - 2j - 1.
//   On each (octave, gamma panel) block H is the tensor Chebyshev interpolant of degree
//   (kHTableNodesX - 1) x (kHTableNodesG - 1) through the first-kind Chebyshev points, its values there
//   from h_exact. Blocks are built on first use (thread-safe), 120 quadratures each.
// Derivative: dH/dw = (dH/dgamma)(-1/(2 gamma)), dH/dgamma being the exact derivative of the
// interpolant (its weights depend on x and on the value of gamma only). At w = 1 (gamma = 0) the
// derivative is 0 by convention, as for the closed forms (safe_sqrt), instead of -infinity.
// Outside the table (x < 2^-kHTableOctaves, x > 1, w outside [0, 1]) h_tabulated calls h_exact.
// Accuracy against h_exact: see the comment block of models/hapke_h_function.h and
// tests/models/hapke_h_table_test.cpp.
#pragma once

#include <cmath>
#include <cstddef>
#include <type_traits>

#include "roadbrdf/core/math.h"
#include "roadbrdf/models/hapke_h_function.h"

namespace roadbrdf::hapke {

inline constexpr int kHTableOctaves = 40;     // x down to 2^-40 ~ 9.1e-13
inline constexpr int kHTableGammaPanels = 8;  // gamma panels of width 1/8
inline constexpr int kHTableNodesX = 12;      // Chebyshev degree 11 in t per octave
inline constexpr int kHTableNodesG = 10;      // Chebyshev degree 9 in s per gamma panel

// Chebyshev coefficients c[a * kHTableNodesG + b] of block (octave, gamma panel):
// H = sum_a sum_b c[a][b] T_a(t) T_b(s). Built on first use; the pointer stays valid.
const double* h_table_block(int octave, int gamma_panel);

// The interpolant at 2^-kHTableOctaves <= x <= 1, 0 <= gamma <= 1, and, if dh_dgamma is not null, its
// derivative with respect to gamma. The value does not depend on whether the derivative is asked for.
double h_table_evaluate(double x, double gamma, double* dh_dgamma);

// The interpolant and its derivatives with respect to x and gamma (the model's roughness option
// evaluates H at effective cosines that depend on a fitted parameter). Same value as
// h_table_evaluate. dH/dx = (dH/dt) 2/(x ln 2), t = 2 log2(x 2^k) + 1: within 1e-6 relative of central
// differences of h_exact for x >= 1e-3 and 1e-5 below (tests/models/hapke_h_table_test.cpp).
double h_table_evaluate_slopes(double x, double gamma, double* dh_dx, double* dh_dgamma);

// The table at one albedo, for callers that evaluate H at many x for a few fixed w (the path tracer:
// one parameter set per wavelength for a whole render). With gamma fixed, the panel j and the
// T_b(s) are fixed, so each block collapses to a one-variable Chebyshev series in t:
//   H(x) = sum_a r_a T_a(t),  r_a = sum_b c_ab T_b(s)   (same interpolant, other summation order),
// 12 multiply-adds per x instead of 120 + the Chebyshev recurrences in s. The value equals
// h_table_evaluate(x, gamma, nullptr) to rounding (a few units in the last place: the double sum is
// only reassociated; tests/models/hapke_h_table_test.cpp bounds it), not bit for bit.
inline constexpr int kHTableSeriesSize = kHTableOctaves * kHTableNodesX;
// series[k * kHTableNodesX + a] = r_a of octave k at this gamma (0 <= gamma <= 1); builds the blocks
// of gamma's panel for every octave.
void h_table_series(double gamma, double* series);
// Where x falls in the table: the octave and T_a(t), a < kHTableNodesX (computed once per x, shared by
// every albedo). False outside 2^-kHTableOctaves <= x <= 1.
struct HTablePoint {
  int octave = 0;
  double tx[kHTableNodesX];
};
bool h_table_point(double x, HTablePoint& point);
// H at a point from the series of one albedo.
inline double h_series_evaluate(const double* series, const HTablePoint& point) {
  const double* r = series + static_cast<std::ptrdiff_t>(point.octave) * kHTableNodesX;
  double value = 0.0;
  for (int a = 0; a < kHTableNodesX; ++a) value += r[a] * point.tx[a];
  return value;
}

// Whether h_tabulated(x, w) reads the table (0 < x <= 1 inside it, 0 <= w <= 1).
inline bool h_table_covers(double x, double w) {
  return x > 0.0 && x <= 1.0 && x >= std::ldexp(1.0, -kHTableOctaves) && w >= 0.0 && w <= 1.0;
}

// H(x, w) from the table (see above); outside it (x < 2^-kHTableOctaves, x > 1, w outside [0, 1]) the
// direct quadrature h_exact.
template <typename T>
inline T h_tabulated(double x, const T& w) {
  if (x <= 0.0) return T(1.0);
  const double wv = scalar_value(w);
  if (!(x <= 1.0 && x >= std::ldexp(1.0, -kHTableOctaves) && wv >= 0.0 && wv <= 1.0)) return h_exact(x, w);
  const double gamma = std::sqrt(1.0 - wv);
  if constexpr (std::is_same_v<T, double>) {
    return h_table_evaluate(x, gamma, nullptr);
  } else {
    double dh_dgamma = 0.0;
    T result(h_table_evaluate(x, gamma, &dh_dgamma));
    // dgamma/dw = -1/(2 gamma); at gamma = 0 (w = 1) the derivative is 0 by convention.
    const double dh_dw = gamma > 0.0 ? -0.5 * dh_dgamma / gamma : 0.0;
    result.v = dh_dw * w.v;
    return result;
  }
}

}  // namespace roadbrdf::hapke
