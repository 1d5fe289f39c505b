#include "roadbrdf/albedo/gradient_integrals.h"

#include "roadbrdf/albedo/black_sky_integrator.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace roadbrdf::albedo {

namespace {

// The integrand of a gradient integral as a Model, so that the adaptive rules of hemisphere.h
// integrate it unchanged: each "parameter set" of this model is one component, P + 2 values
// [p_0 .. p_{P-1}, k, scale] (the set's parameters, the parameter differentiated, its scale), of
// value scale df(p)/dp_k. Components of one set are consecutive, so that evaluate_batch() evaluates
// the set once per geometry (value and full gradient) and hands each component its derivative.
class ScaledDerivativeModel final : public Model, public detail::SetBatchIntegrand {
 public:
  explicit ScaledDerivativeModel(const Model& base)
      : Model(describe(base)),
        base_(base),
        P_(base.parameter_count()),
        affine_(detail::affine_in_every_parameter(base.description()) && gradient_is_constant(base)) {}

  // The affine claim of the metadata checked on the gradient itself: equal at two distant parameter
  // sets at a few scattered geometries (relative 1e-9).
  static bool gradient_is_constant(const Model& base) {
    const std::size_t P = base.parameter_count();
    const ModelDescription& d = base.description();
    std::vector<double> a(P), b(P);
    for (std::size_t k = 0; k < P; ++k) {
      a[k] = d.parameters[k].lower + 0.3 * (d.parameters[k].upper - d.parameters[k].lower);
      b[k] = d.parameters[k].lower + 0.8 * (d.parameters[k].upper - d.parameters[k].lower);
    }
    std::vector<Geometry> g;
    for (int i = 0; i < 6; ++i) g.push_back(geometry_from_radians(0.2 * i, 0.1, 0.25 * i + 0.1, 0.9 * i + 0.3));
    std::vector<double> f(g.size()), ja(g.size() * P), jb(g.size() * P);
    base.evaluate_batch_with_gradient(g.data(), g.size(), a.data(), f.data(), ja.data());
    base.evaluate_batch_with_gradient(g.data(), g.size(), b.data(), f.data(), jb.data());
    for (std::size_t i = 0; i < ja.size(); ++i) {
      if (!(std::fabs(ja[i] - jb[i]) <= 1e-9 * (std::fabs(ja[i]) + std::fabs(jb[i])) + 1e-300)) return false;
    }
    return true;
  }

  static ModelDescription describe(const Model& base) {
    ModelDescription d = base.description();
    // A derivative takes either sign: black_sky() must not prefer the larger of two estimates.
    d.non_negative = false;
    // A model isotropic only where pairs of its parameters are equal (Ashikhmin-Shirley n_u = n_v)
    // has anisotropic derivatives there (d/dn_u breaks the symmetry): they are integrated over every
    // azimuth.
    d.isotropic_when_equal.clear();
    d.parameters.push_back({"derivative_index", "1", "index of the parameter differentiated", 0.0, 0.0, 1e9, false});
    d.parameters.push_back({"derivative_scale", "1", "factor of the derivative", 1.0, 0.0, 1e300, false});
    return d;
  }

  void evaluate_batch(const Geometry* geometries, std::size_t n_geometries, const double* params, std::size_t n_sets,
                      double* out) const override {
    evaluate_sets(geometries, n_geometries, params, n_sets, out);
  }

  void evaluate_sets(const Geometry* geometries, std::size_t n_geometries, const double* params, std::size_t n_sets,
                     double* out) const override {
    const std::size_t W = P_ + 2;
    const std::unique_ptr<PreparedGeometries> prepared = base_.prepare(geometries, n_geometries);
    std::vector<double> values(n_geometries), jacobian(n_geometries * P_);
    // A model affine in every parameter has the same gradient at every set (its kernels): one
    // evaluation serves all components.
    const bool constant_gradient = affine_ && n_sets > 1;
    std::size_t c = 0;
    while (c < n_sets) {
      const double* p = params + c * W;
      if (c == 0 || !constant_gradient) {
        base_.evaluate_prepared_with_gradient(*prepared, p, values.data(), jacobian.data());
      }
      // Every following component of the same set takes its derivative from this evaluation.
      std::size_t end = c;
      do {
        const std::size_t k = static_cast<std::size_t>(params[end * W + P_]);
        const double scale = params[end * W + P_ + 1];
        for (std::size_t n = 0; n < n_geometries; ++n) out[n * n_sets + end] = scale * jacobian[n * P_ + k];
        ++end;
      } while (end < n_sets && std::equal(p, p + P_, params + end * W));
      c = end;
    }
  }

