// Rahman-Pinty-Verstraete (RPV) semi-empirical BRDF model, the standard parametric model for bare soils
// and sand in remote sensing.
//
// H. Rahman, B. Pinty and M. M. Verstraete, "Coupled surface-atmosphere reflectance (CSAR) model 2.
// Semiempirical surface model usable with NOAA advanced very high resolution radiometer data",
// JGR 98(D11):20791-20801 (1993). The bidirectional reflectance FACTOR is
//   rho = rho0 M(k) F(g) [1 + R(G)]
//   M(k)     = cos^(k-1)(theta_i) cos^(k-1)(theta_r) / (cos theta_i + cos theta_r)^(1-k)   (Minnaert-like)
//   F(g)     = (1 - Theta^2) / [1 + Theta^2 - 2 Theta cos(pi - g)]^(3/2)                 (Henyey-Greenstein)
//   1 + R(G) = 1 + (1 - rho0) / (1 + G)                                                   (hot spot)
//   G        = sqrt(tan^2 theta_i + tan^2 theta_r - 2 tan theta_i tan theta_r cos phi)
//   cos g    = cos theta_i cos theta_r + sin theta_i sin theta_r cos phi
// and this model returns the BRDF = rho / pi [sr^-1].
//
// Angle conventions. In the paper phi is the relative azimuth with phi = 0 when sun and viewer are on the
// same side (backscattering): there, for theta_i = theta_r, G = 0 (the hot spot, 1 + R = 2 - rho0) and
// cos g = 1, so g is the phase angle between the directions to the sun and to the viewer (g = 0 at the hot
// spot). roadbrdf's dphi = phi_r - phi_i with both directions pointing away from the surface has the same
// origin (dphi = 0 is the retro side), so cos phi = cos(dphi) and cos g = w_i . w_r. With cos(pi - g) =
// -cos g the phase function is F = (1 - Theta^2) / (1 + 2 Theta cos g + Theta^2)^(3/2): Theta < 0 makes
// F largest at g = 0, i.e. predominantly backward scattering. (The
// I3RC intercomparison's reference code has the same origin: hot spot at mu2 = mu1, phi = 0, and
// F with + 2 Theta cos g.) Implementations that measure phi from the forward side write -cos phi instead.
//
// Properties:
//   - reciprocal and azimuthally isotropic: every factor is symmetric in (theta_i, theta_r) and depends on
//     the azimuths only through cos(dphi).
//   - non-negative for rho0 in [0, 1] and |Theta| < 1 (every factor is >= 0).
//   - NOT energy conserving: for k < 1 the factor M diverges like cos^(k-1) towards grazing directions, and
//     nothing bounds the albedo by 1 (the model is a fitting form, not a radiative-transfer solution).
//   - Exactly grazing directions (cos theta <= kGrazingCosine; 90 deg read from a file gives cos =
//     6.1e-17): for k > 1 the limit of M is 0, for k < 1 M diverges, and the value returned there is 0 in
//     both cases; for k = 1 exactly M = 1 and the formula is evaluated as it stands (its limit: G grows
//     without bound, so 1 + R -> 1).
#pragma once

#include <cmath>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/parameters.h"

namespace roadbrdf {

struct RahmanPintyVerstraete {
  static constexpr const char* kName = "rpv";
  static constexpr int kMaxParameters = 3;
  enum Parameter { kRho0 = 0, kK = 1, kTheta = 2 };

  // A direction whose cosine is at most this is exactly grazing (90 deg read from a file: cos = 6.1e-17);
  // the next angles anyone measures (89.99999 deg: cos = 1.7e-7) stay far above it.
  static constexpr double kGrazingCosine = 1e-12;

