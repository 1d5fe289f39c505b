// The N-term Legendre single-particle phase function of the "hapke" model (models/hapke.h), option
// phase = legendre with legendre_terms = N (1..8):
//   p(g) = 1 + sum_{n=1}^{N} a_n P_n(cos g),   g = phase angle,
// the series of Hapke (1981) (there with N = 2) and of Hapke, Icarus 157:523 (2002), where it feeds the
// anisotropic multiple-scattering terms (option multiple_scattering = anisotropic, below).
// Authors who expand in the scattering angle Theta = pi - g have coefficients (-1)^n a_n (odd ones
// change sign). Report eq. 3.29 writes the same series with the leading 1 absorbed
// (docs/report-corrections.md).
// Normalisation: (1/4pi) int p dOmega = 1 for every a_n, as int_{-1}^{1} P_n(x) dx = 0 for n >= 1.
// Parameters: a_1 = legendre_b, a_2 = legendre_c (the names of the two-term form), a_n = legendre_an
// for n >= 3.
// Bounds (p >= 0 is what makes p a phase function):
//   - N = 1: p = 1 + a_1 cos g >= 0 exactly when |a_1| <= 1: default and physical range [-1, 1].
//   - N = 2: the two-term box b in [-1, 1], c in [0, 1] and its physical extent (models/hapke.h).
//   - N >= 3: default box |a_n| <= 1/N. |P_n(x)| <= 1 on [-1, 1], so p >= 1 - sum |a_n| >= 0 inside
//     it: every default fit is a phase function. The exact region of p >= 0 is not a box; its extent
//     for each coefficient is within |a_n| <= 2n + 1 (a_n = (2n + 1)/2 int p P_n dx with p >= 0 and
//     int p dx = 2; the bound is the limit of a peak at g = 0 or pi), which is the physical range
//     (`fit` bounds may reach it; p may then be negative at some g, and the albedo checks flag it).
#pragma once

#include <string>
#include <utility>

namespace roadbrdf::hapke {

inline constexpr int kMaxLegendreTerms = 8;

// P_0..P_n(x) by Bonnet's recursion (n + 1) P_{n+1} = (2n + 1) x P_n - n P_{n-1}; values[k] = P_k(x),
// k <= n <= kMaxLegendreTerms.
inline void legendre_polynomials(double x, int n, double* values) {
  values[0] = 1.0;
  if (n >= 1) values[1] = x;
  for (int k = 1; k < n; ++k) values[k + 1] = ((2.0 * k + 1.0) * x * values[k] - k * values[k - 1]) / (k + 1.0);
}

// p(g) = 1 + sum_{n=1}^{terms} a[n-1] P_n(cos g).
template <typename T>
T legendre_series(const T* a, int terms, double cos_g) {
  double p[kMaxLegendreTerms + 1];
  legendre_polynomials(cos_g, terms, p);
  T sum(1.0);
  for (int n = 1; n <= terms; ++n) sum += a[n - 1] * p[n];
  return sum;
}

// Hapke's (2002) anisotropic multiple-scattering approximation (option multiple_scattering =
// anisotropic) needs two averages of p over hemispheres (Hapke, Icarus 157:523, 2002, eqs. 23-27):
//   P(mu) = 1 + sum_n A_n a_n P_n(mu)   (p averaged over the directions of one hemisphere, the other
//                                        direction at cosine mu: the light entering or leaving),
//   P-bar = 1 + sum_n A_n^2 a_n         (averaged over both directions),
// with A_n = int_{-1}^{0} P_n(x) dx (addition theorem: the hemispherical mean of P_n(u . v) is
// P_n(v_z) times the mean of P_n over the hemisphere): 0 for even n >= 2, A_1 = -1/2 and
// A_n = (2 - n)/(n + 1) A_{n-2} for odd n (A_3 = 1/8, A_5 = -1/16, A_7 = 5/128).
inline double hemisphere_moment(int n) {
  if (n % 2 == 0) return 0.0;
  double a = -0.5;
  for (int k = 3; k <= n; k += 2) a *= (2.0 - k) / (k + 1.0);
  return a;
}

// P(mu) for the coefficients a[0..terms-1]; mu may be a Jet (effective cosines of the roughness option).
template <typename T, typename X>
T hemisphere_average(const T* a, int terms, const X& mu) {
  X p_previous(1.0), p_current = mu;  // P_0, P_1 by Bonnet's recursion
  T sum(1.0);
  for (int n = 1; n <= terms; ++n) {
    if (n % 2 == 1) sum += (hemisphere_moment(n) * a[n - 1]) * p_current;
    const X next = ((2.0 * n + 1.0) * mu * p_current - static_cast<double>(n) * p_previous) / (n + 1.0);
    p_previous = p_current;
    p_current = next;
  }
  return sum;
}

// P-bar for the coefficients a[0..terms-1].
template <typename T>
T double_hemisphere_average(const T* a, int terms) {
  T sum(1.0);
  for (int n = 1; n <= terms; n += 2) sum += hemisphere_moment(n) * hemisphere_moment(n) * a[n - 1];
  return sum;
}

// Name of coefficient a_n.
inline std::string legendre_name(int n) {
  return n == 1 ? "legendre_b" : n == 2 ? "legendre_c" : "legendre_a" + std::to_string(n);
}

// Default (fitting) bounds and physical range of a_n for N terms, N != 2 (see the header comment).
inline std::pair<double, double> legendre_default_bounds(int terms) {
  const double limit = 1.0 / terms;
  return {-limit, limit};
}
inline std::pair<double, double> legendre_physical_bounds(int n, int terms) {
  if (terms == 1) return {-1.0, 1.0};
  return {-(2.0 * n + 1.0), 2.0 * n + 1.0};
}

}  // namespace roadbrdf::hapke
