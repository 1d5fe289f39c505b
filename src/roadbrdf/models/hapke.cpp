// The hapke model's factory: its adapter and the fitter's Jet instantiations compile here (model_factory.h),
// and its analytic gradient path.
#include "roadbrdf/models/hapke.h"
#include "roadbrdf/models/model_factory.h"

#include <cstddef>
#include <vector>

namespace roadbrdf {

ModelFactory hapke_factory() { return factory_of<Hapke>(); }

// The fixed parameter sets (see FixedSets in hapke.h).
void Hapke::evaluate_fixed(const FixedSets& f, const Geometry& geometry, double* out) const {
  const Prepared q = prepare(geometry);
  hapke::HTablePoint point_i, point_r;
  const bool inside = h_function_ == HFunction::kExact && f.by_operator.size() < f.n_sets && q.mu0 > 0.0 &&
                      q.mu > 0.0 && hapke::h_table_point(q.mu0, point_i) && hapke::h_table_point(q.mu, point_r);
  if (!inside) {
    for (std::size_t s = 0; s < f.n_sets; ++s) out[s] = (*this)(f.params.data() + s * f.n_params, q);
    return;
  }
  constexpr std::size_t kChunk = 16;
  const std::size_t n = f.n_sets;
  const double* rows_i = f.series.data() + static_cast<std::size_t>(point_i.octave) * hapke::kHTableNodesX * n;
  const double* rows_r = f.series.data() + static_cast<std::size_t>(point_r.octave) * hapke::kHTableNodesX * n;
  for (std::size_t first = 0; first < n; first += kChunk) {
    const std::size_t m = std::min(kChunk, n - first);
    double h_i[kChunk] = {}, h_r[kChunk] = {}, phase[kChunk];
    for (int a = 0; a < hapke::kHTableNodesX; ++a) {
      const double* row_i = rows_i + a * n + first;
      const double* row_r = rows_r + a * n + first;
      const double t_i = point_i.tx[a], t_r = point_r.tx[a];
      for (std::size_t s = 0; s < m; ++s) {
        h_i[s] += row_i[s] * t_i;
        h_r[s] += row_r[s] * t_r;
      }
    }
    const double* p1 = f.p1.data() + first;
    const double* p2 = f.p2.data() + first;
    switch (phase_) {
      case Phase::kLegendre:
        if (legendre_terms_ != 2) {
          for (std::size_t s = 0; s < m; ++s) {
            phase[s] = hapke::legendre_series(f.params.data() + (first + s) * f.n_params + kLegendreB, legendre_terms_,
                                              q.cos_g);
          }
          break;
        }
        for (std::size_t s = 0; s < m; ++s) phase[s] = legendre(p1[s], p2[s], q.cos_g);
        break;
      case Phase::kDoubleHenyeyGreenstein:
        for (std::size_t s = 0; s < m; ++s) phase[s] = double_henyey_greenstein(p1[s], p2[s], q.cos_g);
        break;
      case Phase::kHenyeyGreenstein:
        for (std::size_t s = 0; s < m; ++s) phase[s] = henyey_greenstein(p1[s], q.cos_g);
        break;
    }
    const double* w = f.w.data() + first;
    const double* b0 = f.b0.data() + first;
    const double* h = f.h.data() + first;
    double* o = out + first;
    if (q.tan_half_g < std::numeric_limits<double>::infinity()) {
      for (std::size_t s = 0; s < m; ++s) {
        const double b = b0[s] * h[s] / (h[s] + q.tan_half_g);  // opposition(), written out to vectorise
        o[s] = w[s] * q.scale * ((1.0 + b) * phase[s] + (h_i[s] * h_r[s] - 1.0));
      }
    } else {
      for (std::size_t s = 0; s < m; ++s)
        o[s] = w[s] * q.scale * (phase[s] + (h_i[s] * h_r[s] - 1.0));  // B = 0 at g = pi
    }
  }
  for (std::size_t s : f.by_operator) out[s] = (*this)(f.params.data() + s * f.n_params, q);
}

namespace {

// Hapke::henyey_greenstein (the same expression, so the same value bit for bit) and its derivative in
// xi from the same D and sqrt(D): with r = 1/(D sqrt D), dp/dxi = -[2 xi r + 3 p (cos g + xi) r sqrt D],
// one division and no second square root (equal to henyey_greenstein_derivative to rounding).
double henyey_greenstein_and_derivative(double xi, double cos_g, double& derivative) {
  const double xi2 = xi * xi;
  const double base = 1.0 + 2.0 * xi * cos_g + xi2;
  const double root = std::sqrt(base);
  const double base_root = base * root;
  const double p = (1.0 - xi2) / base_root;
  const double r = 1.0 / base_root;
  derivative = -(2.0 * xi * r + 3.0 * p * (cos_g + xi) * (r * root));
  return p;
}

}  // namespace

// Value and analytic gradient of f = w s {[1 + B] p + H(mu0) H(mu) - 1}, s = 1/(4 pi (mu0 + mu)),
// B = b0 h/(h + t), t = tan(g/2):
//   df/dw  = s {...} + w s [H'(mu0) H(mu) + H(mu0) H'(mu)]        (H' = dH/dw, per distinct cosine)
//   df/db0 = w s p h/(h + t),   df/dh = w s p b0 t/(h + t)^2       (0 at g = pi, where B = 0; one
//            reciprocal of h + t for both, the value's B keeps operator()'s division)
//   HG:       df/dxi = w s (1 + B) dp/dxi, dp/dxi = -[2 xi + 3 (1 - xi^2)(cos g + xi)/D] / D^1.5,
//             D = 1 + 2 xi cos g + xi^2 (from the value's D and sqrt D, henyey_greenstein_and_derivative)
//   Legendre: df/db = w s (1 + B) cos g,   df/dc = w s (1 + B) (3 cos^2 g - 1)/2;
//             N terms: df/da_n = w s (1 + B) P_n(cos g).
//   hg2:      df/db = w s (1 + B) [-(1 + c)/2 HG'(-b) + (1 - c)/2 HG'(b)],
//             df/dc = w s (1 + B) [HG(-b) - HG(b)]/2   (HG' = dp/dxi of the HG line).
// The value is computed by the same expressions as operator() (same rounding, bit for bit); dH/dw is
// that of the ceres::Jet path of h_function, so the gradient equals the automatic derivative to
// rounding. Every gradient path of the model (single, batch, prepared) comes here, so they agree
// with each other bit for bit. With roughness = hapke1984: evaluate_with_jets. With AMSA (Hapke 2002):
//   df/dw = s {...} + w s [P(mu0) H'(mu) + P(mu) H'(mu0) + P-bar (H'(mu0) (H(mu) - 1) + (H(mu0) - 1) H'(mu))],
//   df/da_n += w s A_n [P_n(mu0) (H(mu) - 1) + P_n(mu) (H(mu0) - 1) + A_n (H(mu0) - 1)(H(mu) - 1)].
void Hapke::evaluate_shared(const SharedTerms& s, const Prepared* g, std::size_t n, const double* p, double* values,
                            double* jacobian) const {
  if (roughness_) return evaluate_with_jets(s, g, n, p, values, jacobian);
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
    // Henyey-Greenstein with a gradient: its value and derivative from one D and sqrt(D).
    double hg_derivative = 0.0;
    const bool hg_gradient = jacobian != nullptr && phase_ == Phase::kHenyeyGreenstein;
    const double phase =
        hg_gradient ? henyey_greenstein_and_derivative(p[kXi], q.cos_g, hg_derivative) : phase_function(p, q.cos_g);
    const double h0 = hv[s.index_i[k]], h1 = hv[s.index_r[k]];
    const double bracket = (1.0 + b) * phase + multiple_scattering(p, q.mu0, q.mu, h0, h1);
    values[k] = w * q.scale * bracket;
    if (jacobian == nullptr) continue;
    double* d = jacobian + k * P;
    const double ws = w * q.scale;
    const double dh0 = hv[distinct + s.index_i[k]], dh1 = hv[distinct + s.index_r[k]];
    if (anisotropic_) {
      const double* a = p + kLegendreB;
      const double p0 = hapke::hemisphere_average(a, legendre_terms_, q.mu0);
      const double p1 = hapke::hemisphere_average(a, legendre_terms_, q.mu);
      const double p_bar = hapke::double_hemisphere_average(a, legendre_terms_);
      d[kW] = q.scale * bracket + ws * (p0 * dh1 + p1 * dh0 + p_bar * (dh0 * (h1 - 1.0) + (h0 - 1.0) * dh1));
    } else {
      d[kW] = q.scale * bracket + ws * (dh0 * h1 + h0 * dh1);
    }
    if (q.tan_half_g < std::numeric_limits<double>::infinity()) {
      // One reciprocal of h + tan(g/2) serves both derivatives.
      const double inverse = 1.0 / (h + q.tan_half_g);
      const double ws_phase_inverse = ws * phase * inverse;
      d[kB0] = ws_phase_inverse * h;
      d[kH] = ws_phase_inverse * b0 * q.tan_half_g * inverse;
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
        d[kXi] = forward * hg_derivative;
        break;
    }
    if (anisotropic_) {
      // AMSA: d/da_n of A_n a_n [P_n(mu0) (H1 - 1) + P_n(mu) (H0 - 1) + A_n (H0 - 1)(H1 - 1)], odd n only.
      double at_mu0[hapke::kMaxLegendreTerms + 1], at_mu[hapke::kMaxLegendreTerms + 1];
      hapke::legendre_polynomials(q.mu0, legendre_terms_, at_mu0);
      hapke::legendre_polynomials(q.mu, legendre_terms_, at_mu);
      for (int t = 1; t <= legendre_terms_; t += 2) {
        const double moment = hapke::hemisphere_moment(t);
        d[kLegendreB + t - 1] +=
            ws * moment * (at_mu0[t] * (h1 - 1.0) + at_mu[t] * (h0 - 1.0) + moment * (h0 - 1.0) * (h1 - 1.0));
      }
    }
  }
}

