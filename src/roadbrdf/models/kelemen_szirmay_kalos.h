// Kelemen & Szirmay-Kalos coupled specular-matte BRDF.
//
// C. Kelemen and L. Szirmay-Kalos, "A microfacet based coupled specular-matte BRDF model with
// importance sampling", Eurographics 2001 short presentations; report eq. 3.20 and section 3.4.
//
//   f = f_s + f_matte
//   f_s     = P_H(h) F(l.h) / (4 (l.h)^2)                                  (report section 3.4)
//   f_matte = rho_d (1 - rho_s(theta_i)) (1 - rho_s(theta_r)) / (pi (1 - rho_s_bar))
//   rho_s(theta)  = int f_s cos theta_r dw_r   (directional albedo of the specular part)
//   rho_s_bar     = 2 int_0^1 rho_s(mu) mu dmu (its cosine-weighted average)
//
// Specular form. The model replaces Torrance-Sparrow's G / (cos_i cos_r) by 1 / (l.h)^2 (i.e. an
// implicit G = 2 cos_i cos_r / (1 + l.r), since 1 + l.r = 2 (l.h)^2) and uses P_H, the density of the
// half vector, in place of D. The report's section 3.4 prints this form, D F / (4 cos^2 theta'_i),
// with the paper's three densities (eqs. 3.21-3.23); the same implicit G is in the wdas/brdf
// "g_kelemen" reference (domain notes section 5). We could not re-read the paper's own equations
// here, so the form follows the report, with these densities:
//   beckmann: report eq. 3.8, i.e. eq. 3.21 with the missing 1/pi restored
//             (docs/report-corrections.md): exp(-tan^2/a^2) / (pi a^2 cos^4).
//   ward:     report eq. 3.22 as printed: exp(-tan^2/a^2) / (pi a^2 cos^3); a solid-angle density of h.
//   phong:    report eq. 3.23 as printed: (m + 1)/(2 pi) cos^m, a solid-angle density of h, with the
//             exponent from the roughness by Walter 2007 eq. 30's relation m = 2/a^2 - 2 (so that one
//             roughness axis serves all three; a in (0, 1]).
// Fresnel: Schlick (report eq. 2.15) with F0 = ((n - 1)/(n + 1))^2. Because Schlick is affine in F0,
// rho_s = F0 A(mu, a) + B(mu, a) exactly, with A, B computed by quadrature in half-vector space and
// tabulated once per distribution (kelemen_szirmay_kalos_albedo.h: accurate to ~1e-6 down to
// grazing incidence, where the table gives way to direct quadrature).
// The coupling makes the directional albedo rho_s + rho_d (1 - rho_s) <= 1: energy conserving.
#pragma once

#include <string>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/parameters.h"
#include "roadbrdf/models/fresnel.h"
#include "roadbrdf/models/kelemen_szirmay_kalos_albedo.h"
#include "roadbrdf/models/microfacet.h"

namespace roadbrdf {

struct KelemenSzirmayKalos {
  static constexpr const char* kName = "kelemen-szirmay-kalos";
  static constexpr int kMaxParameters = 3;
  enum Parameter { kAlbedo = 0, kRoughness = 1, kIor = 2 };

  static std::vector<OptionInfo> options() {
    return {{"distribution",
             "half-vector density of the specular term: beckmann (eq. 3.8), ward (eq. 3.22), phong (eq. 3.23, "
             "m = 2/roughness^2 - 2)",
             {"beckmann", "ward", "phong"},
             "beckmann"}};
  }
  static ksk::Distribution distribution_of(const OptionSet& o) {
    const std::string& d = o.at("distribution");
    return d == "ward"    ? ksk::Distribution::kWard
           : d == "phong" ? ksk::Distribution::kPhong
                          : ksk::Distribution::kBeckmann;
  }
  static ModelDescription describe(const OptionSet& options) {
    const ksk::Distribution dist = distribution_of(options);
    ModelDescription d;
    d.summary = "Kelemen & Szirmay-Kalos energy-coupled specular + matte microfacet model";
    d.citation = "Kelemen & Szirmay-Kalos, Eurographics 2001 short paper; report eq. 3.20, section 3.4";
    d.parameters = {
        {"albedo", "1", "matte albedo rho_d (albedo of the multiply scattered / re-emitted part)", 0.5, 0.0, 1.0, true,
         true},
        {"roughness", "1",
         dist == ksk::Distribution::kPhong
             ? "alpha: roughness; Phong exponent m = 2/alpha^2 - 2 (Walter 2007 eq. 30 equivalence to Beckmann RMS "
               "slope)"
             : "alpha: RMS slope of the microfacets (Beckmann/Ward width parameter, dimensionless)",
         0.3, ksk::kAlphaMin, ksk::kAlphaMax, false, false},
        {"ior", "1", "relative refractive index n of the facets; Schlick F0 = ((n-1)/(n+1))^2", 1.5, 1.0, 3.0, true,
         false},
    };
    d.energy_conserving = true;
    // Both directions grazing in the forward plane: the specular term's 1/(4 (l.h)^2) diverges as the
    // half vector becomes undefined; the value there is 0 (declared) wherever both are grazing.
    d.grazing_zero = "where both directions are grazing (the specular term's 1/(4 (l.h)^2) diverges forward)";
    return d;
  }

  // The albedo table is built on the first evaluation (not here), so that listing or composing
  // models stays instantaneous.
  explicit KelemenSzirmayKalos(const OptionSet& options) : dist_(distribution_of(options)) {}

  template <typename T>
  T operator()(const T* p, const Geometry& g) const {
    if (g.grazing_i() && g.grazing_r()) return T(0.0);  // grazing_zero
    const T& alpha = p[kRoughness];
    const T f0 = fresnel_f0(p[kIor]);
    const microfacet::HalfVector h = microfacet::half_vector_of(g);
    T specular(0.0);
    if (h.valid) {
      const double lh = h.cos_ih;
      specular = ksk::halfway_density(dist_, h.cos_h, alpha) * fresnel_schlick(T(lh), f0) / (4.0 * lh * lh);
    }
    const ksk::AlbedoTable& table = ksk::albedo_table(dist_);
    T rho_i, rho_r, rho_bar;
    ksk::specular_albedos(table, g.wi.z, g.wr.z, alpha, f0, &rho_i, &rho_r, &rho_bar);
    const T matte = p[kAlbedo] * (1.0 - rho_i) * (1.0 - rho_r) / (kPi * (1.0 - rho_bar));
    return specular + matte;
  }

  ksk::Distribution distribution() const { return dist_; }

 private:
  ksk::Distribution dist_;
};

}  // namespace roadbrdf
