// Hapke's correction for macroscopic roughness (Hapke, "Bidirectional reflectance spectroscopy 3.
// Correction for macroscopic roughness", Icarus 59:41-59, 1984, eqs. 46-51; also
// Hapke, "Theory of Reflectance and Emittance Spectroscopy", 1993, section 12.D), used by the
// "hapke" model with option roughness = hapke1984 (models/hapke.h).
//
// The surface is tilted facets with a Gaussian-like slope distribution of mean slope theta_bar; the
// rough surface's bidirectional reflectance is the smooth one evaluated at effective cosines mu0e,
// mue times a shadowing function S:
//   r_R(i, e, g) = (w/4pi) mu0e/(mu0e + mue) {[1 + B(g)] p(g) + H(mu0e) H(mue) - 1} S(i, e, psi),
// with i, e the incidence and emergence zenith angles, g the phase angle (unchanged) and psi in
// [0, pi] the azimuth between the planes of incidence and emergence (psi = 0: both directions on the
// same side, the backscatter side: cos g = cos i cos e + sin i sin e cos psi). With
//   chi = 1/sqrt(1 + pi tan^2 theta_bar),
//   E1(x) = exp(-(2/pi) cot theta_bar cot x),   E2(x) = exp(-(1/pi) cot^2 theta_bar cot^2 x),
//   eta(x) = chi [cos x + sin x tan theta_bar E2(x)/(2 - E1(x))]          (the psi = 0 cosines),
//   f(psi) = exp(-2 tan(psi/2)),
// for i <= e:
//   mu0e = chi [cos i + sin i tan theta_bar (cos psi E2(e) + sin^2(psi/2) E2(i))/(2 - E1(e) - (psi/pi) E1(i))]
//   mue  = chi [cos e + sin e tan theta_bar (E2(e) - sin^2(psi/2) E2(i))/(2 - E1(e) - (psi/pi) E1(i))]
//   S    = (mue/eta(e)) (mu0/eta(i)) chi / [1 - f(psi) + f(psi) chi (mu0/eta(i))],
// and for e <= i the same with the roles of i and e exchanged (mu0e takes the second form, mue the
// first, and the last factor reads chi (mu/eta(e))). At i = e both forms agree.
// The BRDF is f = r_R/mu0. S carries a factor mu0 (the i <= e form) or mu0/eta(i) (e <= i), so this
// file returns S/mu0, finite at grazing incidence where mu0 = 0:
//   S/mu0 = (mue/eta(e)) (1/eta(i)) chi / [1 - f(psi) + f(psi) chi cos(x)/eta(x)],  x = min(i, e).
// Properties (tests/models/hapke_roughness_test.cpp checks each from the formulas written again):
//   - theta_bar = 0: chi = 1, E1 = E2 = 0, mu0e = mu0, mue = mu, S = 1 (the smooth model).
//   - i = e = 0: mu0e = mue = eta = chi and S = 1.
//   - exchanging i and e exchanges mu0e and mue and leaves (mu0e/mu0) S = mu0e mue chi/(eta(i) eta(e) D)
//     unchanged, so f = r_R/mu0 is reciprocal.
//   - Near theta_bar = 0 every term differs from the smooth one by O(theta_bar^2) (chi = 1 - (pi/2)
//     theta_bar^2 + ...; E1, E2 vanish faster than any power): df/dtheta_bar = 0 at theta_bar = 0, so
//     a fit of theta_bar must start away from 0.
// Where cot x is infinite (x = 0, sin x = 0) E1 = E2 = 0 and every term they multiply vanishes with
// sin x. psi is undefined when one direction is the normal; every psi-dependent term then cancels
// (sin x = 0, or the last factor is 1 since cos(0)/eta(0) = 1/chi).
#pragma once

#include <cmath>
#include <limits>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"

