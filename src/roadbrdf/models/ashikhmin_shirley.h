// Ashikhmin-Shirley anisotropic Phong BRDF.
//
// M. Ashikhmin and P. Shirley, "An anisotropic Phong BRDF model", J. Graphics Tools 5(2):25-32
// (2000), eqs. 4 (specular) and 5 (diffuse); report section 3.2, eq. 3.18.
//
//   f = f_s + f_d
//   f_s = sqrt((n_u + 1)(n_v + 1)) / (8 pi) * (n.h)^{(n_u (h.u)^2 + n_v (h.v)^2) / (1 - (n.h)^2)}
//         / ((h.k) max(n.k1, n.k2)) * F(h.k),       F(c) = R_s + (1 - R_s)(1 - c)^5 (Schlick)
//   f_d = 28 R_d / (23 pi) (1 - R_s) (1 - (1 - n.k1 / 2)^5) (1 - (1 - n.k2 / 2)^5)
//
// k1 = w_i, k2 = w_r, h the half vector, u = x axis and v = y axis of the surface frame, so
// (h.u)^2 / (1 - (n.h)^2) = cos^2(phi_h) and (h.v)^2 / (1 - (n.h)^2) = sin^2(phi_h) (report's form).
//
// Differences from the report's eq. 3.18 (the paper wins, docs/report-corrections.md):
// - The paper has no k_d / k_s weights: R_d and R_s are themselves the amplitudes (a k_s weight would
//   only rescale the specular term, which the Fresnel factor already sets). We implement the paper.
// - The diffuse term uses (1 - R_s), R_s = the specular reflectance at normal incidence (the same
//   R_s as in the Schlick factor), exactly as in the paper's eq. 5; the report's (1 - k_s F_0) is
//   this with k_s = 1 and F_0 = R_s.
//
// Energy: the paper claims the model conserves energy. The specular lobe is the paper's sampling
// density p(k2) = sqrt((n_u+1)(n_v+1))/(2 pi) (n.h)^e / (4 h.k) times F cos(theta_r)/max(cos theta_i,
// cos theta_r) <= F, so its directional albedo is <= 1; the diffuse term's directional albedo is
// R_d (1 - R_s)(1 - (1 - cos(theta_i)/2)^5) exactly (the 28/23 factor normalises it), and for narrow
// lobes the sum is <= 1 because (1 - c)^5 <= (1 - c/2)^5. For broad lobes the Fresnel factor is
// averaged over h and the bound is not a theorem. Numerically (rd = 1, R_s in [0, 1], n_u, n_v in
// [0, 300], theta_i in [0, 89] deg) the largest total directional albedo found is 0.987 (R_s = 1,
// n_u = n_v = 300, normal incidence; it tends to 1 for sharper mirrors); the tests check <= 1 on a subset.
//
// Guards: the exponent is 0/0 at h = n; its limit direction does not matter there because
// (n.h)^e = 1 for every finite e, so the lobe is 1 (and its derivative with respect to n_u, n_v is
// log(1) * ... = 0). When both directions are grazing (max(n.k1, n.k2) = 0) the specular term is a
// divergent 1/0 at the exact grazing mirror and 0 * ... elsewhere; it carries no power (cos(theta_r) = 0)
// and the model returns 0 there rather than inf.
#pragma once

#include <cmath>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/parameters.h"
#include "roadbrdf/models/fresnel.h"

namespace roadbrdf {

struct AshikhminShirley {
  static constexpr const char* kName = "ashikhmin-shirley";
  static constexpr int kMaxParameters = 4;
  enum Parameter { kRd = 0, kRs = 1, kNu = 2, kNv = 3 };
  static constexpr double kMaxExponent = 10000.0;

  static std::vector<OptionInfo> options() { return {}; }
  static ModelDescription describe(const OptionSet&) {
    ModelDescription d;
    d.summary = "Ashikhmin-Shirley anisotropic Phong: Schlick-Fresnel specular lobe + coupled non-Lambertian diffuse";
    d.citation =
        "Ashikhmin & Shirley, J. Graphics Tools 5(2) 2000, eqs. 4-5; report eq. 3.18 (no k_d/k_s weights, "
        "diffuse factor (1 - R_s) as in the paper)";
    d.parameters = {
        {"rd", "1",
         "diffuse reflectance R_d of the substrate (diffuse albedo at normal incidence is "
         "R_d (1 - R_s) 31/32)",
         0.3, 0.0, 1.0, true, true},
        {"rs", "1", "specular reflectance R_s at normal incidence (Schlick F_0; also sets the diffuse factor 1 - R_s)",
         0.05, 0.0, 1.0, true, false},
        {"nu", "1",
         "Phong-like exponent n_u of the specular lobe along the surface x axis (tangent u); "
         "larger = sharper",
         20.0, 0.0, kMaxExponent, false, false},
        {"nv", "1",
         "Phong-like exponent n_v of the specular lobe along the surface y axis (tangent v); "
         "n_v = n_u is isotropic",
         20.0, 0.0, kMaxExponent, false, false},
    };
    d.isotropic = false;                      // the lobe's exponent depends on the half vector's azimuth ...
    d.isotropic_when_equal = {{"nu", "nv"}};  // ... unless n_u = n_v (paper eq. 4)
    d.reciprocal = true;                      // symmetric in k1, k2 (max() and h.k1 = h.k2)
    d.energy_conserving = true;               // paper's claim; holds numerically (see the header comment)
    d.non_negative = true;
    // Both directions grazing: max(n.k1, n.k2) -> 0 in the specular lobe's denominator, which diverges
    // (a broad lobe, small n_u and n_v, keeps a finite numerator there); the value there is 0.
    d.grazing_zero = "where both directions are grazing (the specular lobe's 1/((h.k) max(n.k1, n.k2)) diverges)";
    return d;
  }
  explicit AshikhminShirley(const OptionSet&) {}

  template <typename T>
  T operator()(const T* p, const Geometry& g) const {
    using std::exp;
    using std::sqrt;
    const T& rd = p[kRd];
    const T& rs = p[kRs];
    const T& nu = p[kNu];
    const T& nv = p[kNv];
    const double ci = g.cos_theta_i();
    const double cr = g.cos_theta_r();

    // Diffuse term, paper eq. 5 (the cosine is halved inside the fifth power).
    const double di = 1.0 - ipow(1.0 - 0.5 * ci, 5);
    const double dr = 1.0 - ipow(1.0 - 0.5 * cr, 5);
    T diffuse = (28.0 / (23.0 * kPi)) * rd * (1.0 - rs) * (di * dr);

    // Specular term, paper eq. 4.
    const double max_cos = std::fmax(ci, cr);
    const Vec3 h = g.half_vector();
    const double hk = dot(g.wi, h);
    const double denominator = hk * max_cos;
    if (!(denominator > 0.0) || !(h.z > 0.0)) return diffuse;  // both grazing: no specular power
    const double sin2_h = h.x * h.x + h.y * h.y;               // 1 - (n.h)^2, from the components
    T lobe(1.0);                                               // h = n: (n.h)^e = 1 for every e
    if (sin2_h > 0.0) {
      const T exponent = (nu * (h.x * h.x) + nv * (h.y * h.y)) / sin2_h;
      lobe = exp(exponent * std::log(h.z));
    }
    const T norm = sqrt((nu + 1.0) * (nv + 1.0)) / (8.0 * kPi);
    const T fresnel = fresnel_schlick(T(hk), rs);
    return diffuse + norm * lobe * fresnel / denominator;
  }
};

}  // namespace roadbrdf
