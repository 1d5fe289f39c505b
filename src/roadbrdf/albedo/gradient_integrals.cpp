#include "roadbrdf/albedo/gradient_integrals.h"

#include "roadbrdf/albedo/black_sky_integrator.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace roadbrdf::albedo {

namespace {

// The integrand of a gradient integral as a Model, so that the adaptive rules of hemisphere.h
// integrate it unchanged: each "parameter set" of this model is one component, P + 3 values
// [p_0 .. p_{P-1}, k, scale, leader] (the set's parameters, the parameter differentiated, its scale,
// the first component of the same set), of value scale df(p)/dp_k, or the value f(p) itself for
// k = P (the components that steer a gradient on its value's nodes). evaluate_sets() evaluates each
// set once per geometry (value and full gradient) and hands every component of it its part.
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
    d.parameters.push_back({"derivative_leader", "1", "first component of the same set", 0.0, 0.0, 1e18, false});
    return d;
  }

  void evaluate_batch(const Geometry* geometries, std::size_t n_geometries, const double* params, std::size_t n_sets,
                      double* out) const override {
    evaluate_sets(geometries, n_geometries, params, n_sets, out);
  }

  void evaluate_sets(const Geometry* geometries, std::size_t n_geometries, const double* params, std::size_t n_sets,
                     double* out) const override {
    const std::size_t W = P_ + 3;
    // The components of each set, as lists threaded through `next` from their leader.
    constexpr std::size_t kEnd = static_cast<std::size_t>(-1);
    std::vector<std::size_t> next(n_sets, kEnd), head(n_sets, kEnd);
    for (std::size_t c = n_sets; c-- > 0;) {
      const auto leader = static_cast<std::size_t>(params[c * W + P_ + 2]);
      if (leader >= n_sets) throw std::logic_error("gradient integral: component leader out of range");
      next[c] = head[leader];
      head[leader] = c;
    }
    const std::unique_ptr<PreparedGeometries> prepared = base_.prepare(geometries, n_geometries);
    std::vector<double> values(n_geometries), jacobian(n_geometries * P_), first_values;
    // A model affine in every parameter has the same gradient at every set (its kernels): one
    // evaluation serves all components, and a set's values are f(p_0) + J (p - p_0).
    const bool constant_gradient = affine_ && n_sets > 1;
    const double* p0 = nullptr;
    for (std::size_t leader = 0; leader < n_sets; ++leader) {
      if (head[leader] == kEnd) continue;
      const double* p = params + leader * W;
      if (p0 == nullptr || !constant_gradient) {
        base_.evaluate_prepared_with_gradient(*prepared, p, values.data(), jacobian.data());
        if (p0 == nullptr) {
          p0 = p;
          first_values = values;
        }
      } else {
        for (std::size_t n = 0; n < n_geometries; ++n) {
          double f = first_values[n];
          for (std::size_t k = 0; k < P_; ++k) f += jacobian[n * P_ + k] * (p[k] - p0[k]);
          values[n] = f;
        }
      }
      for (std::size_t c = head[leader]; c != kEnd; c = next[c]) {
        const auto k = static_cast<std::size_t>(params[c * W + P_]);
        const double scale = params[c * W + P_ + 1];
        for (std::size_t n = 0; n < n_geometries; ++n) {
          out[n * n_sets + c] = k == P_ ? values[n] : scale * jacobian[n * P_ + k];
        }
      }
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
    if (k == P_) return base_.delta_reflectance(params, cos_theta_i);
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

// The components wanted (scale > 0), as parameter sets of ScaledDerivativeModel; with `values`,
// preceded by the value of every set (those steer the refinement, GradientNodes::value_nodes).
struct Components {
  std::vector<double> params;           // n x (P + 3)
  std::vector<std::size_t> set, index;  // per component: its set s and parameter k (P: the value)
  std::vector<double> scale;
  std::size_t size() const { return set.size(); }
  void add(const double* p, std::size_t P, std::size_t s, std::size_t k, double u, std::size_t leader) {
    params.insert(params.end(), p, p + P);
    params.push_back(static_cast<double>(k));
    params.push_back(u);
    params.push_back(static_cast<double>(leader));
    set.push_back(s);
    index.push_back(k);
    scale.push_back(u);
  }
};

Components components_of(const double* params, std::size_t n_sets, std::size_t P, const std::vector<double>& scale,
                         bool values) {
  if (scale.size() != n_sets * P) throw std::logic_error("gradient integral: scale is not n_sets x P");
  Components c;
  if (values) {
    for (std::size_t s = 0; s < n_sets; ++s) c.add(params + s * P, P, s, P, 1.0, s);
  }
  for (std::size_t s = 0; s < n_sets; ++s) {
    const std::size_t leader = values ? s : c.size();
    for (std::size_t k = 0; k < P; ++k) {
      const double u = scale[s * P + k];
      if (u > 0.0) c.add(params + s * P, P, s, k, u, leader);
    }
  }
  return c;
}

GradientIntegral unscaled(const Components& c, const SpectralIntegral& r, std::size_t n_sets, std::size_t P) {
  GradientIntegral g;
  g.gradient.assign(n_sets * P, 0.0);
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (c.index[i] < P) {
      g.gradient[c.set[i] * P + c.index[i]] = r.value[i] / c.scale[i];
    } else {  // a value component (components_of: the first n_sets, in set order)
      g.values.value.push_back(r.value[i]);
      g.values.error.push_back(r.error[i]);
    }
  }
  if (!g.values.value.empty()) {
    g.values.converged = r.converged;
    g.values.geometries = r.geometries;
  }
  g.converged = r.converged;
  g.geometries = r.geometries;
  return g;
}

// GradientNodes::value_nodes: the factor on the tolerance to which each component is still held
// (gradient_integrals.h). On the bench's 2151-band Hapke fit (docs/albedo.md) the values' nodes alone
// left u at normal incidence 0.9 % from a reference integrated to 1e-7, with this factor 0.2 %, while
// most of the saving over the components' own tolerance (factor 1) remains.
constexpr double kComponentToleranceFactor = 3.0;

// Settings of the integral of the components: with the values first, they steer at the tolerance
// and the components follow at kComponentToleranceFactor times it.
QuadratureSettings steered(const QuadratureSettings& settings, std::size_t n_sets, GradientNodes nodes) {
  QuadratureSettings s = settings;
  if (nodes == GradientNodes::value_nodes) {
    s.steering_sets = n_sets;
    s.follower_factor = kComponentToleranceFactor;
  }
  return s;
}

}  // namespace

