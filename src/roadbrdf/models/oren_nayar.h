// Oren-Nayar rough diffuse reflector (V-cavity facets with Gaussian slopes, Lambertian facets).
//
// Full model: M. Oren and S. K. Nayar, "Generalization of Lambert's reflectance model",
// SIGGRAPH 1994, eqs. 30 (direct term with C1, C2, C3) and 37 (two-bounce interreflection term,
// proportional to albedo^2); report eq. 3.5. Qualitative model: same paper, eq. 32 (A/B form).
// sigma is the standard deviation of the facet slope angle, in radians (report section 3.1.1).
// The report's eq. 3.5 matches the paper; the shadowing G term of its eq. 3.3 does not
// (docs/report-corrections.md), but that term does not enter this closed form.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/parameters.h"

namespace roadbrdf {

struct OrenNayar {
  static constexpr const char* kName = "oren-nayar";
  static constexpr bool kReadsAngles = true;  // alpha, beta = max, min(theta_i, theta_r) (model.h)
  static constexpr int kMaxParameters = 2;
  enum Parameter { kAlbedo = 0, kSigma = 1 };

  // Upper bound of sigma for the full model. The paper's fitted direct term goes negative near
  // grazing forward geometries (cos(dphi) = -1, theta_i = theta_r -> 90 deg) once sigma exceeds
  // about 0.67 rad (38 deg): there cos(dphi) C2 tan(beta) -> -(6/pi) C2_base, which overtakes C1.
  // 0.65 rad keeps f >= 0 at every geometry and albedo (checked by the non-negativity test) and
  // still covers the paper's fits (plaster 30 deg, white sand 35 deg). The qualitative form has
  // no such limit.
  static constexpr double kMaxSigmaFull = 0.65;
  static constexpr double kMaxSigmaQualitative = 1.5707963267948966;

  static std::vector<OptionInfo> options() {
    return {{"form",
             "full: direct + interreflection terms (eq. 30 + 37); qualitative: A/B form (eq. 32)",
             {"full", "qualitative"},
             "full"}};
  }
  static ModelDescription describe(const OptionSet& options) {
    const bool full = options.at("form") == "full";
    ModelDescription d;
    d.summary = full ? "Oren-Nayar rough diffuse, full model with interreflection"
                     : "Oren-Nayar rough diffuse, qualitative A/B model";
    d.citation = "Oren & Nayar, SIGGRAPH 1994, eqs. 30, 37 (full) and 32 (qualitative); report eq. 3.5";
    d.parameters = {
        {"albedo", "1", "albedo rho of the Lambertian facets", 0.5, 0.0, 1.0, true, !full},
        {"sigma", "rad", "standard deviation of the facet slope angle", 0.3, 0.0,
         full ? kMaxSigmaFull : kMaxSigmaQualitative, false, false},
    };
    // The closed forms are fits to the numerically integrated V-cavity model, not the model itself,
    // and do not conserve energy: with albedo 1 the black-sky albedo (albedo/hemisphere.h) exceeds 1
    // towards grazing sun (full form: from theta_i ~ 55 deg at sigma = 0.1, 1.014 at 89 deg; 1.044 at
    // sigma = 0.3, 89 deg; qualitative form: 1.0075 at sigma = 0.1, 89 deg). Checked in oren_nayar_test.
    d.energy_conserving = false;
    d.mirror_lobe = false;  // no specular term (facets are Lambertian)
    d.reduces_to = {{"lambert", "sigma = 0 (C1 = 1, C2 = C3 = 0, no interreflection)"}};
    d.grazing_zero = full ? "where both directions are grazing, unless cos(dphi) = -1 (tan(beta) and tan((alpha + "
                            "beta)/2) diverge; eqs. 30, 37)"
                          : "where both directions are grazing and cos(dphi) > 0 (tan(beta) diverges; eq. 32)";
    d.summary +=
        "; not energy conserving (fitted closed form: with albedo 1 the black-sky albedo exceeds 1 towards "
        "grazing sun, 1.044 at sigma = 0.3 rad and 89 deg)";
    return d;
  }
  explicit OrenNayar(const OptionSet& options) : full_(options.at("form") == "full") {}

  // Geometry-only factors of eqs. 30, 32 and 37 (alpha = max, beta = min of the zenith angles),
  // computed once per geometry (model.h, "prepared geometry").
  struct Prepared {
    double c = 0.0;         // cos(dphi)
    double tan_beta = 0.0;  // qualitative B factor: max(0, cos dphi) sin(alpha) tan(beta)
    double qualitative_b = 0.0;
    double sin_alpha = 0.0;             // C2 factor for cos(dphi) >= 0
    double sin_alpha_minus_cube = 0.0;  // C2 factor otherwise: sin(alpha) - (2 beta / pi)^3
    double c3_geometry = 0.0;           // (4 alpha beta / pi^2)^2
    double c3_weight = 0.0;             // (1 - |cos dphi|) tan((alpha + beta) / 2)
    double interreflection = 0.0;       // 1 - cos(dphi) (2 beta / pi)^2
    bool zero = false;                  // both directions grazing where the closed form diverges
  };

