// Microfacet building blocks: normal distributions D and masking-shadowing functions G.
//
// Conventions (Walter, Marschner, Li, Torrance, "Microfacet models for refraction through rough
// surfaces", EGSR 2007, section 3):
//  * every distribution here is normalised as a distribution of microfacet *area* projected on the
//    mean plane:  integral over the hemisphere of D(w_m) cos(theta_m) dw_m = 1  (Walter eq. 4);
//  * D takes cos(theta_m) (a plain double: geometry is data) and the roughness as T (double or
//    ceres::Jet, so that the fitter can differentiate with respect to it);
//  * Smith functions are expressed through Lambda (Walter eq. 24 / Heitz 2014 eq. 72): we return
//    cos(theta) * Lambda(theta), which stays finite at grazing angles, so that the BRDF factor
//    G / (cos theta_i cos theta_r) can be computed without 0/0 at theta = 90 deg.
//
// Roughness conventions: Beckmann, GGX, Ward: alpha = RMS slope (dimensionless);
// Gaussian: sigma = standard deviation of the facet angle theta_m in radians (report eq. 3.4);
// Phong: exponent m (dimensionless); Berry / GTR: Burley's alpha (dimensionless).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <ceres/jet.h>

#include "roadbrdf/core/math.h"
#include "roadbrdf/core/quadrature.h"

