// Oren-Nayar rough diffuse reflector (V-cavity facets with Gaussian slopes, Lambertian facets).
//
// Full model: M. Oren and S. K. Nayar, "Generalization of Lambert's reflectance model",
// SIGGRAPH 1994, eqs. 30 (direct term with C1, C2, C3) and 37 (two-bounce interreflection term,
// proportional to albedo^2); report eq. 3.5. Qualitative model: same paper, eq. 32 (A/B form).
// sigma is the standard deviation of the facet slope angle, in radians (report section 3.1.1).
// The report's eq. 3.5 matches the paper; the shadowing G term of its eq. 3.3 does not (see README
// "known errors"), but that term does not enter this closed form.
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
    return {{"form", "full: direct + interreflection terms (eq. 30 + 37); qualitative: A/B form (eq. 32)",
             {"full", "qualitative"}, "full"}};
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
    return d;
  }
  explicit OrenNayar(const OptionSet& options) : full_(options.at("form") == "full") {}

  template <typename T>
  T operator()(const T* p, const Geometry& g) const {
    using std::sin;
    using std::tan;
    const T& rho = p[kAlbedo];
    const T s2 = sqr(p[kSigma]);
    const double alpha = std::fmax(g.theta_i, g.theta_r);
    const double beta = std::fmin(g.theta_i, g.theta_r);
    const double c = g.cos_delta_phi;
    const double tan_beta = std::tan(beta);
    if (!full_) {
      const T a = 1.0 - 0.5 * s2 / (s2 + 0.33);
      const T b = 0.45 * s2 / (s2 + 0.09);
      return rho * kInvPi * (a + b * (std::fmax(0.0, c) * std::sin(alpha) * tan_beta));
    }
    const double two_beta_over_pi = 2.0 * beta / kPi;
    const T c1 = 1.0 - 0.5 * s2 / (s2 + 0.33);
    const double sin_alpha = std::sin(alpha);
    const T c2_base = 0.45 * s2 / (s2 + 0.09);
    const T c2 = c >= 0.0 ? T(c2_base * sin_alpha) : T(c2_base * (sin_alpha - ipow(two_beta_over_pi, 3)));
    const T c3 = 0.125 * s2 / (s2 + 0.09) * sqr(4.0 * alpha * beta / (kPi * kPi));
    const T direct = rho * kInvPi *
                     (c1 + c * tan_beta * c2 + (1.0 - std::fabs(c)) * std::tan(0.5 * (alpha + beta)) * c3);
    const T interreflection = 0.17 * sqr(rho) * kInvPi * s2 / (s2 + 0.13) * (1.0 - c * sqr(two_beta_over_pi));
    return direct + interreflection;
  }

 private:
  bool full_;
};

}  // namespace roadbrdf
