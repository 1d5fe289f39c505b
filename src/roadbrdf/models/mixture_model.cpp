#include "roadbrdf/models/mixture_model.h"

#include <algorithm>
#include <cmath>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/models/hapke_imsa.h"

namespace roadbrdf::mixing {

ModelDescription MixtureModel::make_description(MixtureKind kind,
                                                const std::vector<std::shared_ptr<const Model>>& components,
                                                const std::vector<std::string>& names) {
  if (components.empty()) throw InputError("a mixture needs at least one end-member");
  if (names.size() != components.size()) throw InputError("mixture: one name per end-member is needed");
  ModelDescription d;
  d.name = "mixture-" + name_of(kind);
  d.citation = kind == MixtureKind::kHapke
                   ? "Hapke 1981 (JGR 86:3039) eq. 17 intimate mixing, IMSA with H1; see mixing/mixture_model.h"
                   : "areal mixing; see mixing/mixture_model.h";
  d.summary = description_of(kind);
  const std::size_t K = components.size();
  for (std::size_t k = 0; k < K; ++k) {
    d.parameters.push_back({"weight." + names[k], "1",
                            kind == MixtureKind::kHapke
                                ? "cross-section weight M/(rho D) of " + names[k] + " (normalised)"
                                : "area fraction of " + names[k],
                            1.0 / K, 0.0, 1e3, true, kind == MixtureKind::kLinear});
  }
  if (kind == MixtureKind::kHapke) {
    for (std::size_t k = 0; k < K; ++k) {
      d.parameters.push_back(
          {"ssa." + names[k], "1",
           "single-scattering albedo w of " + names[k] + " (inverted from its white-sky albedo, IMSA H1)", 0.5, 0.0,
           1.0, true, false});
    }
  }
  if (kind == MixtureKind::kShadowed) {
    d.parameters.push_back({"shadowing", "1",
                            "shadowing coefficient s: matrix lit-and-seen fraction exp(-s (tan theta_i + tan theta_r))",
                            0.0, 0.0, 100.0, false, false});
  }
  bool reciprocal = true, non_negative = kind != MixtureKind::kHapke;
  d.mirror_lobe = false;  // unless an end-member has one (the mixing itself adds none)
  for (std::size_t k = 0; k < K; ++k) {
    const ModelDescription& c = components[k]->description();
    for (const ParameterInfo& p : c.parameters) {
      ParameterInfo q = p;
      q.name = names[k] + "." + p.name;
      q.linear = false;
      d.parameters.push_back(q);
    }
    reciprocal = reciprocal && c.reciprocal;
    non_negative = non_negative && c.non_negative;
    d.has_delta = d.has_delta || c.has_delta;
    d.mirror_lobe = d.mirror_lobe || c.mirror_lobe;
    combine_isotropy(d, c, names[k]);
  }
  // Grazing directions: the mixing adds no divergence (the shadowed kind's S = exp(-s (tan theta_i +
  // tan theta_r)) tends to 0, the hapke kind's multiple-scattering correction has a finite limit,
  // MultipleScatteringWeights), so the mixture's limit is that of its end-members' values, unless one of
  // them diverges, where the mixture (positive weights) diverges too: the value there is 0, declared as
  // the end-members declare it (grazing_zero_at).
  // Nested models: each end-member's model alone, at its weight 1 and the others 0 (the hapke kind's
  // w_mix is then w_k and its correction vanishes; the shadowed kind still shades a matrix end-member by
  // S, so there also shadowing = 0 unless no end-member is coarse, which the description cannot know).
  for (std::size_t k = 0; k < K; ++k) {
    const ModelDescription& c = components[k]->description();
    if (!c.grazing_zero.empty()) {
      d.grazing_zero += (d.grazing_zero.empty() ? "0 where an end-member's value is its declared 0, " : "; ") +
                        names[k] + ": " + c.grazing_zero;
    }
    std::string values = "weight." + names[k] + " = 1";
    if (K > 1) values += ", the other weights 0";
    if (kind == MixtureKind::kShadowed) values += ", shadowing = 0 (or " + names[k] + " coarse)";
    d.reduces_to.emplace_back(c.name, values);
  }
  d.reciprocal = reciprocal;
  d.non_negative = non_negative;
  d.energy_conserving = false;  // weights are free (fitted mixtures need not sum to one)
  return d;
}

MixtureModel::MixtureModel(MixtureKind kind, std::vector<std::shared_ptr<const Model>> components,
                           std::vector<std::string> names, std::vector<bool> coarse)
    : Model(make_description(kind, components, names)),
      kind_(kind),
      components_(std::move(components)),
      names_(std::move(names)),
      coarse_(std::move(coarse)) {
  if (coarse_.empty()) coarse_.assign(components_.size(), false);
  if (coarse_.size() != components_.size()) throw InputError("mixture: one coarse flag per end-member is needed");
  const std::size_t K = components_.size();
  std::size_t offset = K + (kind_ == MixtureKind::kHapke ? K : 0) + (kind_ == MixtureKind::kShadowed ? 1 : 0);
  for (std::size_t k = 0; k < K; ++k) {
    offsets_.push_back(offset);
    offset += components_[k]->parameter_count();
    max_component_parameters_ = std::max(max_component_parameters_, components_[k]->parameter_count());
  }
}

namespace {

// The multiple-scattering bracket of the hapke kind without its cancellation. With H1(x) = 1 + x h(x),
// h(x) = 2 (1 - gamma) / (1 + 2 x gamma) (hapke_imsa.h), and w_mix = sum_k c_k w_k,
//   [w_mix H(mu0) H(mu) - sum_k c_k w_k H_k(mu0) H_k(mu)] / (mu0 + mu) = T(w_mix) - sum_k c_k T(w_k),
//   T(w) = w [a h(mu0) + b h(mu) + mu0 mu / (mu0 + mu) h(mu0) h(mu)],  a = mu0 / (mu0 + mu), b = 1 - a,
// since the constant terms w_mix - sum_k c_k w_k cancel exactly. Evaluated as written, the bracket is a
// difference of O(w) numbers divided by mu0 + mu, which near both horizons (mu0 + mu ~ 1e-16 at 90 deg)
// turns rounding into values of the order of the BRDF; T is bounded (a, b in [0, 1]) and continuous. At
// mu0 = mu = 0 its limit, 2 w (1 - gamma), does not depend on the direction of approach (h(0) = 2 (1 -
// gamma) whatever a and b): the mixture's correction has a finite limit at every grazing geometry.
struct MultipleScatteringWeights {
  explicit MultipleScatteringWeights(const Geometry& g) : mu0(g.cos_theta_i()), mu(g.cos_theta_r()) {
    const double sum = mu0 + mu;
    a = sum > 0.0 ? mu0 / sum : 0.5;
    cross = sum > 0.0 ? mu0 * mu / sum : 0.0;
  }
  double term(double w) const {
    const double gamma = std::sqrt(std::max(0.0, 1.0 - w));
    const double h0 = 2.0 * (1.0 - gamma) / (1.0 + 2.0 * mu0 * gamma);
    const double h = 2.0 * (1.0 - gamma) / (1.0 + 2.0 * mu * gamma);
    return w * (a * h0 + (1.0 - a) * h + cross * h0 * h);
  }
  double mu0, mu, a, cross;
};

}  // namespace

double MixtureModel::shadowing_factor(double s, const Geometry& g) {
  if (s <= 0.0) return 1.0;
  const double ci = std::max(g.cos_theta_i(), 1e-300);
  const double cr = std::max(g.cos_theta_r(), 1e-300);
  const double ti = std::sqrt(std::max(0.0, 1.0 - ci * ci)) / ci;
  const double tr = std::sqrt(std::max(0.0, 1.0 - cr * cr)) / cr;
  return std::exp(-s * (ti + tr));
}

double MixtureModel::combine(const double* p, const Geometry& g, const double* f, double* d_df) const {
  const std::size_t K = components_.size();
  switch (kind_) {
    case MixtureKind::kLinear: {
      double sum = 0.0;
      for (std::size_t k = 0; k < K; ++k) {
        sum += p[k] * f[k];
        if (d_df) d_df[k] = p[k];
      }
      return sum;
    }
    case MixtureKind::kHapke: {
      double total = 0.0;
      for (std::size_t k = 0; k < K; ++k) total += p[k];
      if (!(total > 0.0)) throw InputError("hapke mixture: the cross-section weights sum to zero");
      const MultipleScatteringWeights weights(g);
      double linear = 0.0, w_mix = 0.0, ms_components = 0.0;
      for (std::size_t k = 0; k < K; ++k) {
        const double c = p[k] / total;
        const double w = p[K + k];
        linear += c * f[k];
        w_mix += c * w;
        ms_components += c * weights.term(w);
        if (d_df) d_df[k] = c;
      }
      return linear + (weights.term(w_mix) - ms_components) / (4.0 * kPi);
    }
    case MixtureKind::kShadowed: {
      double a_matrix = 0.0, a_coarse = 0.0;
      for (std::size_t k = 0; k < K; ++k) (coarse_[k] ? a_coarse : a_matrix) += p[k];
      // Without coarse end-members S does not enter; with coarse weights all zero the matrix is still
      // attenuated by S (the limit of the fitted form; nothing replaces the hidden area).
      const bool any_coarse = std::find(coarse_.begin(), coarse_.end(), true) != coarse_.end();
      const double S = any_coarse ? shadowing_factor(p[K], g) : 1.0;
      const double boost = a_coarse > 0.0 ? 1.0 + (1.0 - S) * a_matrix / a_coarse : 1.0;
      double sum = 0.0;
      for (std::size_t k = 0; k < K; ++k) {
        const double e = p[k] * (coarse_[k] ? boost : S);
        sum += e * f[k];
        if (d_df) d_df[k] = e;
      }
      return sum;
    }
  }
  return 0.0;
}

bool MixtureModel::grazing_zero_at(const Geometry& g, const double* f) const {
  if (!g.grazing_i() && !g.grazing_r()) return false;
  for (std::size_t k = 0; k < components_.size(); ++k) {
    if (f[k] == 0.0 && !components_[k]->description().grazing_zero.empty()) return true;
  }
  return false;
}

double MixtureModel::evaluate(const double* params, const Geometry& g) const {
  const std::size_t K = components_.size();
  double f[64];
  std::vector<double> big;
  double* values = f;
  if (K > 64) {
    big.resize(K);
    values = big.data();
  }
  for (std::size_t k = 0; k < K; ++k) values[k] = components_[k]->evaluate(params + offsets_[k], g);
  if (grazing_zero_at(g, values)) return 0.0;
  return combine(params, g, values, nullptr);
}

double MixtureModel::evaluate_with_gradient(const double* params, const Geometry& g, double* gradient) const {
  const std::size_t K = components_.size();
  const std::size_t n = parameter_count();
  std::vector<double> f(K), e(K), component_gradient(max_component_parameters_);
  std::fill(gradient, gradient + n, 0.0);
  for (std::size_t k = 0; k < K; ++k) {
    f[k] = components_[k]->evaluate_with_gradient(params + offsets_[k], g, component_gradient.data());
    for (std::size_t q = 0; q < components_[k]->parameter_count(); ++q)
      gradient[offsets_[k] + q] = component_gradient[q];
  }
  if (grazing_zero_at(g, f.data())) {
    std::fill(gradient, gradient + n, 0.0);
    return 0.0;
  }
  const double value = combine(params, g, f.data(), e.data());
  for (std::size_t k = 0; k < K; ++k) {
    for (std::size_t q = 0; q < components_[k]->parameter_count(); ++q) gradient[offsets_[k] + q] *= e[k];
  }
  // Mixture-level parameters: the linear kind is analytic, the others by central differences of
  // combine() with the end-member values held (one-sided at the bounds).
  const std::size_t m = mixing_parameter_count();
  if (kind_ == MixtureKind::kLinear) {
    for (std::size_t k = 0; k < K; ++k) gradient[k] = f[k];
    return value;
  }
  std::vector<double> p(params, params + n);
  for (std::size_t q = 0; q < m; ++q) {
    const ParameterInfo& info = description_.parameters[q];
    const double x = params[q];
    const double h = 1e-6 * std::max(1.0, std::fabs(x));
    const double up = std::min(info.upper, x + h), down = std::max(info.lower, x - h);
    if (!(up > down)) continue;
    p[q] = up;
    const double f_up = combine(p.data(), g, f.data(), nullptr);
    p[q] = down;
    const double f_down = combine(p.data(), g, f.data(), nullptr);
    p[q] = x;
    gradient[q] = (f_up - f_down) / (up - down);
  }
  return value;
}

void MixtureModel::evaluate_batch(const Geometry* geometries, std::size_t n_geometries, const double* params,
                                  std::size_t n_sets, double* out) const {
  const std::size_t K = components_.size();
  const std::size_t n_params = parameter_count();
  // End-member values for every geometry and set, then combine.
  std::vector<std::vector<double>> component_values(K);
  for (std::size_t k = 0; k < K; ++k) {
    const std::size_t pk = components_[k]->parameter_count();
    std::vector<double> sets(n_sets * pk);
    for (std::size_t s = 0; s < n_sets; ++s) {
      std::copy(params + s * n_params + offsets_[k], params + s * n_params + offsets_[k] + pk, sets.begin() + s * pk);
    }
    component_values[k].resize(n_geometries * n_sets);
    components_[k]->evaluate_batch(geometries, n_geometries, sets.data(), n_sets, component_values[k].data());
  }
  std::vector<double> f(K);
  for (std::size_t n = 0; n < n_geometries; ++n) {
    for (std::size_t s = 0; s < n_sets; ++s) {
      for (std::size_t k = 0; k < K; ++k) f[k] = component_values[k][n * n_sets + s];
      out[n * n_sets + s] = grazing_zero_at(geometries[n], f.data())
                                ? 0.0
                                : combine(params + s * n_params, geometries[n], f.data(), nullptr);
    }
  }
}

void MixtureModel::evaluate_batch_with_gradient(const Geometry* geometries, std::size_t n_geometries,
                                                const double* params, double* values, double* jacobian) const {
  const std::size_t n_params = parameter_count();
  for (std::size_t n = 0; n < n_geometries; ++n) {
    values[n] = evaluate_with_gradient(params, geometries[n], jacobian + n * n_params);
  }
}

double MixtureModel::delta_reflectance(const double* params, double cos_theta_i) const {
  if (!description_.has_delta) return 0.0;
  const std::size_t K = components_.size();
  std::vector<double> r(K), e(K);
  for (std::size_t k = 0; k < K; ++k) r[k] = components_[k]->delta_reflectance(params + offsets_[k], cos_theta_i);
  // Weights at the mirror geometry; the hapke multiple-scattering term has no delta part.
  const double theta = std::acos(std::clamp(cos_theta_i, 0.0, 1.0));
  const Geometry mirror = geometry_from_radians(theta, 0.0, theta, kPi);
  std::vector<double> unit(K, 0.0);
  double sum = 0.0;
  for (std::size_t k = 0; k < K; ++k) {
    std::fill(unit.begin(), unit.end(), 0.0);
    unit[k] = 1.0;
    double base = 0.0;
    if (kind_ == MixtureKind::kHapke) {
      double total = 0.0;
      for (std::size_t j = 0; j < K; ++j) total += params[j];
      base = params[k] / total;
    } else {
      // combine() is linear in f with no constant term for these kinds.
      base = combine(params, mirror, unit.data(), nullptr);
    }
    sum += base * r[k];
  }
  return sum;
}

}  // namespace roadbrdf::mixing