  static std::vector<OptionInfo> options() { return {}; }
  static ModelDescription describe(const OptionSet&) {
    ModelDescription d;
    d.summary =
        "Rahman-Pinty-Verstraete semi-empirical model for soils and sand (BRDF = BRF/pi); not energy conserving "
        "(k < 1 diverges towards grazing directions, 0 at exactly 90 deg)";
    d.citation = "Rahman, Pinty & Verstraete, JGR 98(D11):20791 (1993)";
    d.parameters = {
        {"rho0", "1", "amplitude rho0 of the bidirectional reflectance factor (also sets the hot-spot height)", 0.3,
         0.0, 1.0, true, false},
        {"k", "1",
         "Minnaert-like exponent: k < 1 bowl-shaped (brighter towards grazing), k > 1 bell-shaped, k = 1 flat", 0.8,
         0.0, 2.0, true, false},
        {"Theta", "1",
         "Henyey-Greenstein asymmetry parameter of F(g): < 0 backward (soils, sand), > 0 forward scattering", -0.1,
         -0.95, 0.95, true, false},
    };
    d.reciprocal = true;
    d.energy_conserving = false;  // see the header comment
    d.grazing_zero =
        "at any grazing direction when k != 1 (for k < 1 the BRDF diverges like cos^(k-1) theta; for k > 1 0 is the "
        "limit)";
    d.non_negative = true;
    d.mirror_lobe = false;  // F(g)'s forward lobe points below the horizon (mirror_lobe_test, Theta = 0.95)
    return d;
  }
  explicit RahmanPintyVerstraete(const OptionSet&) {}

  // Geometry-only factors, computed once per geometry (model.h, "prepared geometry").
  struct Prepared {
    bool grazing = false;          // either direction exactly grazing
    double log_cos_product = 0.0;  // log(cos theta_i cos theta_r)
    double log_cos_sum = 0.0;      // log(cos theta_i + cos theta_r)
    double cos_phase = 0.0;        // cos g = w_i . w_r
    double hot_spot = 0.0;         // 1 / (1 + G)
  };

  Prepared prepare(const Geometry& g) const {
    Prepared q;
    const double ci = g.cos_theta_i(), cr = g.cos_theta_r();
    q.grazing = ci <= kGrazingCosine || cr <= kGrazingCosine;
    const double ci_clamped = std::fmax(ci, kGrazingCosine), cr_clamped = std::fmax(cr, kGrazingCosine);
    q.log_cos_product = std::log(ci_clamped) + std::log(cr_clamped);
    q.log_cos_sum = std::log(ci_clamped + cr_clamped);
    q.cos_phase = dot(g.wi, g.wr);
    // G from the direction vectors alone (the angle fields are not read, model.h): tan theta = |w_xy| / w_z
    // and tan theta_i tan theta_r cos(dphi) = (w_i,xy . w_r,xy) / (cos theta_i cos theta_r). G^2 =
    // |w_i,xy / cos_i - w_r,xy / cos_r|^2 >= 0, computed as that difference vector's squared length.
    const double dx = g.wi.x / ci_clamped - g.wr.x / cr_clamped, dy = g.wi.y / ci_clamped - g.wr.y / cr_clamped;
    const double g2 = dx * dx + dy * dy;
    q.hot_spot = 1.0 / (1.0 + std::sqrt(g2));
    return q;
  }

  template <typename T>
  T operator()(const T* p, const Geometry& g) const {
    return (*this)(p, prepare(g));
  }

  template <typename T>
  T operator()(const T* p, const Prepared& q) const {
    using std::exp;
    using std::sqrt;
    const T& rho0 = p[kRho0];
    const T& k = p[kK];
    const T& theta = p[kTheta];
    // Exactly grazing: M -> 0 for k > 1, diverges for k < 1 (value 0, declared); k = 1 has M = 1.
    if (q.grazing && scalar_value(k) != 1.0) return T(0.0);
    // M(k) = (cos_i cos_r)^(k-1) (cos_i + cos_r)^(k-1), through logarithms of the (double) cosines.
    const T minnaert = exp((k - 1.0) * (q.log_cos_product + q.log_cos_sum));
    const T denominator = 1.0 + 2.0 * theta * q.cos_phase + theta * theta;
    const T phase = (1.0 - theta * theta) / (denominator * sqrt(denominator));
    const T hot_spot = 1.0 + (1.0 - rho0) * q.hot_spot;
    return rho0 * minnaert * phase * hot_spot * kInvPi;
  }
};

}  // namespace roadbrdf
