// MODIS RossThick-LiSparseR kernel-driven BRDF model (RTLSR).
//
// Semi-empirical linear kernel model of the MODIS BRDF/albedo product (MCD43): the bidirectional
// reflectance FACTOR is
//   BRF = f_iso + f_vol K_vol + f_geo K_geo,
// and this model returns the BRDF = BRF / pi [sr^-1] (domain notes sections 0 and 3).
// RossThick volume-scattering kernel: Roujean, Leroy & Deschamps, JGR 97(D18):20455 (1992);
// Wanner, Li & Strahler, JGR 100(D10):21077 (1995). LiSparse-Reciprocal geometric-optical kernel:
// Li & Strahler, IEEE TGRS 30:276 (1992); reciprocal form and MODIS constants h/b = 2, b/r = 1:
// Lucht, Schaaf & Strahler, IEEE TGRS 38(2):977-998 (2000); MODIS BRDF/Albedo ATBD (Strahler et al.).
// With theta_s = theta_i (sun), theta_v = theta_r (view), phi = phi_r - phi_i (0 = backscatter / hot spot,
// the library's convention), cos xi = cos ts cos tv + sin ts sin tv cos phi (phase angle, xi = 0 at the
// hot spot):
//   K_vol = [(pi/2 - xi) cos xi + sin xi] / (cos ts + cos tv) - pi/4
//   b/r = 1 makes the primed angles equal to the true ones;
//   D^2 = tan^2 ts + tan^2 tv - 2 tan ts tan tv cos phi
//   cos t = (h/b) sqrt(D^2 + (tan ts tan tv sin phi)^2) / (sec ts + sec tv), clamped to [0, 1]
//   O = (1/pi)(t - sin t cos t)(sec ts + sec tv)
//   K_geo = O - sec ts - sec tv + (1/2)(1 + cos xi) sec ts sec tv
// The white-sky integrals of the kernels are 0.189184 (K_vol) and -1.377622 (K_geo) (ATBD; checked by an
// independent quadrature in tests/models/ross_li_test.cpp).
//
// Properties:
//   - reciprocal: both kernels are symmetric in (ts, tv) (every term is), and depend on phi only via cos phi
//     and sin^2 phi.
//   - NOT non-negative: K_vol >= 1/2 - pi/4 but K_geo is unbounded below towards grazing view or sun
//     (e.g. ts = 0: K_geo ~ -sec(tv)/2 as tv -> 90 deg), so for any f_geo > 0 the BRF becomes negative at
//     grazing geometries unless f_iso is large; no box bounds on (f_iso, f_vol, f_geo) with f_geo > 0 can
//     prevent it. The kernels are a fitting basis for view/sun zenith angles up to ~60-70 deg.
//   - NOT energy conserving: nothing bounds the albedo f_iso + f_vol K_vol_bs + f_geo K_geo_bs by 1.
//   - Exactly grazing directions (theta = 90 deg): K_geo diverges like sec(theta) (with ts fixed,
//     K_geo ~ sec(tv) [(1 + sin ts cos phi) sec(ts) / 2 - 1] as tv -> 90 deg; the overlap term vanishes
//     there) and K_vol like 1 / (cos ts + cos tv) when both are grazing, so the model is 0 at any
//     grazing direction (declared in grazing_zero), as no single finite value is the limit for every
//     weight. Just inside, the cosines are floored at kMinCosine so that the (huge) values stay finite.
// Parameter bounds: non-negative kernel weights, as in the MCD43A1 product; upper bound 2 leaves room
// above the BRF of the brightest natural surfaces (~1).
#pragma once

#include <cmath>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/parameters.h"

namespace roadbrdf {

struct RossLi {
  static constexpr const char* kName = "ross-li";
  static constexpr int kMaxParameters = 3;
  enum Parameter { kIso = 0, kVol = 1, kGeo = 2 };

  static constexpr double kMinCosine = 1e-9;
  static constexpr double kHeightToWidth = 2.0;  // h/b of the MODIS LiSparseR kernel (b/r = 1)

