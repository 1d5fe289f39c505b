#include "roadbrdf/mixing/hapke_imsa.h"

#include <cmath>
#include <sstream>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"

namespace roadbrdf::mixing {

namespace {

// Gauss-Legendre nodes and weights on (0, 1) (Newton on the Legendre recurrence).
void gauss_legendre_01(int n, std::vector<double>& x, std::vector<double>& w) {
  x.resize(n);
  w.resize(n);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(kPi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1.0, p1 = 0.0;
      for (int j = 1; j <= n; ++j) {
        const double p2 = p1;
        p1 = p0;
        p0 = ((2.0 * j - 1.0) * z * p1 - (j - 1.0) * p2) / j;
      }
      dp = n * (z * p0 - p1) / (z * z - 1.0);
      const double dz = p0 / dp;
      z -= dz;
      if (std::fabs(dz) < 1e-15) break;
    }
    x[i] = 0.5 * (1.0 - z);
    w[i] = 1.0 / ((1.0 - z * z) * dp * dp);  // (2 / ((1 - z^2) P'^2)) / 2
  }
}

struct MuRule {
  std::vector<double> x, w;
};
const MuRule& mu_rule() {
  static const MuRule rule = [] {
    MuRule r;
    gauss_legendre_01(kQuadratureMu, r.x, r.w);
    return r;
  }();
  return rule;
}

}  // namespace

double hapke_h1(double x, double w) {
  const double gamma = std::sqrt(std::max(0.0, 1.0 - w));
  return (1.0 + 2.0 * x) / (1.0 + 2.0 * x * gamma);
}

double imsa_isotropic_brdf(double w, double mu0, double mu) {
  if (mu0 + mu <= 0.0) return 0.0;
  return w / (4.0 * kPi) * hapke_h1(mu0, w) * hapke_h1(mu, w) / (mu0 + mu);
}

const HemisphereRule& white_sky_rule() {
  static const HemisphereRule rule = [] {
    HemisphereRule r;
    const MuRule& m = mu_rule();
    const double dphi = kPi / kQuadraturePhi;
    for (int a = 0; a < kQuadratureMu; ++a) {
      for (int b = 0; b < kQuadratureMu; ++b) {
        for (int c = 0; c < kQuadraturePhi; ++c) {
          const double phi = (c + 0.5) * dphi;
          r.geometries.push_back(geometry_from_radians(std::acos(m.x[a]), 0.0, std::acos(m.x[b]), phi));
          // 2 * (mu0 w0) * (mu w) * 2 (both halves of the azimuth) * dphi
          r.weights.push_back(4.0 * m.x[a] * m.w[a] * m.x[b] * m.w[b] * dphi);
          r.mu0.push_back(m.x[a]);
          r.mu.push_back(m.x[b]);
        }
      }
    }
    return r;
  }();
  return rule;
}

std::vector<double> white_sky_albedo(const Model& model, const double* params, std::size_t n_sets) {
  const HemisphereRule& rule = white_sky_rule();
  const std::size_t n = rule.geometries.size();
  std::vector<double> values(n * n_sets);
  model.evaluate_batch(rule.geometries.data(), n, params, n_sets, values.data());
  std::vector<double> albedo(n_sets, 0.0);
  for (std::size_t g = 0; g < n; ++g) {
    for (std::size_t s = 0; s < n_sets; ++s) albedo[s] += rule.weights[g] * values[g * n_sets + s];
  }
  if (model.description().has_delta) {
    const MuRule& m = mu_rule();
    const std::size_t p = model.parameter_count();
    for (std::size_t s = 0; s < n_sets; ++s) {
      for (int a = 0; a < kQuadratureMu; ++a) {
        albedo[s] += 2.0 * m.w[a] * m.x[a] * model.delta_reflectance(params + s * p, m.x[a]);
      }
    }
  }
  return albedo;
}

double imsa_white_sky_albedo(double w) {
  const MuRule& m = mu_rule();
  double sum = 0.0;
  for (int a = 0; a < kQuadratureMu; ++a) {
    for (int b = 0; b < kQuadratureMu; ++b) {
      sum += m.x[a] * m.w[a] * m.x[b] * m.w[b] * imsa_isotropic_brdf(w, m.x[a], m.x[b]);
    }
  }
  return 2.0 * 2.0 * kPi * sum;
}

double invert_imsa_white_sky_albedo(double albedo) {
  static const double a_max = imsa_white_sky_albedo(1.0);
  if (!(albedo >= 0.0 && albedo <= a_max)) {
    std::ostringstream msg;
    msg << "white-sky albedo " << albedo << " cannot be matched by the Hapke IMSA model (range [0, " << a_max << "])";
    throw InputError(msg.str());
  }
  double lo = 0.0, hi = 1.0;
  for (int iter = 0; iter < 200 && hi - lo > 1e-13; ++iter) {
    const double mid = 0.5 * (lo + hi);
    if (imsa_white_sky_albedo(mid) < albedo) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

}  // namespace roadbrdf::mixing