GradientIntegral black_sky_gradient(const Model& model, const double* params, std::size_t n_sets,
                                    const std::vector<double>& scale, double theta_s, double phi_s, bool azimuth_mean,
                                    const QuadratureSettings& settings, GradientNodes nodes) {
  const std::size_t P = model.parameter_count();
  const Components c = components_of(params, n_sets, P, scale, nodes == GradientNodes::value_nodes);
  const ScaledDerivativeModel derivative(model);
  const QuadratureSettings s = steered(settings, n_sets, nodes);
  const SpectralIntegral r = azimuth_mean ? black_sky_azimuth_mean(derivative, c.params.data(), c.size(), theta_s, s)
                                          : black_sky(derivative, c.params.data(), c.size(), theta_s, phi_s, s);
  return unscaled(c, r, n_sets, P);
}

GradientIntegral white_sky_gradient(const Model& model, const double* params, std::size_t n_sets,
                                    const std::vector<double>& scale, const QuadratureSettings& settings,
                                    GradientNodes nodes) {
  const std::size_t P = model.parameter_count();
  const Components c = components_of(params, n_sets, P, scale, nodes == GradientNodes::value_nodes);
  const ScaledDerivativeModel derivative(model);
  // The reciprocity of the BRDF itself (its derivatives are then reciprocal too; their own check
  // would compare rounding noise of derivatives that vanish).
  const bool reciprocal = derivative.description().isotropic && detail::white_sky_reciprocal(model, params, n_sets);
  return unscaled(
      c,
      detail::white_sky_integral(derivative, c.params.data(), c.size(), steered(settings, n_sets, nodes), reciprocal),
      n_sets, P);
}

}  // namespace roadbrdf::albedo
