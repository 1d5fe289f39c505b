// Retro-Phong BRDF for retroreflective road markings (glass beads).
//
// R. M. Spieringhs, J. Audenaert, K. Smet, I. Heynderickx, P. Hanselaer, "Road marking BRDF model
// applicable for a wide range of incident illumination conditions", JOSA A 40(3):590-601 (2023);
// report section 3.7, eq. 3.27 (the paper itself was not reachable; the report is the specification,
// see the reference domain notes section 5):
//
//   f = k_d / pi + k_s(theta_i) (n+2)/(2 pi) max(0, w_is . w_r)^n + k_r(theta_i) (n+2)/(2 pi) max(0, w_i . w_r)^n
//   k_r(theta_i) = k1 (1 - cos theta_i) + k2,      k_s(theta_i) = k3 exp(k4 (1 - cos theta_i))
//
// w_is = mirror direction of w_i (-x, -y, z): the specular lobe; w_i . w_r = 1 in the exact retro
// direction (w_r = w_i). The report prints the lobes without max(0, .); with the even exponents of the
// published fits (24, 68) a negative cosine would give a spurious positive lobe on the far side, so the
// cosines are clamped at 0 as in every Phong lobe (the lobes are meant to vanish away from their axis).
//
// Not reciprocal: k_s and k_r depend on theta_i only, so f(w_i, w_r) != f(w_r, w_i) whenever
// theta_i != theta_r (the cosines are symmetric, the weights are not). This is intended by the
// authors: the weights model the entrance-angle dependence of bead retroreflection.
// Not energy conserving in general: each (n+2)/(2 pi) lobe about an axis at zenith angle theta_a has
// directional albedo of at most cos(theta_a) <= 1 (less where it is cut by the horizon), so the albedo
// is <= k_d + k_s(theta_i) + k_r(theta_i); the paper's constraint k_d + k_s + k_r < 1 is not enforced by
// the parameter bounds (and k_s grows exponentially with 1 - cos theta_i).
#pragma once

#include <cmath>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/parameters.h"

namespace roadbrdf {

struct RetroPhong {
  static constexpr const char* kName = "retro-phong";
  static constexpr int kMaxParameters = 6;
  enum Parameter { kKd = 0, kN = 1, kK1 = 2, kK2 = 3, kK3 = 4, kK4 = 5 };

  static std::vector<OptionInfo> options() { return {}; }
  static ModelDescription describe(const OptionSet&) {
    ModelDescription d;
    d.summary =
        "Retro-Phong road-marking BRDF: Lambertian + specular and retro Phong lobes with "
        "incidence-dependent weights (not reciprocal)";
    d.citation = "Spieringhs et al., JOSA A 40(3):590 (2023); report eq. 3.27 (lobes clamped at 0)";
    // Defaults: the report's fit of SWARCO Limboplast D480 with Megalux 0.6-1.5 KT14.
    d.parameters = {
        {"kd", "1", "diffuse albedo k_d (f_d = k_d/pi)", 0.620, 0.0, 1.0, true, true},
        {"n", "1", "Phong exponent n shared by the specular and retro lobes (normalised by (n+2)/(2 pi))", 24.0, 0.0,
         1000.0, false, false},
        {"k1", "1", "retro weight slope: k_r = k1 (1 - cos theta_i) + k2", 0.158, 0.0, 1.0, true, true},
        {"k2", "1", "retro weight at normal incidence: k_r = k1 (1 - cos theta_i) + k2", 0.0145, 0.0, 1.0, true, true},
        {"k3", "1", "specular weight at normal incidence: k_s = k3 exp(k4 (1 - cos theta_i))", 0.00133, 0.0, 1.0, true,
         true},
        {"k4", "1", "specular weight growth rate: k_s = k3 exp(k4 (1 - cos theta_i))", 5.47, -20.0, 20.0, false, false},
    };
    // n = 1000 is the default fitting range; retroreflective tapes and beads have far narrower
    // lobes (the CEA 3M tape fits stop at 1000): any n >= 0 is a Phong lobe, `fit --bounds n=LO:HI`
    // may go up to 1e6 (a lobe of half-width ~0.1 deg).
    d.physical_bounds = {{"n", {0.0, 1.0e6}}};
    d.reciprocal = false;         // weights depend on theta_i only
    d.energy_conserving = false;  // k_d + k_s + k_r < 1 is not enforced
    d.non_negative = true;
    d.reduces_to = {{"lambert", "k1 = k2 = k3 = 0 (no lobes; kd is the albedo)"}};
    return d;
  }
  explicit RetroPhong(const OptionSet&) {}

  template <typename T>
  T operator()(const T* p, const Geometry& g) const {
    using std::exp;
    using std::pow;
    const T& n = p[kN];
    const double one_minus_cos = 1.0 - g.cos_theta_i();
    const T kr = p[kK1] * one_minus_cos + p[kK2];
    const T ks = p[kK3] * exp(p[kK4] * one_minus_cos);
    const T norm = (n + 2.0) * (0.5 * kInvPi);
    T f = p[kKd] * kInvPi;
    const double cos_specular = dot(mirror_direction(g.wi), g.wr);
    const double cos_retro = dot(g.wi, g.wr);
    // pow(c, n) for c > 0 only: the clamped lobe and its gradient are 0 elsewhere.
    if (cos_specular > 0.0) f += ks * norm * pow(std::fmin(cos_specular, 1.0), n);
    if (cos_retro > 0.0) f += kr * norm * pow(std::fmin(cos_retro, 1.0), n);
    return f;
  }
};

}  // namespace roadbrdf
