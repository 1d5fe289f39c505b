// Specular directional albedo rho_s(mu, alpha) of the Kelemen & Szirmay-Kalos model (see
// kelemen_szirmay_kalos.h): direct quadrature and its table.
//
// rho_s(theta_i) = int f_s cos theta_r dw_r with f_s = P_H(h) F(l.h) / (4 (l.h)^2). Changing the
// variable to the half vector (dw_r = 4 (l.h) dw_h; Walter 2007 eq. 14):
//   rho_s = int P_H(h) F(l.h) cos theta_r / (l.h) dw_h   over the h with cos theta_r > 0,
//   cos theta_r = 2 (l.h)(n.h) - cos theta_i.
// With l = (sin t_i, 0, cos t_i) and h = (sin t_h cos p, sin t_h sin p, cos t_h) the condition
// cos theta_r > 0 is cos p > cos t_i (1 - 2 cos^2 t_h) / (2 cos t_h sin t_i sin t_h), which is
// always true for t_h < pi/4 - t_i/2 and never for t_h > pi/4 + t_i/2 (derived here). The azimuth
// integral therefore runs over [0, p_max] (x 2, symmetry), and the polar integral is split at those
// two angles and at multiples of the lobe width, each piece by Gauss-Legendre after a cubic change
// of variable that removes the square-root behaviour of p_max(t_h) at both breaks.
// Schlick F = F0 (1 - w) + w with w = (1 - l.h)^5, so rho_s = F0 A + B with A = int K (1 - w),
// B = int K w, K = P_H cos_r / (l.h).
//
// Accuracy. At grazing incidence (mu -> 0) K has a boundary layer at p_max (l.h falls to ~mu) and
// rho_s(mu) behaves like mu log mu: a table in mu cannot follow it, and neither can a fixed rule in
// p. The quadrature splits the 1/(l.h) part off and integrates it in closed form (converged to
// ~1e-9 with 16 x 16 nodes per piece, checked against 120 nodes); the table covers
// mu in [kMuTable, 1] on a grid uniform in log mu + 3 mu (where rho_s is smooth), and below kMuTable
// (theta > 89.9994 deg) the model integrates directly. In alpha the table is uniform in log alpha
// with cubic Hermite interpolation whose node slopes are fourth-order central differences (C1, so
// gradients with respect to alpha are continuous; O(h^4)); in mu, four-point Lagrange (O(h^4)).
// Table rows are built on first use, one alpha row at a time.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <mutex>
#include <vector>

#include "roadbrdf/core/math.h"
#include "roadbrdf/models/microfacet.h"