namespace {

// Values and Jacobian by ceres::Jet<double, N>, N >= the parameter count (each operation costs in
// proportion to N, so the smallest size that holds the parameters is used).
template <int N>
void evaluate_by_jets(const Hapke& model, const Hapke::SharedTerms& s, const Hapke::Prepared* g, std::size_t n,
                      const double* p, double* values, double* jacobian) {
  using Jet = ceres::Jet<double, N>;
  const std::size_t count = static_cast<std::size_t>(model.parameter_count());
  Jet q[N];
  for (std::size_t k = 0; k < count; ++k) q[k] = Jet(p[k], static_cast<int>(k));
  model.evaluate_rough(s, g, n, q, [&](std::size_t k, const Jet& f) {
    values[k] = f.a;
    for (std::size_t j = 0; j < count; ++j) jacobian[k * count + j] = f.v[static_cast<int>(j)];
  });
}

}  // namespace

void Hapke::evaluate_with_jets(const SharedTerms& s, const Prepared* g, std::size_t n, const double* p, double* values,
                               double* jacobian) const {
  if (jacobian == nullptr) {
    evaluate_rough(s, g, n, p, [values](std::size_t k, double f) { values[k] = f; });
  } else if (parameter_count_ <= 5) {
    evaluate_by_jets<5>(*this, s, g, n, p, values, jacobian);
  } else if (parameter_count_ <= 8) {
    evaluate_by_jets<8>(*this, s, g, n, p, values, jacobian);
  } else {
    evaluate_by_jets<kMaxParameters>(*this, s, g, n, p, values, jacobian);
  }
}

}  // namespace roadbrdf
