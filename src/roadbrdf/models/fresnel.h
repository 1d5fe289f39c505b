// Fresnel reflectance of unpolarised light (report section 2.2, eqs. 2.14-2.16).
//
// All functions take the cosine of the angle between the incident direction and the (micro)normal
// and the relative index of the transmitting medium, eta = n_t / n_i (k = extinction coefficient for
// conductors). Templated so that eta and k can be fitted with automatic differentiation.
#pragma once

#include <cmath>
#include <limits>

#include "roadbrdf/core/math.h"

namespace roadbrdf {

// s- and p-polarised reflectances of a dielectric interface (Born & Wolf, Principles of Optics,
// section 1.5.2); r_perp = rs, r_par = rp in the report's notation. Total internal reflection
// (eta < 1 beyond the critical angle) gives rs = rp = 1.
template <typename T>
struct PolarisedReflectance {
  T rs;
  T rp;
};

template <typename T>
PolarisedReflectance<T> fresnel_dielectric_polarised(T cos_i, T eta) {
  using std::sqrt;
  cos_i = clamp_value(cos_i, 0.0, 1.0);
  const T sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
  if (scalar_value(sin2_t) >= 1.0) return {T(1.0), T(1.0)};
  const T cos_t = sqrt(1.0 - sin2_t);
  const T rs = sqr((cos_i - eta * cos_t) / (cos_i + eta * cos_t));
  const T rp = sqr((eta * cos_i - cos_t) / (eta * cos_i + cos_t));
  return {rs, rp};
}

// Exact dielectric Fresnel reflectance, report eq. 2.14: F = (rs + rp) / 2.
template <typename T>
T fresnel_dielectric(const T& cos_i, const T& eta) {
  const PolarisedReflectance<T> r = fresnel_dielectric_polarised(cos_i, eta);
  return 0.5 * (r.rs + r.rp);
}

// fresnel_dielectric for a cosine that is plain data (a geometry quantity, not differentiated): the
// same values as fresnel_dielectric(T(cos_i), eta), without the ceres::Jet arithmetic on a constant.
template <typename T>
T fresnel_dielectric_at(double cos_i, const T& eta) {
  using std::sqrt;
  const double c = clamp_value(cos_i, 0.0, 1.0);
  const T sin2_t = T(1.0 - c * c) / (eta * eta);
  if (scalar_value(sin2_t) >= 1.0) return T(1.0);  // total internal reflection: rs = rp = 1
  const T cos_t = sqrt(1.0 - sin2_t);
  const T eta_cos_t = eta * cos_t;
  const T eta_cos_i = eta * c;
  const T rs = sqr((c - eta_cos_t) / (c + eta_cos_t));
  const T rp = sqr((eta_cos_i - cos_t) / (eta_cos_i + cos_t));
  return 0.5 * (rs + rp);
}

// Exact conductor Fresnel reflectance for a complex relative index eta + i k (report eq. 2.14,
// conductor case, in the a/b form of Cook & Torrance 1982 / Born & Wolf). k = 0 reduces to the
// dielectric case for eta >= 1.
template <typename T>
T fresnel_conductor(T cos_i, const T& eta, const T& k) {
  using std::sqrt;
  cos_i = clamp_value(cos_i, 0.0, 1.0);
  const T cos2 = cos_i * cos_i;
  const T sin2 = 1.0 - cos2;
  const T t0 = eta * eta - k * k - sin2;
  const T a2_plus_b2 = sqrt(t0 * t0 + 4.0 * eta * eta * k * k);
  const T a = safe_sqrt(0.5 * (a2_plus_b2 + t0));
  // b^2 = (a^2 + b^2 - t0) / 2 >= 0; clamped because a2_plus_b2 may round one ulp below |t0|.
  const T b2 = clamp_value(T(0.5 * (a2_plus_b2 - t0)), 0.0, std::numeric_limits<double>::infinity());
  // Both factors written as sums of squares, (a - cos)^2 + b^2 over (a + cos)^2 + b^2 and
  // (a cos - sin^2)^2 + b^2 cos^2 over (a cos + sin^2)^2 + b^2 cos^2 (the same algebra as the
  // expanded a^2 + b^2 form), so that rounding cannot make the reflectance negative (k = 0 at
  // grazing incidence gave -5e-17).
  const T rs_denominator = sqr(a + cos_i) + b2;
  // a = b = 0 at grazing incidence only for n = 1, k = 0: the grazing limit of every interface, 1.
  if (scalar_value(rs_denominator) == 0.0) return T(1.0);
  const T rs = (sqr(a - cos_i) + b2) / rs_denominator;
  const T rp = rs * (sqr(a * cos_i - sin2) + b2 * cos2) / (sqr(a * cos_i + sin2) + b2 * cos2);
  return 0.5 * (rs + rp);
}

// Normal-incidence reflectance of a dielectric interface: ((eta - 1) / (eta + 1))^2.
template <typename T>
T fresnel_f0(const T& eta) {
  return sqr((eta - 1.0) / (eta + 1.0));
}

// Schlick's approximation for dielectrics (Schlick 1994; report eq. 2.15).
template <typename T>
T fresnel_schlick(const T& cos_i, const T& f0) {
  const T m = 1.0 - clamp_value(cos_i, 0.0, 1.0);
  const T m2 = m * m;
  return f0 + (1.0 - f0) * (m2 * m2 * m);
}

// Lazanyi & Szirmay-Kalos (2005) Schlick-type approximation for conductors (report eq. 2.16):
// F = ((eta - 1)^2 + 4 eta (1 - cos)^5 + k^2) / ((eta + 1)^2 + k^2).
template <typename T>
T fresnel_schlick_conductor(const T& cos_i, const T& eta, const T& k) {
  const T m = 1.0 - clamp_value(cos_i, 0.0, 1.0);
  const T m2 = m * m;
  return (sqr(eta - 1.0) + 4.0 * eta * (m2 * m2 * m) + k * k) / (sqr(eta + 1.0) + k * k);
}

}  // namespace roadbrdf
