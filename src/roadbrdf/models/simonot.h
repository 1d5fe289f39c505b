// Flat interface over a Lambertian background ("interfaced Lambertian" facet).
//
// L. Simonot, "Photometric model of diffuse surfaces described as a distribution of interfaced
// Lambertian facets", Appl. Opt. 48(30):5793-5801 (2009): the BRDF of one facet, i.e. a flat
// dielectric interface (relative index eta = eta_1 / eta_0) over a Lambertian background of intrinsic
// reflectance rho, with all the multiple reflections between background and interface summed.
// Report section 3.3, eq. 3.19:
//
//   f = f_d + f_s
//   f_d = rho (eta_0/eta_1)^2 (1 - R01(theta_i)) (1 - R01(theta_r)) / (pi (1 - rho r10))
//   f_s = R01(theta_i) delta(w_r - mirror(w_i)) / cos(theta_r)        (ideal specular part)
//   1 - r10 = (eta_0/eta_1)^2 (1 - r01),   r01 = int_0^{pi/2} R01(theta) sin(2 theta) d theta
//
// R01 is the exact unpolarised Fresnel reflectance (fresnel.h). The report's r01 integral lacks the
// d theta (docs/report-corrections.md); it is the hemispherical (Lambertian-illumination)
// reflectance of the interface seen from medium 0, r01 = int_0^1 R01(mu) 2 mu d mu, evaluated here by a
// fixed 64-node Gauss-Legendre rule in mu = cos(theta) so that it is differentiable in eta (Jets pass
// through). The integrand is analytic on [0, 1] for eta >= 1 (branch points at mu = +-i sqrt(eta^2 - 1)),
// so the rule is accurate to rounding for eta in the bounds (checked against the closed form of the
// diffuse Fresnel reflectance in the tests).
//
// Only the flat facet is implemented (the report's eq. 3.19); Simonot's distribution of rough
// interfaced facets (roughness parameter) is not. The smooth part f_d is returned by operator(); the
// ideal specular part by delta_reflectance() = R01(theta_i).
//
// Energy: the directional albedo is R01(theta_i) + (1 - R01(theta_i)) rho (1 - r10) / (1 - rho r10),
// <= 1 for rho <= 1 and = 1 for rho = 1 (a flat interface over a white Lambertian absorbs nothing).
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/parameters.h"
#include "roadbrdf/core/quadrature.h"
#include "roadbrdf/models/fresnel.h"

namespace roadbrdf {

namespace simonot_detail {

inline constexpr int kQuadratureNodes = 64;

// Gauss-Legendre rule on [0, 1] in mu, computed once.
inline const QuadratureRule& mu_rule() {
  static const QuadratureRule rule = gauss_legendre(kQuadratureNodes, 0.0, 1.0);
  return rule;
}

// r01 = int_0^1 R01(mu, eta) 2 mu d mu: reflectance of the interface under Lambertian illumination
// from medium 0 (Simonot 2009; report section 3.3 with the missing d theta restored).
template <typename T>
T hemispherical_fresnel(const T& eta) {
  const QuadratureRule& rule = mu_rule();
  T sum(0.0);
  for (int k = 0; k < kQuadratureNodes; ++k) {
    sum += (2.0 * rule.weights[k] * rule.nodes[k]) * fresnel_dielectric(T(rule.nodes[k]), eta);
  }
  return sum;
}

}  // namespace simonot_detail

struct Simonot {
  static constexpr const char* kName = "simonot";
  static constexpr int kMaxParameters = 2;
  enum Parameter { kAlbedo = 0, kIor = 1 };

  static std::vector<OptionInfo> options() { return {}; }
  static ModelDescription describe(const OptionSet&) {
    ModelDescription d;
    d.summary =
        "Flat dielectric interface over a Lambertian background (Simonot interfaced Lambertian facet), "
        "with ideal specular part";
    d.citation =
        "Simonot, Appl. Opt. 48(30):5793 (2009), flat interfaced Lambertian facet; report eq. 3.19 "
        "(r01 integral with d theta restored)";
    d.parameters = {
        {"albedo", "1", "intrinsic reflectance rho of the Lambertian background under the interface", 0.5, 0.0, 1.0,
         true, false},
        {"ior", "1", "relative refractive index eta_1/eta_0 of the binder (medium 1) to the upper medium 0", 1.5, 1.0,
         3.0, true, false},
    };
    d.reciprocal = true;
    d.energy_conserving = true;  // albedo = R01 + (1 - R01) rho (1 - r10)/(1 - rho r10) <= 1 for rho <= 1
    d.non_negative = true;
    d.has_delta = true;
    d.reduces_to = {{"lambert", "ior = 1 (no interface: R01 = r10 = 0, f = rho/pi)"}};
    return d;
  }
  explicit Simonot(const OptionSet&) {}

  // Geometry-only data (model.h, "prepared geometry"): the two cosines.
  struct Prepared {
    double cos_i = 0.0, cos_r = 0.0;
  };
  Prepared prepare(const Geometry& g) const { return {g.cos_theta_i(), g.cos_theta_r()}; }

  // Parameter-only factors (model.h, "coefficients"): the hemispherical Fresnel reflectance r01 is an
  // integral over the interface's directions, 64 Fresnel terms, so it is computed once per parameter
  // set rather than at every geometry.
  template <typename T>
  struct Coefficients {
    T eta;
    T rho_over_eta2;  // rho (eta_0 / eta_1)^2
    T denominator;    // pi (1 - rho r10)
  };

  template <typename T>
  Coefficients<T> coefficients(const T* p) const {
    const T& rho = p[kAlbedo];
    const T& eta = p[kIor];
    const T inv_eta2 = 1.0 / (eta * eta);  // (eta_0 / eta_1)^2
    const T r01 = simonot_detail::hemispherical_fresnel(eta);
    const T r10 = 1.0 - inv_eta2 * (1.0 - r01);
    return {eta, rho * inv_eta2, kPi * (1.0 - rho * r10)};
  }

  // f = rho (eta_0/eta_1)^2 (1 - R(theta_i)) (1 - R(theta_r)) / (pi (1 - rho r10)).
  template <typename T>
  T operator()(const Coefficients<T>& k, const Prepared& g) const {
    const T ti = 1.0 - fresnel_dielectric(T(g.cos_i), k.eta);
    const T tr = 1.0 - fresnel_dielectric(T(g.cos_r), k.eta);
    return k.rho_over_eta2 * ti * tr / k.denominator;
  }

  template <typename T>
  T operator()(const T* p, const Prepared& g) const {
    return (*this)(coefficients(p), g);
  }

  template <typename T>
  T operator()(const T* p, const Geometry& g) const {
    return (*this)(p, prepare(g));
  }

  // Ideal specular part: R01(theta_i), the Fresnel reflectance of the flat interface.
  double delta_reflectance(const double* p, double cos_theta_i) const {
    return fresnel_dielectric(cos_theta_i, p[kIor]);
  }
};

}  // namespace roadbrdf
