// Tabulation of the specular directional albedo of the Kelemen & Szirmay-Kalos model.
//
// rho_s(theta_i) = int f_s cos theta_r dw_r with f_s = P_H(h) F(l.h) / (4 (l.h)^2). Changing the
// variable to the half vector (dw_r = 4 (l.h) dw_h; Walter 2007 eq. 14):
//   rho_s = int P_H(h) F(l.h) cos theta_r / (l.h) dw_h   over the h with cos theta_r > 0,
//   cos theta_r = 2 (l.h)(n.h) - cos theta_i.
// With l = (sin t_i, 0, cos t_i) and h = (sin t_h cos p, sin t_h sin p, cos t_h) the condition
// cos theta_r > 0 is cos p > cos t_i (1 - 2 cos^2 t_h) / (2 cos t_h sin t_i sin t_h), which is
// always true for t_h < pi/4 - t_i/2 and never for t_h > pi/4 + t_i/2 (derived here). The azimuth
// integral therefore runs over [0, p_max] (x 2, symmetry) with a smooth integrand, and the polar
// integral is split at those two angles and at multiples of the lobe width, each piece by
// Gauss-Legendre.
// Schlick F = F0 (1 - w) + w with w = (1 - l.h)^5, so rho_s = F0 A + B with A = int K (1 - w),
// B = int K w, K = P_H cos_r / (l.h).
#include "roadbrdf/models/kelemen_szirmay_kalos.h"

#include <algorithm>
#include <cmath>

namespace roadbrdf {
namespace ksk {

void specular_albedo_parts(Distribution d, double mu, double alpha, double* a_out, double* b_out) {
  const int kNodesTheta = 20;
  const int kNodesPhi = 20;
  const QuadratureRule& rt = microfacet::gauss_legendre_01(kNodesTheta);
  const QuadratureRule& rp = microfacet::gauss_legendre_01(kNodesPhi);
  mu = std::fmin(std::fmax(mu, 0.0), 1.0);
  const double theta_i = std::acos(mu);
  const double sin_i = std::sqrt(std::fmax(0.0, 1.0 - mu * mu));
  const double t_full = kPi / 4 - theta_i / 2;  // below: the whole azimuth circle reflects upwards
  const double t_end = kPi / 4 + theta_i / 2;   // above: nothing does
  std::vector<double> breaks = {0.0, t_end};
  if (t_full > 0.0) breaks.push_back(t_full);
  for (double k : {0.5, 1.0, 2.0, 3.5, 6.0}) {
    const double t = std::atan(k * alpha);
    if (t < t_end) breaks.push_back(t);
  }
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end(),
                           [](double x, double y) { return std::fabs(x - y) < 1e-12; }),
               breaks.end());
  double sum_a = 0.0, sum_b = 0.0;
  for (std::size_t seg = 0; seg + 1 < breaks.size(); ++seg) {
    const double t0 = breaks[seg];
    const double t1 = breaks[seg + 1];
    for (std::size_t it = 0; it < rt.nodes.size(); ++it) {
      const double th = t0 + (t1 - t0) * rt.nodes[it];
      const double ch = std::cos(th);
      const double sh = std::sin(th);
      const double ph = halfway_density(d, ch, alpha);
      if (ph == 0.0) continue;
      double phi_max = kPi;
      const double num = mu * (1.0 - 2.0 * ch * ch);
      const double den = 2.0 * ch * sin_i * sh;
      if (den <= 1e-300) {
        phi_max = num < 0.0 ? kPi : 0.0;
      } else {
        phi_max = std::acos(std::fmin(1.0, std::fmax(-1.0, num / den)));
      }
      if (phi_max <= 0.0) continue;
      double inner_a = 0.0, inner_b = 0.0;
      for (std::size_t ip = 0; ip < rp.nodes.size(); ++ip) {
        const double p = phi_max * rp.nodes[ip];
        const double lh = sin_i * sh * std::cos(p) + mu * ch;
        if (lh <= 0.0) continue;
        const double cr = 2.0 * lh * ch - mu;
        if (cr <= 0.0) continue;
        const double k = cr / lh;
        const double m = 1.0 - lh;
        const double w = (m * m) * (m * m) * m;
        inner_a += rp.weights[ip] * k * (1.0 - w);
        inner_b += rp.weights[ip] * k * w;
      }
      const double weight = rt.weights[it] * (t1 - t0) * sh * ph * 2.0 * phi_max;
      sum_a += weight * inner_a;
      sum_b += weight * inner_b;
    }
  }
  *a_out = sum_a;
  *b_out = sum_b;
}

namespace {

AlbedoTable build_table(Distribution d) {
  AlbedoTable t;
  t.log_alpha_min = std::log(kAlphaMin);
  t.log_alpha_step = (std::log(kAlphaMax) - std::log(kAlphaMin)) / (AlbedoTable::kAlpha - 1);
  t.a.resize(static_cast<std::size_t>(AlbedoTable::kAlpha) * AlbedoTable::kMu);
  t.b.resize(t.a.size());
  t.a_avg.resize(AlbedoTable::kAlpha);
  t.b_avg.resize(AlbedoTable::kAlpha);
  const QuadratureRule& rmu = microfacet::gauss_legendre_01(24);
  for (int ia = 0; ia < AlbedoTable::kAlpha; ++ia) {
    const double alpha = std::exp(t.log_alpha_min + ia * t.log_alpha_step);
    for (int im = 0; im < AlbedoTable::kMu; ++im) {
      const double mu = static_cast<double>(im) / (AlbedoTable::kMu - 1);
      const std::size_t idx = static_cast<std::size_t>(ia) * AlbedoTable::kMu + static_cast<std::size_t>(im);
      specular_albedo_parts(d, mu, alpha, &t.a[idx], &t.b[idx]);
    }
    // rho_bar = 2 int_0^1 rho_s(mu) mu dmu, by its own Gauss-Legendre rule (not from the table).
    double avg_a = 0.0, avg_b = 0.0;
    for (std::size_t k = 0; k < rmu.nodes.size(); ++k) {
      double a = 0.0, b = 0.0;
      specular_albedo_parts(d, rmu.nodes[k], alpha, &a, &b);
      avg_a += 2.0 * rmu.weights[k] * rmu.nodes[k] * a;
      avg_b += 2.0 * rmu.weights[k] * rmu.nodes[k] * b;
    }
    t.a_avg[static_cast<std::size_t>(ia)] = avg_a;
    t.b_avg[static_cast<std::size_t>(ia)] = avg_b;
  }
  return t;
}

}  // namespace

const AlbedoTable& albedo_table(Distribution d) {
  switch (d) {
    case Distribution::kWard: {
      static const AlbedoTable ward = build_table(Distribution::kWard);
      return ward;
    }
    case Distribution::kPhong: {
      static const AlbedoTable phong = build_table(Distribution::kPhong);
      return phong;
    }
    case Distribution::kBeckmann:
      break;
  }
  static const AlbedoTable beckmann = build_table(Distribution::kBeckmann);
  return beckmann;
}

}  // namespace ksk
}  // namespace roadbrdf