  static std::vector<OptionInfo> options() { return {}; }
  static ModelDescription describe(const OptionSet&) {
    ModelDescription d;
    d.summary = "MODIS RossThick-LiSparseR kernel model (BRDF = BRF/pi; h/b = 2, b/r = 1)";
    d.citation =
        "Lucht, Schaaf & Strahler, IEEE TGRS 38:977 (2000); Wanner, Li & Strahler, JGR 100:21077 (1995); "
        "Roujean et al., JGR 97:20455 (1992); MODIS BRDF/Albedo ATBD";
    d.parameters = {
        {"f_iso", "1", "isotropic kernel weight (BRF units: BRF = f_iso + f_vol K_vol + f_geo K_geo)", 0.1, 0.0, 2.0,
         true, true},
        {"f_vol", "1", "RossThick volume-scattering kernel weight (BRF units)", 0.05, 0.0, 2.0, true, true},
        {"f_geo", "1", "LiSparse-Reciprocal geometric-optical kernel weight (BRF units)", 0.01, 0.0, 2.0, true, true},
    };
    d.reciprocal = true;
    d.energy_conserving = false;
    d.non_negative = false;  // K_geo -> -infinity towards grazing angles (see the header comment)
    d.mirror_lobe = false;   // volume and geometric kernels: smooth, the hot spot is at backscatter
    d.grazing_zero = "at any grazing direction (K_geo diverges like sec theta, K_vol like 1/(cos ts + cos tv))";
    return d;
  }
  explicit RossLi(const OptionSet&) {}

  // Kernel values for the sun (incident) and view (reflected) directions of g.
  struct Kernels {
    double vol = 0.0;
    double geo = 0.0;
  };

  static Kernels kernels(const Geometry& g) {
    const double cos_s = std::fmax(g.cos_theta_i(), kMinCosine);
    const double cos_v = std::fmax(g.cos_theta_r(), kMinCosine);
    const double sin_s = std::sqrt(std::fmax(0.0, 1.0 - cos_s * cos_s));
    const double sin_v = std::sqrt(std::fmax(0.0, 1.0 - cos_v * cos_v));
    const double cos_phi = g.cos_delta_phi;
    const double sin2_phi = std::fmax(0.0, 1.0 - cos_phi * cos_phi);

    Kernels k;
    // RossThick.
    const double cos_xi = std::fmax(-1.0, std::fmin(1.0, cos_s * cos_v + sin_s * sin_v * cos_phi));
    const double xi = std::acos(cos_xi);
    const double sin_xi = std::sqrt(std::fmax(0.0, 1.0 - cos_xi * cos_xi));
    k.vol = ((0.5 * kPi - xi) * cos_xi + sin_xi) / (cos_s + cos_v) - 0.25 * kPi;

    // LiSparse-Reciprocal (b/r = 1: primed angles = true angles, cos xi' = cos xi).
    const double tan_s = sin_s / cos_s;
    const double tan_v = sin_v / cos_v;
    const double sec_s = 1.0 / cos_s;
    const double sec_v = 1.0 / cos_v;
    const double d2 = std::fmax(0.0, tan_s * tan_s + tan_v * tan_v - 2.0 * tan_s * tan_v * cos_phi);
    const double cross = tan_s * tan_v;
    const double cos_t = std::fmin(1.0, kHeightToWidth * std::sqrt(d2 + cross * cross * sin2_phi) / (sec_s + sec_v));
    const double t = std::acos(cos_t);
    const double sin_t = std::sqrt(std::fmax(0.0, 1.0 - cos_t * cos_t));
    const double overlap = kInvPi * (t - sin_t * cos_t) * (sec_s + sec_v);
    k.geo = overlap - sec_s - sec_v + 0.5 * (1.0 + cos_xi) * sec_s * sec_v;
    return k;
  }

  template <typename T>
  T operator()(const T* p, const Geometry& g) const {
    if (g.grazing_i() || g.grazing_r()) return T(0.0);
    const Kernels k = kernels(g);
    return (p[kIso] + p[kVol] * k.vol + p[kGeo] * k.geo) * kInvPi;
  }
};

}  // namespace roadbrdf
