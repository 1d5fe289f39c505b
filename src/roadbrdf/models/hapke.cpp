// The hapke model's factory: its adapter and the fitter's Jet instantiations compile here (model_factory.h),
// and its analytic gradient path.
#include "roadbrdf/models/hapke.h"
#include "roadbrdf/models/model_factory.h"

#include <cstddef>
#include <vector>

namespace roadbrdf {

ModelFactory hapke_factory() { return factory_of<Hapke>(); }

// Value and analytic gradient of f = w s {[1 + B] p + H(mu0) H(mu) - 1}, s = 1/(4 pi (mu0 + mu)),
// B = b0 h/(h + t), t = tan(g/2):
//   df/dw  = s {...} + w s [H'(mu0) H(mu) + H(mu0) H'(mu)]        (H' = dH/dw, per distinct cosine)
//   df/db0 = w s p h/(h + t),   df/dh = w s p b0 t/(h + t)^2       (0 at g = pi, where B = 0)
//   HG:       df/dxi = w s (1 + B) dp/dxi, dp/dxi = -[2 xi + 3 (1 - xi^2)(cos g + xi)/D] / D^1.5,
//             D = 1 + 2 xi cos g + xi^2
//   Legendre: df/db = w s (1 + B) cos g,   df/dc = w s (1 + B) (3 cos^2 g - 1)/2;
//             N terms: df/da_n = w s (1 + B) P_n(cos g).
//   hg2:      df/db = w s (1 + B) [-(1 + c)/2 HG'(-b) + (1 - c)/2 HG'(b)],
//             df/dc = w s (1 + B) [HG(-b) - HG(b)]/2   (HG' = dp/dxi of the HG line).
// The value is computed by the same expressions as operator() (same rounding, bit for bit); dH/dw is
// that of the ceres::Jet path of h_function, so the gradient equals the automatic derivative to
// rounding. Every gradient path of the model (single, batch, prepared) comes here, so they agree
// with each other bit for bit. With roughness = hapke1984: evaluate_with_jets.
void Hapke::evaluate_shared(const SharedTerms& s, const Prepared* g, std::size_t n, const double* p, double* values,
                            double* jacobian) const {
  if (roughness_) return evaluate_with_jets(g, n, p, values, jacobian);
  using Jet1 = ceres::Jet<double, 1>;
  const double w = p[kW], b0 = p[kB0], h = p[kH];
  const std::size_t distinct = s.cosines.size();
  std::vector<double> hv(jacobian != nullptr ? 2 * distinct : distinct);
  for (std::size_t c = 0; c < distinct; ++c) {
    const double x = s.cosines[c];
    if (jacobian == nullptr) {
      hv[c] = h_function(x, w);
    } else if (h_function_ == HFunction::kExact && hapke::h_table_covers(x, w)) {
      // One table evaluation gives H (the same value as without the derivative) and dH/dgamma.
      double dh_dgamma = 0.0;
      const double gamma = std::sqrt(1.0 - w);
      hv[c] = hapke::h_table_evaluate(x, gamma, &dh_dgamma);
      hv[distinct + c] = gamma > 0.0 ? -0.5 * dh_dgamma / gamma : 0.0;
    } else {
      hv[c] = h_function(x, w);
      hv[distinct + c] = h_function(x, Jet1(w, 0)).v[0];
    }
  }
  const std::size_t P = static_cast<std::size_t>(parameter_count_);
  for (std::size_t k = 0; k < n; ++k) {
    const Prepared& q = g[k];
    const double b = opposition(b0, h, q.tan_half_g);
    const double phase = phase_function(p, q.cos_g);
    const double h0 = hv[s.index_i[k]], h1 = hv[s.index_r[k]];
    const double bracket = (1.0 + b) * phase + (h0 * h1 - 1.0);
    values[k] = w * q.scale * bracket;
    if (jacobian == nullptr) continue;
    double* d = jacobian + k * P;
    const double ws = w * q.scale;
    const double dh0 = hv[distinct + s.index_i[k]], dh1 = hv[distinct + s.index_r[k]];
    d[kW] = q.scale * bracket + ws * (dh0 * h1 + h0 * dh1);
    if (q.tan_half_g < std::numeric_limits<double>::infinity()) {
      const double denominator = h + q.tan_half_g;
      d[kB0] = ws * phase * h / denominator;
      d[kH] = ws * phase * b0 * q.tan_half_g / (denominator * denominator);
    } else {
      d[kB0] = 0.0;
      d[kH] = 0.0;
    }
    const double forward = ws * (1.0 + b);
    switch (phase_) {
      case Phase::kLegendre:
        if (legendre_terms_ != 2) {
          double legendre_p[hapke::kMaxLegendreTerms + 1];
          hapke::legendre_polynomials(q.cos_g, legendre_terms_, legendre_p);
          for (int t = 1; t <= legendre_terms_; ++t) d[kLegendreB + t - 1] = forward * legendre_p[t];
          break;
        }
        d[kLegendreB] = forward * q.cos_g;
        d[kLegendreC] = forward * (1.5 * q.cos_g * q.cos_g - 0.5);
        break;
      case Phase::kDoubleHenyeyGreenstein: {
        const double width = p[kHg2B], c = p[kHg2C];
        d[kHg2B] = forward * (-0.5 * (1.0 + c) * henyey_greenstein_derivative(-width, q.cos_g) +
                              0.5 * (1.0 - c) * henyey_greenstein_derivative(width, q.cos_g));
        d[kHg2C] = forward * 0.5 * (henyey_greenstein(-width, q.cos_g) - henyey_greenstein(width, q.cos_g));
        break;
      }
      case Phase::kHenyeyGreenstein:
        d[kXi] = forward * henyey_greenstein_derivative(p[kXi], q.cos_g);
        break;
    }
  }
}

void Hapke::evaluate_with_jets(const Prepared* g, std::size_t n, const double* p, double* values,
                               double* jacobian) const {
  const std::size_t count = static_cast<std::size_t>(parameter_count_);
  if (jacobian == nullptr) {
    for (std::size_t k = 0; k < n; ++k) values[k] = (*this)(p, g[k]);
    return;
  }
  using Jet = ceres::Jet<double, kMaxParameters>;
  Jet q[kMaxParameters];
  for (std::size_t k = 0; k < count; ++k) q[k] = Jet(p[k], static_cast<int>(k));
  for (std::size_t k = 0; k < n; ++k) {
    const Jet f = (*this)(q, g[k]);
    values[k] = f.a;
    for (std::size_t j = 0; j < count; ++j) jacobian[k * count + j] = f.v[static_cast<int>(j)];
  }
}

}  // namespace roadbrdf
