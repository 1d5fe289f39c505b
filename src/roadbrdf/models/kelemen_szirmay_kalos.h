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
//   beckmann: report eq. 3.8, i.e. eq. 3.21 with the missing 1/pi restored (reference README
//             "known errors"): exp(-tan^2/a^2) / (pi a^2 cos^4).
//   ward:     report eq. 3.22 as printed: exp(-tan^2/a^2) / (pi a^2 cos^3); a solid-angle density of h.
//   phong:    report eq. 3.23 as printed: (m + 1)/(2 pi) cos^m, a solid-angle density of h, with the
//             exponent from the roughness by Walter 2007 eq. 30's relation m = 2/a^2 - 2 (so that one
//             roughness axis serves all three; a in (0, 1]).
// Fresnel: Schlick (report eq. 2.15) with F0 = ((n - 1)/(n + 1))^2. Because Schlick is affine in F0,
// rho_s = F0 A(mu, a) + B(mu, a) exactly, with A, B tabulated ONCE per distribution by quadrature in
// half-vector space (kelemen_szirmay_kalos.cpp) over mu = cos theta in [0, 1] and log a, and
// interpolated by Catmull-Rom splines (C1 in a, so gradients with respect to a are continuous).
// The coupling makes the directional albedo rho_s + rho_d (1 - rho_s) <= 1: energy conserving.
#pragma once

#include <string>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/parameters.h"
#include "roadbrdf/models/fresnel.h"
#include "roadbrdf/models/microfacet.h"

