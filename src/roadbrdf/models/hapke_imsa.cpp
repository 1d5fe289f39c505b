#include "roadbrdf/models/hapke_imsa.h"

#include <algorithm>
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
  // Both directions grazing: 1/(mu0 + mu) diverges; 0 there, as the "hapke" model declares.
  if (mu0 <= kGrazingCosine && mu <= kGrazingCosine) return 0.0;
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

namespace {

// A(w) of imsa_white_sky_albedo as a function of gamma = sqrt(1 - w) (w = 1 - gamma^2), and dA/dgamma:
//   A = sum_ab W_ab w H_a H_b,  W_ab = 4 pi mu_a wt_a mu_b wt_b / (4 pi (mu_a + mu_b)),
//   H_a = (1 + 2 mu_a) / (1 + 2 mu_a gamma),  dH_a/dgamma = -H_a 2 mu_a / (1 + 2 mu_a gamma),
//   d(w H_a H_b)/dgamma = H_a H_b [-2 gamma - w (2 mu_a / (1 + 2 mu_a gamma) + 2 mu_b / (1 + 2 mu_b gamma))].
// A is smooth in gamma on [0, 1] (in w it has a square-root singularity at w = 1) and decreasing.
void imsa_albedo_in_gamma(double gamma, double& value, double& derivative) {
  const QuadratureRule& m = mu_rule();
  double h[kQuadratureMu], d[kQuadratureMu];
  for (int a = 0; a < kQuadratureMu; ++a) {
    const double x = m.nodes[a];
    h[a] = (1.0 + 2.0 * x) / (1.0 + 2.0 * x * gamma);
    d[a] = 2.0 * x / (1.0 + 2.0 * x * gamma);
  }
  const double w = 1.0 - gamma * gamma;
  value = 0.0;
  derivative = 0.0;
  for (int a = 0; a < kQuadratureMu; ++a) {
    for (int b = 0; b < kQuadratureMu; ++b) {
      const double weight = m.nodes[a] * m.weights[a] * m.nodes[b] * m.weights[b] / (m.nodes[a] + m.nodes[b]);
      const double hh = h[a] * h[b];
      value += weight * w * hh;
      derivative += weight * hh * (-2.0 * gamma - w * (d[a] + d[b]));
    }
  }
}

}  // namespace

double invert_imsa_white_sky_albedo(double albedo) {
  static const double a_max = imsa_white_sky_albedo(1.0);
  if (!(albedo >= 0.0 && albedo <= a_max)) {
    std::ostringstream msg;
    msg << "white-sky albedo " << albedo << " cannot be matched by the Hapke IMSA model (range [0, " << a_max << "])";
    throw InputError(msg.str());
  }
  if (albedo == 0.0) return 0.0;
  if (albedo == a_max) return 1.0;
  // Safeguarded Newton in gamma on the bracket [lo, hi] (A(lo) >= albedo >= A(hi)): a Newton step
  // leaving the bracket is replaced by bisection. Start: the single-scattering guess
  // A ~ a_max (1 - gamma) is poor near w = 1 but the safeguard makes any start converge.
  double lo = 0.0, hi = 1.0;
  double gamma = std::clamp(1.0 - albedo / a_max, 0.0, 1.0);
  for (int iter = 0; iter < 100; ++iter) {
    double value = 0.0, derivative = 0.0;
    imsa_albedo_in_gamma(gamma, value, derivative);
    const double f = value - albedo;
    if (f == 0.0) break;
    if (f > 0.0) {
      lo = gamma;  // albedo too high: gamma too small (w too large)
    } else {
      hi = gamma;
    }
    double next = derivative < 0.0 ? gamma - f / derivative : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const double step = std::fabs(next - gamma);
    gamma = next;
    if (step < 1e-15 || hi - lo < 1e-15) break;
  }
  return 1.0 - gamma * gamma;
}

}  // namespace roadbrdf::mixing