namespace roadbrdf {
namespace microfacet {

// Gauss-Legendre rule on [0, 1] (core/quadrature.h); computed once per n, cached. Thread-safe.
const QuadratureRule& gauss_legendre_01(int n);

inline constexpr double kSqrtPi = 1.7724538509055160273;

// ---- helpers --------------------------------------------------------------------------------

// (exp(y) - 1) / y, equal to 1 at y = 0, smooth (series near 0). Works for Jets.
template <typename T>
T expm1_over_x(const T& y) {
  using std::expm1;
  if (std::fabs(scalar_value(y)) < 1e-5) return 1.0 + y * (0.5 + y * (1.0 / 6.0));
  return expm1(y) / y;
}

// Scaled complementary error function erfcx(x) = exp(x^2) erfc(x), x >= 0. Direct form for
// x < 12; asymptotic series (Abramowitz & Stegun 7.1.23, 8 terms) beyond, relative error < 1e-13.
template <typename T>
T erfcx(const T& x) {
  using std::erfc;
  using std::exp;
  if (scalar_value(x) < 12.0) return exp(x * x) * erfc(x);
  const T u = 1.0 / (2.0 * x * x);  // 1/(2x^2)
  // sum_k (-1)^k (2k-1)!! u^k, k = 0..7
  const T series =
      1.0 + u * (-1.0 + u * (3.0 + u * (-15.0 + u * (105.0 + u * (-945.0 + u * (10395.0 + u * -135135.0))))));
  return series / (x * kSqrtPi);
}

// ---- normal distributions (cos-weighted normalisation, see top) ------------------------------

// Beckmann, report eq. 3.8 (Walter 2007 eq. 25): exp(-tan^2/alpha^2) / (pi alpha^2 cos^4).
// (Report eq. 3.21 misses the 1/pi; eq. 3.8 and the papers have it.)
template <typename T>
T beckmann_d(double cos_m, const T& alpha) {
  using std::exp;
  if (cos_m <= 0.0) return T(0.0);
  const double c2 = cos_m * cos_m;
  const double tan2 = (1.0 - c2) / c2;
  const T a2 = alpha * alpha;
  return exp(-tan2 / a2) / (kPi * a2 * c2 * c2);
}

// GGX / Trowbridge-Reitz, report eq. 3.14 (Walter 2007 eq. 33), written as
// alpha^2 / (pi (1 + (alpha^2 - 1) cos^2)^2), which equals eq. 3.14 and has no tan.
template <typename T>
T ggx_d(double cos_m, const T& alpha) {
  if (cos_m <= 0.0) return T(0.0);
  const T a2 = alpha * alpha;
  const T t = 1.0 + (a2 - 1.0) * (cos_m * cos_m);
  return a2 / (kPi * t * t);
}

// Normalisation constant of the generalised Trowbridge-Reitz distribution (Burley 2012, appendix
// B.2): c = (gamma - 1)(alpha^2 - 1) / (pi (1 - (alpha^2)^(1 - gamma))), and for gamma = 1 (Berry)
// c = (alpha^2 - 1) / (pi ln alpha^2). With x = ln alpha^2 both read
// c = (1/pi) * expm1_over_x(x) / expm1_over_x(-(gamma - 1) x), smooth through gamma = 1 and alpha = 1.
template <typename T>
T gtr_normalisation(const T& alpha, const T& gamma) {
  using std::log;
  const T x = 2.0 * log(alpha);
  return kInvPi * expm1_over_x(x) / expm1_over_x(-(gamma - 1.0) * x);
}

// GTR, Burley 2012 eq. (B.2 family): c / (alpha^2 cos^2 + sin^2)^gamma. gamma = 2 is GGX.
template <typename T>
T gtr_d(double cos_m, const T& alpha, const T& gamma) {
  using std::pow;
  if (cos_m <= 0.0) return T(0.0);
  const double c2 = cos_m * cos_m;
  const T base = alpha * alpha * c2 + (1.0 - c2);
  return gtr_normalisation(alpha, gamma) / pow(base, gamma);
}

// Berry distribution = GTR with gamma = 1 (Burley 2012 section 5.4 and appendix B).
template <typename T>
T berry_d(double cos_m, const T& alpha) {
  return gtr_d(cos_m, alpha, T(1.0));
}

// Ward's distribution as printed in report eq. 3.22 (Kelemen & Szirmay-Kalos 2001):
// exp(-tan^2/alpha^2) / (pi alpha^2 cos^3). That form integrates to 1 over the solid angle of the
// half vector (it is a probability density of h, = Beckmann * cos); its cos-weighted integral is
// N(alpha) = (sqrt(pi)/alpha) erfcx(1/alpha) (derived by t = tan theta, u = 1 + alpha^2 v...; -> 1 as
// alpha -> 0). ward_d returns eq. 3.22 / N(alpha), so that it obeys the common normalisation.
template <typename T>
T ward_cos_normalisation(const T& alpha) {
  return kSqrtPi / alpha * erfcx(1.0 / alpha);
}
template <typename T>
T ward_halfway_pdf(double cos_m, const T& alpha) {
  if (cos_m <= 0.0) return T(0.0);
  return beckmann_d(cos_m, alpha) * cos_m;
}
template <typename T>
T ward_d(double cos_m, const T& alpha) {
  return ward_halfway_pdf(cos_m, alpha) / ward_cos_normalisation(alpha);
}

// Phong (Blinn) distribution. Report eq. 3.23 prints (m + 1)/(2 pi) cos^m, which is the density of
// the half vector over solid angle (integral of D dw = 1, Kelemen & Szirmay-Kalos 2001). The
// cos-weighted normalisation used here is (m + 2)/(2 pi) cos^m (Walter 2007 eq. 30).
template <typename T>
T phong_d(double cos_m, const T& m) {
  using std::pow;
  if (cos_m <= 0.0) return T(0.0);
  return (m + 2.0) * (0.5 * kInvPi) * pow(cos_m, m);
}
template <typename T>
T phong_halfway_pdf(double cos_m, const T& m) {
  using std::pow;
  if (cos_m <= 0.0) return T(0.0);
  return (m + 1.0) * (0.5 * kInvPi) * pow(cos_m, m);
}

// Gaussian distribution of the facet angle, report eq. 3.4: c exp(-theta_m^2 / (2 sigma^2)), theta_m
// in radians. The constant makes the cos-weighted integral 1:
//   1/c = 2 pi int_0^{pi/2} exp(-theta^2/(2 sigma^2)) cos theta sin theta dtheta,
// computed by a fixed 64-point Gauss-Legendre rule on [0, theta_max], theta_max = min(pi/2, 9 sigma)
// (the neglected tail is below exp(-40)); the rule is fixed, so c is a smooth function of sigma
// and differentiates with Jets. (The report normalises with sin only, a solid-angle density; we use
// the cos-weighted normalisation that the BRDF formula eq. 3.7 needs, Walter 2007 eq. 4.)
template <typename T>
T gaussian_normalisation(const T& sigma) {
  using std::exp;
  using std::sin;
  const QuadratureRule& rule = gauss_legendre_01(64);
  const T theta_max = scalar_value(sigma) * 9.0 < kPi / 2 ? T(9.0 * sigma) : T(kPi / 2);
  const T inv_two_s2 = 0.5 / (sigma * sigma);
  T sum(0.0);
  for (std::size_t k = 0; k < rule.nodes.size(); ++k) {
    const T theta = theta_max * rule.nodes[k];
    sum += rule.weights[k] * exp(-theta * theta * inv_two_s2) * sin(2.0 * theta);
  }
  // 2 pi * int cos sin = pi * int sin(2 theta)
  return 1.0 / (kPi * theta_max * sum);
}
// The quadrature costs 64 exponentials: cache c(sigma) and dc/dsigma for the last sigma (per
// thread) and rebuild the value (and, for Jets, the first-order derivative) from them.
inline void gaussian_normalisation_cached(double sigma, double* c, double* dc) {
  thread_local double last_sigma = -1.0, last_c = 0.0, last_dc = 0.0;
  if (sigma != last_sigma) {
    const ceres::Jet<double, 1> j = gaussian_normalisation(ceres::Jet<double, 1>(sigma, 0));
    last_sigma = sigma;
    last_c = j.a;
    last_dc = j.v[0];
  }
  *c = last_c;
  *dc = last_dc;
}
template <typename T>
T gaussian_d(double cos_m, const T& sigma) {
  using std::exp;
  if (cos_m <= 0.0) return T(0.0);
  const double theta = std::acos(std::fmin(cos_m, 1.0));
  const double s = scalar_value(sigma);
  double c = 0.0, dc = 0.0;
  gaussian_normalisation_cached(s, &c, &dc);
  const T norm = c + dc * (sigma - s);  // value c; derivative dc * dsigma for Jets
  return norm * exp(-(theta * theta) / (2.0 * sigma * sigma));
}

// ---- Smith masking: cos(theta) * Lambda(theta) ----------------------------------------------

// Beckmann, exact (Walter 2007 eq. 24-26 / Heitz 2014 eq. 80; report eq. 3.12 with a = 1/(alpha tan)):
// Lambda = (erf(a) - 1)/2 + exp(-a^2)/(2 a sqrt(pi)). Multiplied by cos = a alpha sin, the 1/a
// disappears: cos Lambda = cos (erf(a) - 1)/2 + alpha sin exp(-a^2)/(2 sqrt(pi)).
template <typename T>
T beckmann_cos_lambda(double cos_t, const T& alpha) {
  using std::erfc;
  using std::exp;
  const double c = std::fmin(std::fmax(cos_t, 0.0), 1.0);
  const double s = std::sqrt(std::fmax(0.0, 1.0 - c * c));
  if (s == 0.0) return T(0.0);
  const T a = c / (alpha * s);
  return -0.5 * c * erfc(a) + alpha * (s / (2.0 * kSqrtPi)) * exp(-a * a);
}

// Beckmann, rational approximation (Walter 2007 eq. 27, written for Lambda as report eq. 3.13):
// Lambda = (1 - 1.259 a + 0.396 a^2) / (3.535 a + 2.181 a^2) for a < 1.6, else 0.
// cos Lambda = alpha sin (1 - 1.259 a + 0.396 a^2) / (3.535 + 2.181 a).
template <typename T>
T beckmann_cos_lambda_rational(double cos_t, const T& alpha) {
  const double c = std::fmin(std::fmax(cos_t, 0.0), 1.0);
  const double s = std::sqrt(std::fmax(0.0, 1.0 - c * c));
  if (s == 0.0) return T(0.0);
  const T a = c / (alpha * s);
  if (scalar_value(a) >= 1.6) return T(0.0);
  return alpha * s * (1.0 - 1.259 * a + 0.396 * a * a) / (3.535 + 2.181 * a);
}

// GGX exact (Walter 2007 eq. 34 / Heitz 2014 eq. 86; report eq. 3.15):
// Lambda = (-1 + sqrt(1 + alpha^2 tan^2)) / 2  =>  cos Lambda = (sqrt(cos^2 + alpha^2 sin^2) - cos) / 2.
// The geometry-only inputs of ggx_cos_lambda (clamped cos, cos^2, sin^2), precomputable per direction.
struct GgxLambdaGeometry {
  double c = 0.0;
  double c2 = 0.0;
  double s2 = 0.0;
};
inline GgxLambdaGeometry ggx_lambda_geometry(double cos_t) {
  GgxLambdaGeometry q;
  q.c = std::fmin(std::fmax(cos_t, 0.0), 1.0);
  q.c2 = q.c * q.c;
  q.s2 = std::fmax(0.0, 1.0 - q.c2);
  return q;
}
// Same value as ggx_cos_lambda(q, alpha) with alpha2 = alpha * alpha (shared by both directions).
template <typename T>
T ggx_cos_lambda_from_alpha2(const GgxLambdaGeometry& q, const T& alpha2) {
  using std::sqrt;
  return 0.5 * (sqrt(q.c2 + alpha2 * q.s2) - q.c);
}
template <typename T>
T ggx_cos_lambda(const GgxLambdaGeometry& q, const T& alpha) {
  return ggx_cos_lambda_from_alpha2(q, alpha * alpha);
}
template <typename T>
T ggx_cos_lambda(double cos_t, const T& alpha) {
  return ggx_cos_lambda(ggx_lambda_geometry(cos_t), alpha);
}

// Smith G1(w) / cos(theta) = 1 / (cos (1 + Lambda)) (Heitz 2014 eq. 43, microfacet-independent
// part; the chi+(w.m) factor is 1 for the reflection half vector).
template <typename T>
T smith_g1_over_cos(double cos_t, const T& cos_lambda) {
  return 1.0 / (cos_t + cos_lambda);
}

// G2 / (cos_i cos_r) for the Smith profile.
//  height-correlated: G2 = 1 / (1 + Lambda_i + Lambda_r)  (Heitz 2014 eq. 99; report eq. 3.10);
//  uncorrelated:      G2 = G1(i) G1(r)                     (Heitz 2014 eq. 98; Walter 2007 eq. 23).
// Returns 0 when both directions are exactly grazing (the height-correlated form diverges there;
// the point has zero measure and every cosine-weighted quantity vanishes).
template <typename T>
T smith_g2_over_cos(double cos_i, double cos_r, const T& cos_lambda_i, const T& cos_lambda_r, bool height_correlated) {
  if (height_correlated) {
    const T denom = cos_i * cos_r + cos_r * cos_lambda_i + cos_i * cos_lambda_r;
    if (scalar_value(denom) <= 0.0) return T(0.0);
    return 1.0 / denom;
  }
  const T denom = (cos_i + cos_lambda_i) * (cos_r + cos_lambda_r);
  if (scalar_value(denom) <= 0.0) return T(0.0);
  return 1.0 / denom;
}

// V-cavity G / (cos_i cos_r) (Torrance & Sparrow 1967; Cook & Torrance 1982 eq. for G; report eq. 3.3
// with the second term corrected, docs/report-corrections.md):
//   G = min(1, 2 (n.h)(n.v)/(v.h), 2 (n.h)(n.l)/(l.h)),  v.h = l.h for the half vector.
// With a = 2 (n.h)/(l.h), G/(cos_i cos_r) = min(1/c_min, a) / c_max, finite when one cosine is 0.
inline double vcavity_g_over_cos(double cos_i, double cos_r, double cos_h, double cos_ih) {
  const double c_min = std::fmin(cos_i, cos_r);
  const double c_max = std::fmax(cos_i, cos_r);
  if (c_max <= 0.0 || cos_ih <= 0.0 || cos_h <= 0.0) return 0.0;
  const double a = 2.0 * cos_h / cos_ih;
  if (c_min <= 0.0) return a / c_max;
  return std::fmin(1.0 / c_min, a) / c_max;
}

// Plain V-cavity G (for tests and tools).
inline double vcavity_g(double cos_i, double cos_r, double cos_h, double cos_ih) {
  if (cos_ih <= 0.0) return 0.0;
  const double a = 2.0 * cos_h / cos_ih;
  return std::fmax(0.0, std::fmin(1.0, std::fmin(a * cos_r, a * cos_i)));
}

// Half-vector quantities of a geometry, computed without trigonometry.
struct HalfVector {
  double cos_h = 1.0;   // n.h
  double cos_ih = 1.0;  // w_i.h = w_r.h
  bool valid = false;   // false when w_i = -w_r (both grazing, opposite): h undefined
};
template <class Geom>
HalfVector half_vector_of(const Geom& g) {
  const double sx = g.wi.x + g.wr.x;
  const double sy = g.wi.y + g.wr.y;
  const double sz = g.wi.z + g.wr.z;
  const double len2 = sx * sx + sy * sy + sz * sz;
  HalfVector h;
  if (!(len2 > 1e-300)) return h;
  const double len = std::sqrt(len2);
  h.cos_h = sz / len;
  h.cos_ih = 0.5 * len;  // w_i.(w_i + w_r)/|w_i + w_r| = (1 + w_i.w_r)/|...| = |...|/2
  h.valid = true;
  return h;
}

}  // namespace microfacet
}  // namespace roadbrdf