namespace roadbrdf {

namespace ksk {

enum class Distribution { kBeckmann, kWard, kPhong };

// Roughness range of the tables (and of the parameter).
inline constexpr double kAlphaMin = 0.01;
inline constexpr double kAlphaMax = 1.0;

// P_H(h) of the specular term (see the header comment).
template <typename T>
T halfway_density(Distribution d, double cos_h, const T& alpha) {
  switch (d) {
    case Distribution::kBeckmann:
      return microfacet::beckmann_d(cos_h, alpha);
    case Distribution::kWard:
      return microfacet::ward_halfway_pdf(cos_h, alpha);
    case Distribution::kPhong:
      return microfacet::phong_halfway_pdf(cos_h, T(2.0 / (alpha * alpha) - 2.0));
  }
  return T(0.0);
}

// rho_s(mu) = f0 * a[...] + b[...]; tables on a uniform mu grid x uniform log(alpha) grid.
struct AlbedoTable {
  static constexpr int kMu = 65;
  static constexpr int kAlpha = 49;
  double log_alpha_min = 0.0;
  double log_alpha_step = 0.0;
  std::vector<double> a, b;          // [i_alpha * kMu + i_mu]
  std::vector<double> a_avg, b_avg;  // [i_alpha]: 2 int a mu dmu, 2 int b mu dmu
};

// Built on first use (thread-safe), about a tenth of a second per distribution.
const AlbedoTable& albedo_table(Distribution d);

// Direct quadrature of the two parts of rho_s (no table): (A, B) at one (mu, alpha). Used to build
// the table; exposed for tools.
void specular_albedo_parts(Distribution d, double mu, double alpha, double* a, double* b);

// Catmull-Rom weights at fractional position t in [0, 1] for nodes -1, 0, 1, 2.
template <typename T>
void catmull_rom_weights(const T& t, T w[4]) {
  const T t2 = t * t;
  const T t3 = t2 * t;
  w[0] = 0.5 * (-t3 + 2.0 * t2 - t);
  w[1] = 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0);
  w[2] = 0.5 * (-3.0 * t3 + 4.0 * t2 + t);
  w[3] = 0.5 * (t3 - t2);
}

struct AlphaStencil {
  int index[4];
};

template <typename T>
AlphaStencil alpha_stencil(const AlbedoTable& table, const T& alpha, T w[4]) {
  using std::log;
  T u = (log(alpha) - table.log_alpha_min) / table.log_alpha_step;
  const double uv = scalar_value(u);
  const int last = AlbedoTable::kAlpha - 1;
  if (!(uv > 0.0)) u = T(0.0);  // also NaN (alpha <= 0): no undefined int cast below
  if (uv >= last) u = T(static_cast<double>(last));
  int i = static_cast<int>(std::floor(scalar_value(u)));
  if (i > last - 1) i = last - 1;
  if (i < 0) i = 0;
  catmull_rom_weights(T(u - static_cast<double>(i)), w);
  AlphaStencil s;
  for (int k = 0; k < 4; ++k) {
    int j = i - 1 + k;
    s.index[k] = j < 0 ? 0 : (j > last ? last : j);
  }
  return s;
}

// Catmull-Rom interpolation in mu (double) of one alpha row.
inline double interpolate_mu(const std::vector<double>& values, int i_alpha, double mu) {
  const int last = AlbedoTable::kMu - 1;
  double u = std::fmin(std::fmax(mu, 0.0), 1.0) * last;
  int i = static_cast<int>(std::floor(u));
  if (i > last - 1) i = last - 1;
  double w[4];
  catmull_rom_weights(u - i, w);
  const double* row = values.data() + static_cast<std::size_t>(i_alpha) * AlbedoTable::kMu;
  double v = 0.0;
  for (int k = 0; k < 4; ++k) {
    int j = i - 1 + k;
    j = j < 0 ? 0 : (j > last ? last : j);
    v += w[k] * row[j];
  }
  return v;
}

// Specular directional albedo rho_s(mu) for Schlick F0 = f0, interpolated.
template <typename T>
T specular_albedo(const AlbedoTable& table, double mu, const T& alpha, const T& f0) {
  T w[4];
  const AlphaStencil s = alpha_stencil(table, alpha, w);
  T a(0.0), b(0.0);
  for (int k = 0; k < 4; ++k) {
    a += w[k] * interpolate_mu(table.a, s.index[k], mu);
    b += w[k] * interpolate_mu(table.b, s.index[k], mu);
  }
  return f0 * a + b;
}

// Cosine-weighted average rho_s_bar for Schlick F0 = f0, interpolated in alpha.
template <typename T>
T specular_albedo_average(const AlbedoTable& table, const T& alpha, const T& f0) {
  T w[4];
  const AlphaStencil s = alpha_stencil(table, alpha, w);
  T a(0.0), b(0.0);
  for (int k = 0; k < 4; ++k) {
    a += w[k] * table.a_avg[static_cast<std::size_t>(s.index[k])];
    b += w[k] * table.b_avg[static_cast<std::size_t>(s.index[k])];
  }
  return f0 * a + b;
}

// rho_s(mu_i), rho_s(mu_r) and rho_s_bar in one pass (one alpha stencil; mu weights computed once).
template <typename T>
void specular_albedos(const AlbedoTable& table, double mu_i, double mu_r, const T& alpha, const T& f0, T* rho_i,
                      T* rho_r, T* rho_bar) {
  T w[4];
  const AlphaStencil s = alpha_stencil(table, alpha, w);
  T ai(0.0), bi(0.0), ar(0.0), br(0.0), aa(0.0), ba(0.0);
  for (int k = 0; k < 4; ++k) {
    const int ia = s.index[k];
    ai += w[k] * interpolate_mu(table.a, ia, mu_i);
    bi += w[k] * interpolate_mu(table.b, ia, mu_i);
    ar += w[k] * interpolate_mu(table.a, ia, mu_r);
    br += w[k] * interpolate_mu(table.b, ia, mu_r);
    aa += w[k] * table.a_avg[static_cast<std::size_t>(ia)];
    ba += w[k] * table.b_avg[static_cast<std::size_t>(ia)];
  }
  *rho_i = f0 * ai + bi;
  *rho_r = f0 * ar + br;
  *rho_bar = f0 * aa + ba;
}

}  // namespace ksk

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
    return d == "ward" ? ksk::Distribution::kWard : d == "phong" ? ksk::Distribution::kPhong
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
             ? "alpha: roughness; Phong exponent m = 2/alpha^2 - 2 (Walter 2007 eq. 30 equivalence to Beckmann RMS slope)"
             : "alpha: RMS slope of the microfacets (Beckmann/Ward width parameter, dimensionless)",
         0.3, ksk::kAlphaMin, ksk::kAlphaMax, false, false},
        {"ior", "1", "relative refractive index n of the facets; Schlick F0 = ((n-1)/(n+1))^2", 1.5, 1.0, 3.0, true,
         false},
    };
    d.energy_conserving = true;
    return d;
  }

  // The albedo table is built on the first evaluation (not here), so that listing or composing
  // models stays instantaneous.
  explicit KelemenSzirmayKalos(const OptionSet& options) : dist_(distribution_of(options)) {}

  template <typename T>
  T operator()(const T* p, const Geometry& g) const {
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