namespace roadbrdf::ksk {

enum class Distribution { kBeckmann, kWard, kPhong };

// Roughness range of the tables (and of the parameter).
inline constexpr double kAlphaMin = 0.01;
inline constexpr double kAlphaMax = 1.0;
// Smallest mu of the table; below it rho_s is integrated directly.
inline constexpr double kMuTable = 1e-5;
// The table is uniform in v = log mu + kMuLinear mu: logarithmic towards grazing, where rho_s varies
// on the scale of mu itself, nearly linear towards normal incidence.
inline constexpr double kMuLinear = 3.0;
inline double mu_variable(double mu) { return std::log(mu) + kMuLinear * mu; }
double mu_of_variable(double v);  // inverse of mu_variable

// P_H(h) of the specular term (see kelemen_szirmay_kalos.h).
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

// int_0^P dp / (b + a cos p) for a, b >= 0 with b + a cos p > 0 on [0, P], P in (0, pi]. With
// t = tan(p/2) it is 2/(a + b) int_0^T dt / (1 - s t^2), s = (a - b)/(a + b), T = tan(P/2).
double azimuth_inverse_integral(double a, double b, double big_p);

// Direct quadrature of the two parts of rho_s (no table): (A, B) at one (mu, alpha), `nodes` Gauss
// nodes per polar piece and in azimuth. T is double or a ceres::Jet (derivatives in alpha flow
// through P_H only; the break points are quadrature details, not part of the value).
template <typename T>
void specular_albedo_parts(Distribution d, double mu, const T& alpha, T* a_out, T* b_out, int nodes = 16) {
  const QuadratureRule& rt = microfacet::gauss_legendre_01(nodes);
  const QuadratureRule& rp = microfacet::gauss_legendre_01(nodes);
  mu = std::fmin(std::fmax(mu, 0.0), 1.0);
  const double alpha_v = scalar_value(alpha);
  const double theta_i = std::acos(mu);
  const double sin_i = std::sqrt(std::fmax(0.0, 1.0 - mu * mu));
  const double t_full = kPi / 4 - theta_i / 2;  // below: the whole azimuth circle reflects upwards
  const double t_end = kPi / 4 + theta_i / 2;   // above: nothing does
  std::array<double, 8> breaks{};
  std::size_t n_breaks = 0;
  breaks[n_breaks++] = 0.0;
  breaks[n_breaks++] = t_end;
  if (t_full > 0.0) breaks[n_breaks++] = t_full;
  for (double k : {0.5, 1.0, 2.0, 3.5, 6.0}) {
    const double t = std::atan(k * alpha_v);
    if (t < t_end) breaks[n_breaks++] = t;
  }
  for (std::size_t i = 1; i < n_breaks; ++i) {  // insertion sort of the few break points
    for (std::size_t j = i; j > 0 && breaks[j - 1] > breaks[j]; --j) std::swap(breaks[j - 1], breaks[j]);
  }
  T sum_a(0.0), sum_b(0.0);
  for (std::size_t seg = 0; seg + 1 < n_breaks; ++seg) {
    const double t0 = breaks[seg];
    const double t1 = breaks[seg + 1];
    if (t1 - t0 < 1e-12) continue;
    for (std::size_t it = 0; it < rt.nodes.size(); ++it) {
      // t = t0 + (t1 - t0) (3 s^2 - 2 s^3): dt/ds vanishes at both ends.
      const double sn = rt.nodes[it];
      const double th = t0 + (t1 - t0) * sn * sn * (3.0 - 2.0 * sn);
      const double dt = (t1 - t0) * 6.0 * sn * (1.0 - sn);
      const double ch = std::cos(th);
      const double sh = std::sin(th);
      const T ph = halfway_density(d, ch, alpha);
      if (scalar_value(ph) == 0.0) continue;
      double phi_max = kPi;
      const double num = mu * (1.0 - 2.0 * ch * ch);
      const double den = 2.0 * ch * sin_i * sh;
      if (den <= 1e-300) {
        phi_max = num < 0.0 ? kPi : 0.0;
      } else {
        phi_max = std::acos(std::fmin(1.0, std::fmax(-1.0, num / den)));
      }
      if (phi_max <= 0.0) continue;
      // K = cr / (l.h) = 2 n.h - mu / (l.h); on [0, phi_max] cr >= 0, i.e. l.h >= mu / (2 n.h). At
      // grazing incidence mu / (l.h) has a boundary layer of width ~mu at phi_max. Split it off:
      // (1 - w)/(l.h) = q(l.h) is a polynomial and w/(l.h) = 1/(l.h) - q(l.h), whose 1/(l.h) part
      // integrates in closed form.
      const double alpha_h = sin_i * sh, beta_h = mu * ch;
      double inner_a = 0.0, inner_b = 0.0;
      for (std::size_t ip = 0; ip < rp.nodes.size(); ++ip) {
        const double p = phi_max * rp.nodes[ip];
        const double lh = alpha_h * std::cos(p) + beta_h;
        const double m = 1.0 - lh;
        const double w = (m * m) * (m * m) * m;
        const double q = 5.0 + lh * (-10.0 + lh * (10.0 + lh * (-5.0 + lh)));  // (1 - (1 - x)^5) / x
        inner_a += rp.weights[ip] * (2.0 * ch * (1.0 - w) - mu * q);
        inner_b += rp.weights[ip] * (2.0 * ch * w + mu * q);
      }
      if (mu > 0.0) inner_b -= mu * azimuth_inverse_integral(alpha_h, beta_h, phi_max) / phi_max;
      const double weight = rt.weights[it] * dt * sh * 2.0 * phi_max;
      sum_a += (weight * inner_a) * ph;
      sum_b += (weight * inner_b) * ph;
    }
  }
  *a_out = sum_a;
  *b_out = sum_b;
}

// rho_s(mu) = f0 A + B and rho_s_bar = f0 A_bar + B_bar, tabulated per distribution.
class AlbedoTable {
 public:
  static constexpr int kMu = 129;    // nodes in mu_variable on [kMuTable, 1]
  static constexpr int kAlpha = 97;  // nodes in log alpha on [kAlphaMin, kAlphaMax]
  static constexpr int kGhost = 2;   // extra rows beyond each end (for the central differences)

  struct Row {
    std::vector<double> a, b;         // [i_mu]
    double a_avg = 0.0, b_avg = 0.0;  // 2 int_0^1 A mu dmu, 2 int_0^1 B mu dmu
  };

  explicit AlbedoTable(Distribution d);
  Distribution distribution() const { return dist_; }
  double log_alpha_min() const { return log_alpha_min_; }
  double log_alpha_step() const { return log_alpha_step_; }
  double v_min() const { return v_min_; }
  double v_step() const { return v_step_; }
  // Row i in [-kGhost, kAlpha - 1 + kGhost], built on first use (thread-safe).
  const Row& row(int i) const;
  double row_alpha(int i) const { return std::exp(log_alpha_min_ + i * log_alpha_step_); }