  Prepared prepare(const Geometry& g) const {
    Prepared q;
    const double alpha = std::fmax(g.theta_i, g.theta_r);
    const double beta = std::fmin(g.theta_i, g.theta_r);
    const double c = g.cos_delta_phi;
    q.c = c;
    q.tan_beta = std::tan(beta);
    q.sin_alpha = std::sin(alpha);
    q.qualitative_b = std::fmax(0.0, c) * q.sin_alpha * q.tan_beta;
    const double two_beta_over_pi = 2.0 * beta / kPi;
    q.sin_alpha_minus_cube = q.sin_alpha - ipow(two_beta_over_pi, 3);
    q.c3_geometry = sqr(4.0 * alpha * beta / (kPi * kPi));
    q.c3_weight = (1.0 - std::fabs(c)) * std::tan(0.5 * (alpha + beta));
    q.interreflection = 1.0 - c * sqr(two_beta_over_pi);
    if (g.grazing_i() && g.grazing_r()) grazing_limit(q);
    return q;
  }

  // Both directions grazing (alpha = beta = pi/2), approached with one of them held at 90 deg: with
  // alpha = pi/2 and beta = pi/2 - e, tan(beta) = 1/e + O(e), sin(alpha) = 1 and
  // (2 beta / pi)^3 = 1 - 6e/pi + O(e^2), so
  //   tan(beta) (sin(alpha) - (2 beta/pi)^3) -> 6/pi   (full form, cos dphi < 0: finite),
  //   tan(beta) sin(alpha) -> infinity                 (full form, cos dphi >= 0; qualitative, cos dphi > 0),
  //   (1 - |cos dphi|) tan((alpha + beta)/2) -> infinity unless |cos dphi| = 1 (C3 weight, full form).
  // The limit is finite only in the forward plane (cos dphi = -1) for the full form and wherever
  // cos dphi <= 0 for the qualitative form; elsewhere the value there is 0 (grazing_zero).
  void grazing_limit(Prepared& q) const {
    constexpr double kTiny = 1e-12;  // cos(dphi) at 90 deg evaluates to 6e-17, at 180 deg to -1
    q.c3_weight = 0.0;
    if (!full_) {
      q.qualitative_b = 0.0;
      q.zero = q.c > kTiny;
      return;
    }
    q.zero = q.c > -1.0 + kTiny;
    q.tan_beta = 6.0 * kInvPi;  // the product tan(beta) (sin(alpha) - (2 beta/pi)^3), with:
    q.sin_alpha_minus_cube = 1.0;
  }

  template <typename T>
  T operator()(const T* p, const Geometry& g) const {
    return (*this)(p, prepare(g));
  }

  // Parameter-only factors, computed once per parameter set (model.h, "coefficients").
  template <typename T>
  struct Coefficients {
    T rho_over_pi;      // rho / pi
    T c1;               // full: C1 of eq. 30; qualitative: A of eq. 32
    T c2_base;          // full: C2 without its geometric factor; qualitative: B of eq. 32
    T c3_base;          // C3 without its geometric factor
    T interreflection;  // eq. 37 without its geometric factor
  };

  template <typename T>
  Coefficients<T> coefficients(const T* p) const {
    const T& rho = p[kAlbedo];
    const T s2 = sqr(p[kSigma]);
    Coefficients<T> k{};
    k.rho_over_pi = rho * kInvPi;
    k.c1 = 1.0 - 0.5 * s2 / (s2 + 0.33);
    k.c2_base = 0.45 * s2 / (s2 + 0.09);
    if (full_) {
      k.c3_base = 0.125 * s2 / (s2 + 0.09);
      k.interreflection = 0.17 * sqr(rho) * kInvPi * s2 / (s2 + 0.13);
    }
    return k;
  }

  template <typename T>
  T operator()(const T* p, const Prepared& g) const {
    return (*this)(coefficients(p), g);
  }

  template <typename T>
  T operator()(const Coefficients<T>& k, const Prepared& g) const {
    if (g.zero) return T(0.0);
    if (!full_) return k.rho_over_pi * (k.c1 + k.c2_base * g.qualitative_b);
    const T c2 = g.c >= 0.0 ? T(k.c2_base * g.sin_alpha) : T(k.c2_base * g.sin_alpha_minus_cube);
    const T c3 = k.c3_base * g.c3_geometry;
    const T direct = k.rho_over_pi * (k.c1 + g.c * g.tan_beta * c2 + g.c3_weight * c3);
    const T interreflection = k.interreflection * g.interreflection;
    return direct + interreflection;
  }

 private:
  bool full_;
};

}  // namespace roadbrdf
