#include "roadbrdf/mixing/hapke_imsa.h"

#include <cmath>
#include <sstream>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/quadrature.h"

namespace roadbrdf::mixing {

namespace {

// Gauss-Legendre rule on [0, 1] in mu, computed once.
const QuadratureRule& mu_rule() {
  static const QuadratureRule rule = gauss_legendre(kQuadratureMu, 0.0, 1.0);
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
    const QuadratureRule& m = mu_rule();
    const double dphi = kPi / kQuadraturePhi;
    for (int a = 0; a < kQuadratureMu; ++a) {
      for (int b = 0; b < kQuadratureMu; ++b) {
        for (int c = 0; c < kQuadraturePhi; ++c) {
          const double phi = (c + 0.5) * dphi;
          r.geometries.push_back(geometry_from_radians(std::acos(m.nodes[a]), 0.0, std::acos(m.nodes[b]), phi));
          // 2 * (mu0 w0) * (mu w) * 2 (both halves of the azimuth) * dphi
          r.weights.push_back(4.0 * m.nodes[a] * m.weights[a] * m.nodes[b] * m.weights[b] * dphi);
          r.mu0.push_back(m.nodes[a]);
          r.mu.push_back(m.nodes[b]);
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
    const QuadratureRule& m = mu_rule();
    const std::size_t p = model.parameter_count();
    for (std::size_t s = 0; s < n_sets; ++s) {
      for (int a = 0; a < kQuadratureMu; ++a) {
        albedo[s] += 2.0 * m.weights[a] * m.nodes[a] * model.delta_reflectance(params + s * p, m.nodes[a]);
      }
    }
  }
  return albedo;
}

double imsa_white_sky_albedo(double w) {
  const QuadratureRule& m = mu_rule();
  double sum = 0.0;
  for (int a = 0; a < kQuadratureMu; ++a) {
    for (int b = 0; b < kQuadratureMu; ++b) {
      sum += m.nodes[a] * m.weights[a] * m.nodes[b] * m.weights[b] * imsa_isotropic_brdf(w, m.nodes[a], m.nodes[b]);
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