  double evaluate(const double* params, const Geometry& g) const override {
    double f = 0.0;
    evaluate_batch(&g, 1, params, 1, &f);
    return f;
  }

  // The ideal specular part R(p, cos theta_s) is a closed form: its derivative by a central
  // difference with a step far below the parameter's scale (relative error ~1e-8, negligible against
  // the integrals' tolerance), one-sided at the parameter's physical range.
  double delta_reflectance(const double* params, double cos_theta_i) const override {
    if (!base_.description().has_delta) return 0.0;
    const std::size_t k = static_cast<std::size_t>(params[P_]);
    const double scale = params[P_ + 1];
    const auto [lower, upper] = base_.description().physical_range(k);
    const double h = 1e-6 * std::max(1.0, std::fabs(params[k]));
    std::vector<double> up(params, params + P_), down = up;
    up[k] = std::min(params[k] + h, upper);
    down[k] = std::max(params[k] - h, lower);
    if (!(up[k] > down[k])) return 0.0;
    return scale *
           (base_.delta_reflectance(up.data(), cos_theta_i) - base_.delta_reflectance(down.data(), cos_theta_i)) /
           (up[k] - down[k]);
  }

  bool reads_angles() const override { return base_.reads_angles(); }

  // Not integrands of a quadrature: a derivative model is never fitted.
  double evaluate_with_gradient(const double*, const Geometry&, double*) const override {
    throw std::logic_error("ScaledDerivativeModel has no gradient");
  }
  void evaluate_batch_with_gradient(const Geometry*, std::size_t, const double*, double*, double*) const override {
    throw std::logic_error("ScaledDerivativeModel has no gradient");
  }

 private:
  const Model& base_;
  std::size_t P_;
  bool affine_;
};

// The components wanted (scale > 0), as parameter sets of ScaledDerivativeModel.
struct Components {
  std::vector<double> params;           // n x (P + 2)
  std::vector<std::size_t> set, index;  // per component: its set s and parameter k
  std::vector<double> scale;
  std::size_t size() const { return set.size(); }
};

Components components_of(const double* params, std::size_t n_sets, std::size_t P, const std::vector<double>& scale) {
  if (scale.size() != n_sets * P) throw std::logic_error("gradient integral: scale is not n_sets x P");
  Components c;
  for (std::size_t s = 0; s < n_sets; ++s) {
    for (std::size_t k = 0; k < P; ++k) {
      const double u = scale[s * P + k];
      if (!(u > 0.0)) continue;
      c.params.insert(c.params.end(), params + s * P, params + (s + 1) * P);
      c.params.push_back(static_cast<double>(k));
      c.params.push_back(u);
      c.set.push_back(s);
      c.index.push_back(k);
      c.scale.push_back(u);
    }
  }
  return c;
}

GradientIntegral unscaled(const Components& c, const SpectralIntegral& r, std::size_t n_sets, std::size_t P) {
  GradientIntegral g;
  g.gradient.assign(n_sets * P, 0.0);
  for (std::size_t i = 0; i < c.size(); ++i) g.gradient[c.set[i] * P + c.index[i]] = r.value[i] / c.scale[i];
  g.converged = r.converged;
  g.geometries = r.geometries;
  return g;
}

}  // namespace

GradientIntegral black_sky_gradient(const Model& model, const double* params, std::size_t n_sets,
                                    const std::vector<double>& scale, double theta_s, double phi_s, bool azimuth_mean,
                                    const QuadratureSettings& settings) {
  const std::size_t P = model.parameter_count();
  const Components c = components_of(params, n_sets, P, scale);
  const ScaledDerivativeModel derivative(model);
  const SpectralIntegral r = azimuth_mean
                                 ? black_sky_azimuth_mean(derivative, c.params.data(), c.size(), theta_s, settings)
                                 : black_sky(derivative, c.params.data(), c.size(), theta_s, phi_s, settings);
  return unscaled(c, r, n_sets, P);
}

GradientIntegral white_sky_gradient(const Model& model, const double* params, std::size_t n_sets,
                                    const std::vector<double>& scale, const QuadratureSettings& settings) {
  const std::size_t P = model.parameter_count();
  const Components c = components_of(params, n_sets, P, scale);
  const ScaledDerivativeModel derivative(model);
  // The reciprocity of the BRDF itself (its derivatives are then reciprocal too; their own check
  // would compare rounding noise of derivatives that vanish).
  const bool reciprocal = derivative.description().isotropic && detail::white_sky_reciprocal(model, params, n_sets);
  return unscaled(c, detail::white_sky_integral(derivative, c.params.data(), c.size(), settings, reciprocal), n_sets,
                  P);
}

}  // namespace roadbrdf::albedo
