// Table of the specular directional albedo of the Kelemen & Szirmay-Kalos model (see
// kelemen_szirmay_kalos_albedo.h for the quadrature and the interpolation).
#include <cmath>
#include <limits>

#include "roadbrdf/models/kelemen_szirmay_kalos.h"

namespace roadbrdf::ksk {

double azimuth_inverse_integral(double a, double b, double big_p) {
  const double t = big_p >= kPi ? std::numeric_limits<double>::infinity() : std::tan(0.5 * big_p);
  const double s = (a - b) / (a + b);
  double integral;  // int_0^T dt / (1 - s t^2)
  if (std::isfinite(t) && std::fabs(s) * t * t < 1e-4) {
    const double x = s * t * t;
    integral = t * (1.0 + x * (1.0 / 3.0 + x * (1.0 / 5.0 + x / 7.0)));
  } else if (s > 0.0) {
    integral = std::atanh(std::sqrt(s) * t) / std::sqrt(s);
  } else {
    integral = std::atan(std::sqrt(-s) * t) / std::sqrt(-s);
  }
  return 2.0 * integral / (a + b);
}

AlbedoTable::AlbedoTable(Distribution d)
    : dist_(d),
      log_alpha_min_(std::log(kAlphaMin)),
      log_alpha_step_((std::log(kAlphaMax) - std::log(kAlphaMin)) / (kAlpha - 1)),
      v_min_(mu_variable(kMuTable)),
      v_step_((mu_variable(1.0) - mu_variable(kMuTable)) / (kMu - 1)),
      rows_(kAlpha + 2 * kGhost),
      once_(new std::once_flag[kAlpha + 2 * kGhost]) {}

const AlbedoTable::Row& AlbedoTable::row(int i) const {
  const int index = i + kGhost;  // ghost rows below 0 are slots 0..kGhost-1
  const auto slot = static_cast<std::size_t>(index);
  std::call_once(once_[slot], [&] {
    auto r = std::make_unique<Row>();
    // Ghost rows lie beyond the roughness range; the quadrature is smooth in alpha there too (for
    // phong, m = 2/alpha^2 - 2 > -1 still gives an integrable density).
    const double alpha = row_alpha(i);
    r->a.resize(kMu);
    r->b.resize(kMu);
    for (int j = 0; j < kMu; ++j) {
      const double mu = j == kMu - 1 ? 1.0 : mu_of_variable(v_min_ + j * v_step_);
      specular_albedo_parts(dist_, mu, alpha, &r->a[static_cast<std::size_t>(j)], &r->b[static_cast<std::size_t>(j)]);
    }
    // rho_bar = 2 int_0^1 rho_s(mu) mu dmu by its own rules (not from the table): Gauss-Legendre in mu
    // on [0, kMuTable], and in v = log mu on [log kMuTable, 0] (dmu = mu dv), in equal panels.
    double sa = 0.0, sb = 0.0;
    const QuadratureRule& g = microfacet::gauss_legendre_01(10);
    for (std::size_t k = 0; k < g.nodes.size(); ++k) {
      const double mu = kMuTable * g.nodes[k];
      double a, b;
      specular_albedo_parts(dist_, mu, alpha, &a, &b);
      sa += 2.0 * kMuTable * g.weights[k] * mu * a;
      sb += 2.0 * kMuTable * g.weights[k] * mu * b;
    }
    const int panels = 8;
    const double log_mu_min = std::log(kMuTable);
    const double span = -log_mu_min / panels;
    for (int p = 0; p < panels; ++p) {
      for (std::size_t k = 0; k < g.nodes.size(); ++k) {
        const double v = log_mu_min + span * (p + g.nodes[k]);
        const double mu = std::exp(v);
        double a, b;
        specular_albedo_parts(dist_, mu, alpha, &a, &b);
        sa += 2.0 * span * g.weights[k] * mu * mu * a;
        sb += 2.0 * span * g.weights[k] * mu * mu * b;
      }
    }
    r->a_avg = sa;
    r->b_avg = sb;
    rows_[slot] = std::move(r);
  });
  return *rows_[slot];
}

double mu_of_variable(double v) {
  // Newton on x = log mu: x + k e^x = v (increasing, convex in x); from below it converges monotonically.
  double x = std::fmin(v, 0.0) - 1.0;
  for (int it = 0; it < 100; ++it) {
    const double e = std::exp(x);
    const double dx = (x + kMuLinear * e - v) / (1.0 + kMuLinear * e);
    x -= dx;
    if (std::fabs(dx) < 1e-15) break;
  }
  return std::exp(x);
}

int mu_weights(const AlbedoTable& table, double mu, double w[4]) {
  const double s = (mu_variable(std::fmin(mu, 1.0)) - table.v_min()) / table.v_step();
  const int j = std::clamp(static_cast<int>(std::floor(s)), 1, AlbedoTable::kMu - 3);
  const double t = s - j;  // nodes at -1, 0, 1, 2
  w[0] = -t * (t - 1.0) * (t - 2.0) / 6.0;
  w[1] = (t + 1.0) * (t - 1.0) * (t - 2.0) / 2.0;
  w[2] = -(t + 1.0) * t * (t - 2.0) / 2.0;
  w[3] = (t + 1.0) * t * (t - 1.0) / 6.0;
  return j - 1;
}

const AlbedoTable& albedo_table(Distribution d) {
  switch (d) {
    case Distribution::kWard: {
      static const AlbedoTable ward(Distribution::kWard);
      return ward;
    }
    case Distribution::kPhong: {
      static const AlbedoTable phong(Distribution::kPhong);
      return phong;
    }
    case Distribution::kBeckmann:
      break;
  }
  static const AlbedoTable beckmann(Distribution::kBeckmann);
  return beckmann;
}

}  // namespace roadbrdf::ksk

#include "roadbrdf/models/model_factory.h"

namespace roadbrdf {

// The model's factory: its adapter and the fitter's Jet instantiations compile here (model_factory.h).
ModelFactory kelemen_szirmay_kalos_factory() { return factory_of<KelemenSzirmayKalos>(); }

}  // namespace roadbrdf