namespace roadbrdf::hapke {

// Geometry-only terms of the correction.
struct RoughnessGeometry {
  double cos_i = 1.0, sin_i = 0.0, cot_i = 0.0;  // cot: +infinity where sin = 0
  double cos_e = 1.0, sin_e = 0.0, cot_e = 0.0;
  double psi = 0.0;               // azimuth between the planes of incidence and emergence, [0, pi]
  double cos_psi = 1.0;           // cos(psi)
  double sin2_half_psi = 0.0;     // sin^2(psi/2)
  double f_psi = 1.0;             // f(psi) = exp(-2 tan(psi/2)); 0 at psi = pi
  bool incidence_steeper = true;  // i <= e (the first form)
};

inline RoughnessGeometry roughness_geometry(const Vec3& wi, const Vec3& wr) {
  RoughnessGeometry r;
  r.cos_i = std::fmax(0.0, std::fmin(1.0, wi.z));
  r.cos_e = std::fmax(0.0, std::fmin(1.0, wr.z));
  r.sin_i = std::hypot(wi.x, wi.y);
  r.sin_e = std::hypot(wr.x, wr.y);
  r.cot_i = r.sin_i > 0.0 ? r.cos_i / r.sin_i : std::numeric_limits<double>::infinity();
  r.cot_e = r.sin_e > 0.0 ? r.cos_e / r.sin_e : std::numeric_limits<double>::infinity();
  // psi from the horizontal components (atan2: accurate near 0 and pi); 0 where one is the normal.
  const double along = wi.x * wr.x + wi.y * wr.y;
  const double across = std::fabs(wi.x * wr.y - wi.y * wr.x);
  r.psi = std::atan2(across, along);
  r.cos_psi = std::cos(r.psi);
  const double half = std::sin(0.5 * r.psi);
  r.sin2_half_psi = half * half;
  r.f_psi = r.psi < kPi ? std::exp(-2.0 * std::tan(0.5 * r.psi)) : 0.0;
  r.incidence_steeper = r.cos_i >= r.cos_e;
  return r;
}

// exp(-a) for a >= 0, 0 (value and derivatives) once it underflows, so that a Jet's derivative is
// not 0 * infinity.
template <typename T>
T exp_of_negative(const T& a) {
  using std::exp;
  if (!(scalar_value(a) < 745.0)) return T(0.0);
  return exp(-a);
}

// E1(x) = exp(-(2/pi) cot theta_bar cot x) and E2(x) = exp(-(1/pi) cot^2 theta_bar cot^2 x).
template <typename T>
T roughness_e1(const T& cot_theta_bar, double cot_x) {
  if (!(cot_x < std::numeric_limits<double>::infinity())) return T(0.0);
  return exp_of_negative(T(2.0 * kInvPi * cot_x * cot_theta_bar));
}
template <typename T>
T roughness_e2(const T& cot_theta_bar, double cot_x) {
  if (!(cot_x < std::numeric_limits<double>::infinity())) return T(0.0);
  const T a = cot_x * cot_theta_bar;
  return exp_of_negative(T(kInvPi * a * a));
}

template <typename T>
struct RoughCosines {
  T mu0e, mue;        // effective cosines of incidence and emergence
  T shadow_over_mu0;  // S/mu0 (finite at mu0 = 0)
};

// The terms that depend on theta_bar alone (one parameter set): tan, cot and chi.
template <typename T>
struct RoughSlope {
  T tan_t, cot_t, chi;
};
template <typename T>
RoughSlope<T> rough_slope(const T& theta_bar) {
  using std::sqrt;
  using std::tan;
  RoughSlope<T> r{tan(theta_bar), T(0.0), T(0.0)};
  r.cot_t = 1.0 / r.tan_t;
  r.chi = 1.0 / sqrt(1.0 + kPi * r.tan_t * r.tan_t);
  return r;
}

// The terms of one zenith angle x at one theta_bar: E1(x), E2(x) and eta(x). A grid has few distinct
// zeniths, so a batch computes them once per zenith and parameter set (Hapke::evaluate_rough).
template <typename T>
struct RoughZenith {
  T e1, e2, eta;
};
template <typename T>
RoughZenith<T> rough_zenith(const RoughSlope<T>& s, double cos_x, double sin_x, double cot_x) {
  RoughZenith<T> z{roughness_e1(s.cot_t, cot_x), roughness_e2(s.cot_t, cot_x), T(0.0)};
  z.eta = s.chi * (cos_x + sin_x * s.tan_t * z.e2 / (2.0 - z.e1));
  return z;
}

// The effective cosines and S/mu0 from those terms (i: incidence, e: emergence).
template <typename T>
RoughCosines<T> rough_cosines(const RoughSlope<T>& s, const RoughZenith<T>& i, const RoughZenith<T>& e,
                              const RoughnessGeometry& g) {
  const T& tan_t = s.tan_t;
  const T& chi = s.chi;
  const double psi_fraction = g.psi * kInvPi;
  RoughCosines<T> r;
  T last;  // 1 - f(psi) + f(psi) chi cos(x)/eta(x), x the steeper direction
  if (g.incidence_steeper) {
    const T denominator = 2.0 - e.e1 - psi_fraction * i.e1;
    r.mu0e = chi * (g.cos_i + g.sin_i * tan_t * (g.cos_psi * e.e2 + g.sin2_half_psi * i.e2) / denominator);
    r.mue = chi * (g.cos_e + g.sin_e * tan_t * (e.e2 - g.sin2_half_psi * i.e2) / denominator);
    last = 1.0 - g.f_psi + g.f_psi * chi * g.cos_i / i.eta;
  } else {
    const T denominator = 2.0 - i.e1 - psi_fraction * e.e1;
    r.mu0e = chi * (g.cos_i + g.sin_i * tan_t * (i.e2 - g.sin2_half_psi * e.e2) / denominator);
    r.mue = chi * (g.cos_e + g.sin_e * tan_t * (g.cos_psi * i.e2 + g.sin2_half_psi * e.e2) / denominator);
    last = 1.0 - g.f_psi + g.f_psi * chi * g.cos_e / e.eta;
  }
  r.shadow_over_mu0 = (r.mue / e.eta) * chi / (i.eta * last);
  return r;
}

// The effective cosines and S/mu0 at theta_bar > 0 (radians; theta_bar = 0 is the smooth model,
// which the caller evaluates directly).
template <typename T>
RoughCosines<T> rough_cosines(const T& theta_bar, const RoughnessGeometry& g) {
  const RoughSlope<T> s = rough_slope(theta_bar);
  return rough_cosines(s, rough_zenith(s, g.cos_i, g.sin_i, g.cot_i), rough_zenith(s, g.cos_e, g.sin_e, g.cot_e), g);
}

}  // namespace roadbrdf::hapke