 private:
  Distribution dist_;
  double log_alpha_min_, log_alpha_step_, v_min_, v_step_;
  mutable std::vector<std::unique_ptr<Row>> rows_;
  mutable std::unique_ptr<std::once_flag[]> once_;
};

const AlbedoTable& albedo_table(Distribution d);

// Weights of the six rows i-2 .. i+3 for alpha (cubic Hermite between rows i and i+1, slopes from
// fourth-order central differences). Returns i - 2.
template <typename T>
int alpha_weights(const AlbedoTable& table, const T& alpha, T w[6]) {
  using std::log;
  T u = (log(alpha) - table.log_alpha_min()) / table.log_alpha_step();
  const int last = AlbedoTable::kAlpha - 1;
  // Outside the declared bounds the value is held (the bounds keep fits inside).
  if (!(scalar_value(u) > 0.0)) u = T(0.0);  // also NaN (alpha <= 0): no undefined int cast below
  if (scalar_value(u) > last) u = T(static_cast<double>(last));
  int i = static_cast<int>(std::floor(scalar_value(u)));
  i = std::clamp(i, 0, last - 1);
  const T t = u - static_cast<double>(i);
  const T t2 = t * t, t3 = t2 * t;
  const T h00 = 2.0 * t3 - 3.0 * t2 + 1.0, h10 = t3 - 2.0 * t2 + t;
  const T h01 = -2.0 * t3 + 3.0 * t2, h11 = t3 - t2;
  // slope m_j = (y_{j-2} - 8 y_{j-1} + 8 y_{j+1} - y_{j+2}) / 12 (per row step)
  const double c[5] = {1.0 / 12.0, -8.0 / 12.0, 0.0, 8.0 / 12.0, -1.0 / 12.0};
  for (int k = 0; k < 6; ++k) w[k] = T(0.0);
  w[2] += h00;
  w[3] += h01;
  for (int k = 0; k < 5; ++k) {
    w[k] += h10 * c[k];      // slope at row i uses rows i-2 .. i+2 (w indices 0 .. 4)
    w[k + 1] += h11 * c[k];  // slope at row i+1 uses rows i-1 .. i+3 (w indices 1 .. 5)
  }
  return i - 2;
}

// Four-point Lagrange weights in mu_variable(mu) (mu >= kMuTable); returns the first node index.
int mu_weights(const AlbedoTable& table, double mu, double w[4]);

// A and B of one row at mu >= kMuTable.
inline void row_parts(const AlbedoTable::Row& row, int j0, const double w[4], double* a, double* b) {
  double sa = 0.0, sb = 0.0;
  const auto first = static_cast<std::size_t>(j0);
  for (std::size_t k = 0; k < 4; ++k) {
    sa += w[k] * row.a[first + k];
    sb += w[k] * row.b[first + k];
  }
  *a = sa;
  *b = sb;
}

// rho_s(mu_i), rho_s(mu_r) and rho_s_bar for Schlick F0 = f0.
template <typename T>
void specular_albedos(const AlbedoTable& table, double mu_i, double mu_r, const T& alpha, const T& f0, T* rho_i,
                      T* rho_r, T* rho_bar) {
  T w[6];
  const int r0 = alpha_weights(table, alpha, w);
  double wi[4], wr[4];
  const bool table_i = mu_i >= kMuTable, table_r = mu_r >= kMuTable;
  const int ji = table_i ? mu_weights(table, mu_i, wi) : 0;
  const int jr = table_r ? mu_weights(table, mu_r, wr) : 0;
  T ai(0.0), bi(0.0), ar(0.0), br(0.0), aa(0.0), ba(0.0);
  for (int k = 0; k < 6; ++k) {
    const AlbedoTable::Row& row = table.row(r0 + k);
    double a, b;
    if (table_i) {
      row_parts(row, ji, wi, &a, &b);
      ai += w[k] * a;
      bi += w[k] * b;
    }
    if (table_r) {
      row_parts(row, jr, wr, &a, &b);
      ar += w[k] * a;
      br += w[k] * b;
    }
    aa += w[k] * row.a_avg;
    ba += w[k] * row.b_avg;
  }
  const T alpha_in = clamp_value(alpha, kAlphaMin, kAlphaMax);
  if (!table_i) specular_albedo_parts(table.distribution(), mu_i, alpha_in, &ai, &bi);
  if (!table_r) specular_albedo_parts(table.distribution(), mu_r, alpha_in, &ar, &br);
  *rho_i = f0 * ai + bi;
  *rho_r = f0 * ar + br;
  *rho_bar = f0 * aa + ba;
}

// Specular directional albedo rho_s(mu) for Schlick F0 = f0.
template <typename T>
T specular_albedo(const AlbedoTable& table, double mu, const T& alpha, const T& f0) {
  T rho_i, rho_r, rho_bar;
  specular_albedos(table, mu, 1.0, alpha, f0, &rho_i, &rho_r, &rho_bar);
  return rho_i;
}

// Cosine-weighted average rho_s_bar for Schlick F0 = f0.
template <typename T>
T specular_albedo_average(const AlbedoTable& table, const T& alpha, const T& f0) {
  T rho_i, rho_r, rho_bar;
  specular_albedos(table, 1.0, 1.0, alpha, f0, &rho_i, &rho_r, &rho_bar);
  return rho_bar;
}

}  // namespace roadbrdf::ksk
