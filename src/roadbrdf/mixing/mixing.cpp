#include "roadbrdf/mixing/mixing.h"

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <random>
#include <set>
#include <sstream>

#include "roadbrdf/core/error.h"
#include "roadbrdf/fitting/fit_file.h"
#include "roadbrdf/mixing/hapke_imsa.h"

namespace roadbrdf::mixing {

namespace {

std::string stem_of_fit(const std::string& path) {
  std::string name = std::filesystem::path(path).filename().string();
  for (const char* suffix : {".fit.json", ".json"}) {
    const std::string s(suffix);
    if (name.size() > s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0) {
      return name.substr(0, name.size() - s.size());
    }
  }
  return name;
}

double volume(const Component& c) { return c.mass_percent / c.density; }

bool in_binder_phase(const Component& c) {
  return c.kind == ComponentKind::kBinder || c.kind == ComponentKind::kPigment;
}

// Common wavelength range of a set of spectral models; lo > hi when disjoint.
void common_range(const std::vector<const SpectralModel*>& models, double& lo, double& hi, bool& any_spectral) {
  lo = -std::numeric_limits<double>::infinity();
  hi = std::numeric_limits<double>::infinity();
  any_spectral = false;
  for (const SpectralModel* m : models) {
    if (!m->is_spectral()) continue;
    any_spectral = true;
    lo = std::max(lo, m->wavelengths().front());
    hi = std::min(hi, m->wavelengths().back());
  }
}

// The output wavelength grid of a method over the given end-members.
std::vector<double> output_grid(const MixInputs& inputs, const std::vector<std::size_t>& members,
                                const MixSettings& settings, const SpectralDataset* data) {
  std::vector<const SpectralModel*> models;
  for (std::size_t e : members) models.push_back(inputs.end_members[e].model.get());
  double lo, hi;
  bool any;
  common_range(models, lo, hi, any);
  std::vector<double> grid;
  if (!settings.wavelengths.empty()) {
    grid = settings.wavelengths;
  } else if (data) {
    grid = data->wavelengths;
  } else {
    if (!any) return {};
    if (lo > hi) throw InputError("the end-members' fit files have no common wavelength range");
    std::set<double> nodes;
    for (const SpectralModel* m : models) {
      for (double w : m->wavelengths()) {
        if (w >= lo && w <= hi) nodes.insert(w);
      }
    }
    return {nodes.begin(), nodes.end()};
  }
  if (any) {
    for (double w : grid) {
      if (!(w >= lo && w <= hi)) {
        std::ostringstream msg;
        msg << "wavelength " << w << " nm is outside the common range [" << lo << ", " << hi
            << "] nm of the end-members' fits (no extrapolation)";
        throw InputError(msg.str());
      }
    }
  }
  return grid;
}

// Per-wavelength parameter table of a mixture: mixing parameters from `mixing(w_index, out)` then
// every end-member's parameters at the wavelength.
SpectralModel build_table(const std::shared_ptr<const MixtureModel>& mixture, const MixInputs& inputs,
                          const std::vector<std::size_t>& members, const std::vector<double>& grid,
                          const std::function<void(std::size_t, double*)>& mixing) {
  const std::size_t n = mixture->parameter_count();
  const std::size_t rows = grid.empty() ? 1 : grid.size();
  std::vector<double> table(rows * n);
  for (std::size_t r = 0; r < rows; ++r) {
    double* row = table.data() + r * n;
    mixing(r, row);
    for (std::size_t k = 0; k < members.size(); ++k) {
      const SpectralModel& m = *inputs.end_members[members[k]].model;
      const std::vector<double> p = grid.empty() ? m.parameter_table() : m.parameters_at(grid[r]);
      std::copy(p.begin(), p.end(), row + mixture->component_offset(k));
    }
  }
  if (grid.empty()) return SpectralModel(mixture, table);
  return SpectralModel(mixture, grid, table);
}

std::shared_ptr<const MixtureModel> make_mixture(MixtureKind kind, const MixInputs& inputs,
                                                 const std::vector<std::size_t>& members,
                                                 const std::vector<bool>& coarse = {}) {
  std::vector<std::shared_ptr<const Model>> models;
  std::vector<std::string> names;
  for (std::size_t e : members) {
    models.push_back(inputs.end_members[e].model->model_ptr());
    names.push_back(inputs.end_members[e].name);
  }
  return std::make_shared<MixtureModel>(kind, models, names, coarse);
}

// End-members used by the components (not the separate mastic fit), in order.
std::vector<std::size_t> component_members(const MixInputs& inputs) {
  std::vector<std::size_t> members;
  for (std::size_t e = 0; e < inputs.end_members.size(); ++e) {
    if (!inputs.end_members[e].components.empty()) members.push_back(e);
  }
  return members;
}

std::size_t member_position(const std::vector<std::size_t>& members, std::size_t e) {
  return static_cast<std::size_t>(std::find(members.begin(), members.end(), e) - members.begin());
}

std::size_t member_of_component(const MixInputs& inputs, std::size_t component) {
  for (std::size_t e = 0; e < inputs.end_members.size(); ++e) {
    const auto& c = inputs.end_members[e].components;
    if (std::find(c.begin(), c.end(), component) != c.end()) return e;
  }
  throw InputError("internal: component without end-member");
}

// Areal weights on the component end-members; fills settings["binder_coverage"].
std::vector<double> areal_weights(const MixInputs& inputs, const MixSettings& settings,
                                  const std::vector<std::size_t>& members, std::map<std::string, double>& info) {
  const Formulation& f = inputs.formulation;
  double binder_volume = 0.0, total_volume = 0.0, granular_area = 0.0;
  for (const Component& c : f.components) {
    total_volume += volume(c);
    if (in_binder_phase(c)) {
      binder_volume += volume(c);
    } else {
      granular_area += c.mass_percent / (c.density * effective_diameter_mm(f, c));
    }
  }
  double coverage = settings.binder_coverage ? *settings.binder_coverage
                    : f.binder_coverage      ? *f.binder_coverage
                                             : binder_volume / total_volume;
  if (!(coverage >= 0.0 && coverage <= 1.0)) throw InputError("binder coverage must lie in [0, 1]");
  if (binder_volume <= 0.0 && coverage > 0.0) {
    if (settings.binder_coverage || f.binder_coverage) throw InputError("binder coverage > 0 but no binder component");
    coverage = 0.0;
  }
  if (granular_area <= 0.0) coverage = 1.0;
  info["binder_coverage"] = coverage;
  std::vector<double> weights(members.size(), 0.0);
  for (std::size_t i = 0; i < f.components.size(); ++i) {
    const Component& c = f.components[i];
    const double a = in_binder_phase(c) ? coverage * volume(c) / binder_volume
                                        : (1.0 - coverage) * (c.mass_percent / (c.density * effective_diameter_mm(f, c))) /
                                              granular_area;
    weights[member_position(members, member_of_component(inputs, i))] += a;
  }
  return weights;
}

// Mastic method: end-members (the mastic, then the coarse classes' fits) and their area weights.
std::vector<double> mastic_weights(const MixInputs& inputs, const MixSettings& settings, std::vector<std::size_t>& members,
                                   std::map<std::string, double>& info, std::vector<std::string>& notes) {
  const Formulation& f = inputs.formulation;
  if (!f.mastic) throw InputError("the formulation has no \"mastic\" (the fit of the measured mastic)");
  std::size_t mastic_member = inputs.end_members.size();
  for (std::size_t e = 0; e < inputs.end_members.size(); ++e) {
    if (inputs.end_members[e].is_mastic) mastic_member = e;
  }
  members = {mastic_member};
  double mastic_volume = 0.0, total_volume = 0.0, coarse_area = 0.0;
  for (const Component& c : f.components) {
    total_volume += volume(c);
    if (is_coarse(f, c)) {
      coarse_area += c.mass_percent / (c.density * effective_diameter_mm(f, c));
    } else {
      mastic_volume += volume(c);
    }
  }
  for (std::size_t i = 0; i < f.components.size(); ++i) {
    if (!is_coarse(f, f.components[i])) continue;
    const std::size_t e = member_of_component(inputs, i);
    if (e == mastic_member) {
      throw InputError("coarse component '" + f.components[i].name + "' uses the mastic's fit file");
    }
    if (std::find(members.begin(), members.end(), e) == members.end()) members.push_back(e);
  }
  double m = settings.mastic_area_fraction ? *settings.mastic_area_fraction
             : f.mastic_area_fraction      ? *f.mastic_area_fraction
                                           : mastic_volume / total_volume;
  if (!(m >= 0.0 && m <= 1.0)) throw InputError("mastic area fraction must lie in [0, 1]");
  if (coarse_area <= 0.0) {
    m = 1.0;
    notes.push_back("no coarse aggregate (d_min >= " + std::to_string(f.coarse_min_size_mm) +
                    " mm): the mixture is the mastic alone");
  }
  info["mastic_area_fraction"] = m;
  std::vector<double> weights(members.size(), 0.0);
  weights[0] = m;
  for (std::size_t i = 0; i < f.components.size(); ++i) {
    const Component& c = f.components[i];
    if (!is_coarse(f, c)) continue;
    weights[member_position(members, member_of_component(inputs, i))] +=
        (1.0 - m) * c.mass_percent / (c.density * effective_diameter_mm(f, c)) / coarse_area;
  }
  return weights;
}

// Weighted least squares setup for linear fits: component values on the training geometries.
struct LinearSystem {
  std::vector<std::size_t> rows;  // geometry indices
  std::size_t M = 0, K = 0;
  std::vector<double> F;          // [row][k][m]
  std::vector<double> y;          // [row][m]
  // [row][m]: 1/sigma of each measured value (residual multiplier), or empty (unweighted).
  std::vector<double> inverse_sigma;
  double multiplier(std::size_t row, std::size_t m) const {
    return inverse_sigma.empty() ? 1.0 : inverse_sigma[row * M + m];
  }
};

LinearSystem linear_system(const MixInputs& inputs, const std::vector<std::size_t>& members, const SpectralDataset& data,
                           const std::vector<std::size_t>* training, const std::vector<double>& grid,
                           bool use_sigma) {
  if (grid != data.wavelengths) throw InputError("fitted mixing uses the data's wavelengths (no --wavelengths)");
  LinearSystem s;
  if (training) {
    s.rows = *training;
  } else {
    s.rows.resize(data.geometry_count());
    std::iota(s.rows.begin(), s.rows.end(), 0);
  }
  s.M = data.wavelength_count();
  s.K = members.size();
  std::vector<Geometry> geometries;
  for (std::size_t n : s.rows) geometries.push_back(data.geometries[n]);
  s.F.assign(s.rows.size() * s.K * s.M, 0.0);
  for (std::size_t k = 0; k < s.K; ++k) {
    const std::vector<double> v = evaluate_spectral(*inputs.end_members[members[k]].model, geometries, data.wavelengths);
    for (std::size_t r = 0; r < s.rows.size(); ++r) {
      for (std::size_t m = 0; m < s.M; ++m) s.F[(r * s.K + k) * s.M + m] = v[r * s.M + m];
    }
  }
  s.y.resize(s.rows.size() * s.M);
  for (std::size_t r = 0; r < s.rows.size(); ++r) {
    for (std::size_t m = 0; m < s.M; ++m) {
      const double y = data.value(s.rows[r], m);
      if (!std::isfinite(y)) throw InputError("the measured mixture has missing values: mixing needs complete data");
      s.y[r * s.M + m] = y;
    }
  }
  if (use_sigma && data.has_sigma()) {
    if (data.sigma.size() != data.brdf.size()) throw InputError("the measured mixture's sigma table has the wrong size");
    s.inverse_sigma.resize(s.rows.size() * s.M);
    for (std::size_t r = 0; r < s.rows.size(); ++r) {
      for (std::size_t m = 0; m < s.M; ++m) {
        const double sigma = data.sigma[s.rows[r] * s.M + m];
        if (!(sigma > 0.0) || !std::isfinite(sigma)) {
          std::ostringstream msg;
          msg << "the measured mixture's uncertainty at geometry " << s.rows[r] + 1 << ", wavelength "
              << data.wavelengths[m] << " nm is " << sigma
              << " (must be > 0 for 1/sigma^2 weighting; or use --no-sigma)";
          throw InputError(msg.str());
        }
        s.inverse_sigma[r * s.M + m] = 1.0 / sigma;
      }
    }
  }
  return s;
}

// NNLS over the wavelengths in [m0, m1) of the system, optionally sum-to-one. With sigma, weighted
// least squares: min sum ((sum_k x_k F_k - y) / sigma)^2, i.e. G = A^T W A, h = A^T W y, W = 1/sigma^2.
std::vector<double> solve_weights(const LinearSystem& s, std::size_t m0, std::size_t m1, bool sum_to_one) {
  const std::size_t K = s.K;
  std::vector<double> G(K * K, 0.0), h(K, 0.0);
  for (std::size_t r = 0; r < s.rows.size(); ++r) {
    for (std::size_t m = m0; m < m1; ++m) {
      const double y = s.y[r * s.M + m];
      const double v = s.multiplier(r, m);
      const double weight = v * v;
      for (std::size_t a = 0; a < K; ++a) {
        const double fa = weight * s.F[(r * K + a) * s.M + m];
        h[a] += fa * y;
        for (std::size_t b = 0; b < K; ++b) G[a * K + b] += fa * s.F[(r * K + b) * s.M + m];
      }
    }
  }
  if (sum_to_one) {
    // Heavily weighted extra equation sum_k x_k = 1 (the usual fully-constrained NNLS device).
    double trace = 0.0;
    for (std::size_t a = 0; a < K; ++a) trace += G[a * K + a];
    const double penalty = 1e8 * std::max(trace / K, 1e-300);
    for (std::size_t a = 0; a < K; ++a) {
      h[a] += penalty;
      for (std::size_t b = 0; b < K; ++b) G[a * K + b] += penalty;
    }
  }
  return nnls_normal(G, h, K);
}

void weight_distance(MixResult& r) {
  const double sum = std::accumulate(r.weights.begin(), r.weights.end(), 0.0);
  r.weight_sum = sum;
  double d = 0.0;
  for (std::size_t k = 0; k < r.weights.size(); ++k) {
    d += std::fabs((sum > 0.0 ? r.weights[k] / sum : 0.0) - r.formulation_weights[k]);
  }
  r.weight_distance = 0.5 * d;
}

// Cost of the shadowed mixture at one geometry: M residuals.
struct ShadowedResidual {
  const double* F;  // [k][m] of this geometry
  const double* y;  // [m]
  const double* inverse_sigma;  // [m], or nullptr (unweighted)
  std::size_t K, M;
  double path_tangent;  // tan theta_i + tan theta_r
  const std::vector<bool>* coarse;
  template <typename T>
  bool operator()(T const* const* p, T* residuals) const {
    const T* a = p[0];
    const T& s = p[1][0];
    T a_matrix(0.0), a_coarse(0.0);
    for (std::size_t k = 0; k < K; ++k) ((*coarse)[k] ? a_coarse : a_matrix) += a[k];
    using std::exp;
    const T S = exp(-s * path_tangent);
    const T boost = 1.0 + (1.0 - S) * a_matrix / (a_coarse + 1e-12);
    for (std::size_t m = 0; m < M; ++m) {
      T sum(0.0);
      for (std::size_t k = 0; k < K; ++k) sum += a[k] * ((*coarse)[k] ? boost : S) * F[k * M + m];
      residuals[m] = inverse_sigma ? (sum - y[m]) * inverse_sigma[m] : sum - y[m];
    }
    return true;
  }
};

struct SumToOneResidual {
  double scale;
  std::size_t K;
  template <typename T>
  bool operator()(T const* const* p, T* residual) const {
    T sum(0.0);
    for (std::size_t k = 0; k < K; ++k) sum += p[0][k];
    residual[0] = scale * (sum - 1.0);
    return true;
  }
};

}  // namespace

// ---------------------------------------------------------------------------------------------

std::string to_string(Method method) {
  switch (method) {
    case Method::kAreal: return "areal";
    case Method::kFitted: return "fitted";
    case Method::kMastic: return "mastic";
    case Method::kHapke: return "hapke";
    case Method::kShadowed: return "shadowed";
  }
  return "?";
}

Method method_from_string(const std::string& text) {
  for (Method m : all_methods()) {
    if (to_string(m) == text) return m;
  }
  throw InputError("unknown mixing method '" + text + "' (areal, fitted, mastic, hapke, shadowed)");
}

std::vector<Method> all_methods() {
  return {Method::kAreal, Method::kFitted, Method::kMastic, Method::kHapke, Method::kShadowed};
}

bool method_needs_data(Method method) { return method == Method::kFitted || method == Method::kShadowed; }

std::string method_description(Method method) {
  switch (method) {
    case Method::kAreal:
      return "areal mixing, area fractions from the formulation (projected area per mass 3/(2 rho D), binder coverage)";
    case Method::kFitted: return "linear mixing, weights fitted to the measured mixture by non-negative least squares";
    case Method::kMastic: return "measured mastic + coarse aggregate classes, areal mixing";
    case Method::kHapke:
      return "intimate Hapke mixing: w from white-sky albedo (IMSA H1), weights M/(rho D), phase terms by c w";
    case Method::kShadowed:
      return "nonlinear fitted mixing: coarse aggregates shadow the matrix, exp(-s (tan theta_i + tan theta_r))";
  }
  return "";
}

MixInputs load_mix_inputs(const Formulation& formulation, const FitLoader& loader_in) {
  const FitLoader loader = loader_in ? loader_in : FitLoader([](const std::string& path, const std::string& model) {
    return read_fit_file(path, model);
  });
  MixInputs inputs;
  inputs.formulation = formulation;
  const std::string where = formulation.path.empty() ? std::string("<formulation>") : formulation.path;
  auto find_or_add = [&](const std::string& path, const std::string& fit_model, const std::string& key) {
    for (std::size_t e = 0; e < inputs.end_members.size(); ++e) {
      if (inputs.end_members[e].fit_path == path && inputs.end_members[e].fit_model == fit_model) return e;
    }
    EndMember m;
    m.fit_path = path;
    m.fit_model = fit_model;
    m.name = stem_of_fit(path);
    if (!fit_model.empty()) m.name += "[" + fit_model + "]";
    // Unique names.
    std::string base = m.name;
    for (int count = 2;; ++count) {
      bool clash = false;
      for (const auto& other : inputs.end_members) clash = clash || other.name == m.name;
      if (!clash) break;
      m.name = base + "#" + std::to_string(count);
    }
    try {
      m.model = std::make_shared<const SpectralModel>(loader(path, fit_model));
    } catch (const InputError& e) {
      throw FileError(where, 0, 0, key + ": cannot use fit file '" + path + "': " + e.what());
    }
    inputs.end_members.push_back(std::move(m));
    return inputs.end_members.size() - 1;
  };
  for (std::size_t i = 0; i < formulation.components.size(); ++i) {
    const Component& c = formulation.components[i];
    const std::string path = c.fit_path.empty() ? c.fit : c.fit_path;
    const std::size_t e =
        find_or_add(path, c.fit_model, "components[" + std::to_string(i) + "] (\"" + c.name + "\").fit");
    inputs.end_members[e].components.push_back(i);
  }
  if (formulation.mastic) {
    const std::string path = formulation.mastic->fit_path.empty() ? formulation.mastic->fit : formulation.mastic->fit_path;
    const std::size_t e = find_or_add(path, formulation.mastic->fit_model, "mastic.fit");
    inputs.end_members[e].is_mastic = true;
  }
  return inputs;
}

std::vector<double> evaluate_spectral(const SpectralModel& model, const std::vector<Geometry>& geometries,
                                      const std::vector<double>& wavelengths) {
  const std::size_t n = model.model().parameter_count();
  const std::size_t sets = wavelengths.empty() ? 1 : wavelengths.size();
  std::vector<double> params(sets * n);
  for (std::size_t s = 0; s < sets; ++s) {
    const std::vector<double> p = wavelengths.empty() ? model.parameter_table() : model.parameters_at(wavelengths[s]);
    std::copy(p.begin(), p.begin() + n, params.begin() + s * n);
  }
  std::vector<double> out(geometries.size() * sets);
  model.model().evaluate_batch(geometries.data(), geometries.size(), params.data(), sets, out.data());
  return out;
}

std::vector<double> spectral_white_sky_albedo(const SpectralModel& model, const std::vector<double>& wavelengths) {
  const std::size_t n = model.model().parameter_count();
  const std::size_t sets = wavelengths.empty() ? 1 : wavelengths.size();
  std::vector<double> params(sets * n);
  for (std::size_t s = 0; s < sets; ++s) {
    const std::vector<double> p = wavelengths.empty() ? model.parameter_table() : model.parameters_at(wavelengths[s]);
    std::copy(p.begin(), p.begin() + n, params.begin() + s * n);
  }
  return white_sky_albedo(model.model(), params.data(), sets);
}

std::vector<double> mixture_white_sky_albedo(const MixInputs& inputs, const MixResult& result,
                                             const std::vector<double>& wavelengths) {
  const MixtureModel& mixture = *result.mixture;
  const SpectralModel& model = *result.model;
  const std::size_t K = mixture.component_count();
  if (mixture.kind() == MixtureKind::kShadowed || result.end_members.size() != K) {
    return spectral_white_sky_albedo(model, wavelengths);
  }
  // The end-member of each mixture component (by name).
  std::vector<const SpectralModel*> members(K, nullptr);
  for (std::size_t k = 0; k < K; ++k) {
    for (const EndMember& e : inputs.end_members) {
      if (e.name == result.end_members[k]) members[k] = e.model.get();
    }
    if (!members[k]) return spectral_white_sky_albedo(model, wavelengths);
  }
  const std::size_t sets = wavelengths.empty() ? 1 : wavelengths.size();
  std::vector<std::vector<double>> rows(sets);
  for (std::size_t q = 0; q < sets; ++q) {
    rows[q] = wavelengths.empty() ? model.parameter_table() : model.parameters_at(wavelengths[q]);
    for (std::size_t k = 0; k < K; ++k) {
      const std::vector<double> own =
          wavelengths.empty() ? members[k]->parameter_table() : members[k]->parameters_at(wavelengths[q]);
      const std::size_t offset = mixture.component_offset(k);
      if (own.size() != mixture.component(k).parameter_count() ||
          !std::equal(own.begin(), own.end(), rows[q].begin() + offset)) {
        return spectral_white_sky_albedo(model, wavelengths);
      }
    }
  }
  std::vector<std::vector<double>> member_albedo(K);
  for (std::size_t k = 0; k < K; ++k) member_albedo[k] = inputs.albedo_cache->white_sky(*members[k], wavelengths);
  const HemisphereRule& rule = white_sky_rule();
  const std::vector<double> zero(K, 0.0);
  std::vector<double> albedo(sets, 0.0);
  for (std::size_t q = 0; q < sets; ++q) {
    const double* p = rows[q].data();
    double total = 0.0;
    for (std::size_t k = 0; k < K; ++k) total += p[k];
    for (std::size_t k = 0; k < K; ++k) {
      const double e = mixture.kind() == MixtureKind::kHapke ? p[k] / total : p[k];
      albedo[q] += e * member_albedo[k][q];
    }
    if (mixture.kind() == MixtureKind::kHapke) {
      for (std::size_t n = 0; n < rule.geometries.size(); ++n) {
        albedo[q] += rule.weights[n] * mixture.combine(p, rule.geometries[n], zero.data(), nullptr);
      }
    }
  }
  return albedo;
}

std::vector<double> nnls_normal(const std::vector<double>& G, const std::vector<double>& h, std::size_t K) {
  std::vector<double> x(K, 0.0);
  std::vector<bool> passive(K, false);
  double scale = 0.0;
  for (std::size_t a = 0; a < K; ++a) scale = std::max(scale, std::fabs(h[a]));
  const double tol = 1e-13 * std::max(scale, 1e-300);
  auto gradient = [&](std::size_t j) {
    double g = h[j];
    for (std::size_t b = 0; b < K; ++b) g -= G[j * K + b] * x[b];
    return g;
  };
  auto solve_passive = [&](std::vector<double>& z) {
    std::vector<std::size_t> idx;
    for (std::size_t a = 0; a < K; ++a) {
      if (passive[a]) idx.push_back(a);
    }
    Eigen::MatrixXd A(idx.size(), idx.size());
    Eigen::VectorXd b(idx.size());
    for (std::size_t i = 0; i < idx.size(); ++i) {
      b(i) = h[idx[i]];
      for (std::size_t j = 0; j < idx.size(); ++j) A(i, j) = G[idx[i] * K + idx[j]];
    }
    const Eigen::VectorXd sol = A.completeOrthogonalDecomposition().solve(b);
    std::fill(z.begin(), z.end(), 0.0);
    for (std::size_t i = 0; i < idx.size(); ++i) z[idx[i]] = sol(i);
  };
  std::vector<double> z(K);
  for (std::size_t outer = 0; outer < 3 * K + 10; ++outer) {
    std::size_t best = K;
    double best_gradient = tol;
    for (std::size_t j = 0; j < K; ++j) {
      if (passive[j]) continue;
      const double g = gradient(j);
      if (g > best_gradient) {
        best_gradient = g;
        best = j;
      }
    }
    if (best == K) break;
    passive[best] = true;
    for (std::size_t inner = 0; inner < 3 * K + 10; ++inner) {
      solve_passive(z);
      bool feasible = true;
      for (std::size_t a = 0; a < K; ++a) feasible = feasible && (!passive[a] || z[a] > 0.0);
      if (feasible) {
        x = z;
        break;
      }
      double alpha = 1.0;
      for (std::size_t a = 0; a < K; ++a) {
        if (passive[a] && z[a] <= 0.0) alpha = std::min(alpha, x[a] / (x[a] - z[a]));
      }
      for (std::size_t a = 0; a < K; ++a) {
        x[a] += alpha * (z[a] - x[a]);
        if (passive[a] && x[a] <= 1e-15 * std::max(1.0, scale)) {
          passive[a] = false;
          x[a] = 0.0;
        }
      }
    }
  }
  return x;
}

MixResult mix(const MixInputs& inputs, Method method, const MixSettings& settings, const SpectralDataset* data,
              const std::vector<std::size_t>* training) {
  const Formulation& f = inputs.formulation;
  MixResult r;
  r.method = method;
  r.description = method_description(method);
  if (method_needs_data(method) && !data) {
    throw InputError("mixing method '" + to_string(method) + "' is fitted to a measured mixture: give --data");
  }
  std::vector<std::size_t> members = component_members(inputs);
  std::vector<bool> coarse;

  if (method == Method::kMastic) {
    if (!f.mastic) {
      throw InputError("method 'mastic' needs the formulation key \"mastic\" (the fit of the measured mastic)");
    }
    const std::vector<double> weights = mastic_weights(inputs, settings, members, r.settings, r.notes);
    const std::vector<double> grid = output_grid(inputs, members, settings, data);
    r.mixture = make_mixture(MixtureKind::kLinear, inputs, members);
    r.model = std::make_shared<const SpectralModel>(
        build_table(r.mixture, inputs, members, grid, [&](std::size_t, double* row) {
          std::copy(weights.begin(), weights.end(), row);
        }));
    r.weights = weights;
  } else if (method == Method::kAreal) {
    const std::vector<double> weights = areal_weights(inputs, settings, members, r.settings);
    const std::vector<double> grid = output_grid(inputs, members, settings, data);
    r.mixture = make_mixture(MixtureKind::kLinear, inputs, members);
    r.model = std::make_shared<const SpectralModel>(
        build_table(r.mixture, inputs, members, grid, [&](std::size_t, double* row) {
          std::copy(weights.begin(), weights.end(), row);
        }));
    r.weights = weights;
  } else if (method == Method::kHapke) {
    std::vector<double> c(members.size(), 0.0);
    double total = 0.0;
    for (std::size_t i = 0; i < f.components.size(); ++i) {
      const Component& comp = f.components[i];
      const double x = comp.mass_percent / (comp.density * effective_diameter_mm(f, comp));
      c[member_position(members, member_of_component(inputs, i))] += x;
      total += x;
    }
    for (double& x : c) x /= total;
    const std::vector<double> grid = output_grid(inputs, members, settings, data);
    // Single-scattering albedos: invert the white-sky albedo of each end-member at each wavelength.
    const std::size_t rows = grid.empty() ? 1 : grid.size();
    std::vector<std::vector<double>> w(members.size(), std::vector<double>(rows));
    for (std::size_t k = 0; k < members.size(); ++k) {
      const EndMember& em = inputs.end_members[members[k]];
      const std::vector<double> albedo = inputs.albedo_cache->white_sky(*em.model, grid);
      for (std::size_t q = 0; q < rows; ++q) {
        try {
          w[k][q] = invert_imsa_white_sky_albedo(albedo[q]);
        } catch (const InputError& e) {
          std::ostringstream msg;
          msg << "hapke mixing: end-member '" << em.name << "'";
          if (!grid.empty()) msg << " at " << grid[q] << " nm";
          msg << ": " << e.what();
          throw InputError(msg.str());
        }
      }
    }
    r.mixture = make_mixture(MixtureKind::kHapke, inputs, members);
    const std::size_t K = members.size();
    r.model = std::make_shared<const SpectralModel>(
        build_table(r.mixture, inputs, members, grid, [&](std::size_t q, double* row) {
          for (std::size_t k = 0; k < K; ++k) {
            row[k] = c[k];
            row[K + k] = w[k][q];
          }
        }));
    r.weights = c;
    r.settings["binder_film_thickness_mm"] = f.binder_film_thickness_mm;
  } else {
    // fitted, shadowed
    std::map<std::string, double> info;
    if (method == Method::kShadowed && f.mastic) {
      // The report's structure: the matrix between the coarse grains is the measured mastic.
      r.formulation_weights = mastic_weights(inputs, settings, members, info, r.notes);
    } else {
      r.formulation_weights = areal_weights(inputs, settings, members, info);
    }
    const std::vector<double> grid = output_grid(inputs, members, settings, data);
    const LinearSystem sys = linear_system(inputs, members, *data, training, grid, settings.use_sigma);
    const std::size_t K = members.size();
    if (sys.rows.size() * (settings.per_wavelength ? 1 : sys.M) < K) {
      throw InputError("too few measured values to fit " + std::to_string(K) + " weights");
    }
    if (method == Method::kFitted) {
      std::vector<std::vector<double>> table;
      if (settings.per_wavelength) {
        for (std::size_t m = 0; m < sys.M; ++m) table.push_back(solve_weights(sys, m, m + 1, settings.sum_to_one));
      } else {
        table.assign(sys.M, solve_weights(sys, 0, sys.M, settings.sum_to_one));
      }
      r.weights.assign(K, 0.0);
      for (const auto& row : table) {
        for (std::size_t k = 0; k < K; ++k) r.weights[k] += row[k] / table.size();
      }
      r.mixture = make_mixture(MixtureKind::kLinear, inputs, members);
      r.model = std::make_shared<const SpectralModel>(
          build_table(r.mixture, inputs, members, grid, [&](std::size_t q, double* row) {
            std::copy(table[q].begin(), table[q].end(), row);
          }));
      r.settings["per_wavelength"] = settings.per_wavelength ? 1.0 : 0.0;
      r.settings["sigma_weighted"] = sys.inverse_sigma.empty() ? 0.0 : 1.0;
      r.settings["sum_to_one"] = settings.sum_to_one ? 1.0 : 0.0;
    } else {
      for (std::size_t e : members) {
        const EndMember& em = inputs.end_members[e];
        bool all_coarse = !em.is_mastic && !em.components.empty();
        for (std::size_t i : em.components) all_coarse = all_coarse && is_coarse(f, f.components[i]);
        coarse.push_back(all_coarse);
      }
      if (std::none_of(coarse.begin(), coarse.end(), [](bool b) { return b; })) {
        throw InputError("method 'shadowed' needs a coarse aggregate end-member (a fit file used only by aggregates "
                         "with d_min_mm >= coarse_min_size_mm)");
      }
      if (std::all_of(coarse.begin(), coarse.end(), [](bool b) { return b; })) {
        throw InputError("method 'shadowed' needs a matrix end-member (binder, mastic or fines) besides the coarse ones");
      }
      std::vector<double> a = solve_weights(sys, 0, sys.M, settings.sum_to_one);
      double a_sum = std::accumulate(a.begin(), a.end(), 0.0);
      if (!(a_sum > 0.0)) a = r.formulation_weights;
      for (double& x : a) x = std::max(x, 1e-6);
      double s = 0.0;
      ceres::Problem problem;
      for (std::size_t row = 0; row < sys.rows.size(); ++row) {
        const Geometry& g = data->geometries[sys.rows[row]];
        const double ci = std::max(g.cos_theta_i(), 1e-9), cr = std::max(g.cos_theta_r(), 1e-9);
        const double path = std::sqrt(std::max(0.0, 1.0 - ci * ci)) / ci + std::sqrt(std::max(0.0, 1.0 - cr * cr)) / cr;
        auto* functor = new ShadowedResidual{sys.F.data() + row * K * sys.M, sys.y.data() + row * sys.M,
                                             sys.inverse_sigma.empty() ? nullptr : sys.inverse_sigma.data() + row * sys.M,
                                             K, sys.M, path, &coarse};
        auto* cost = new ceres::DynamicAutoDiffCostFunction<ShadowedResidual, 4>(functor);
        cost->AddParameterBlock(static_cast<int>(K));
        cost->AddParameterBlock(1);
        cost->SetNumResiduals(static_cast<int>(sys.M));
        problem.AddResidualBlock(cost, nullptr, a.data(), &s);
      }
      if (settings.sum_to_one) {
        // Scale of the penalty: the (weighted) data norm per geometry.
        double y2 = 0.0;
        for (std::size_t i = 0; i < sys.y.size(); ++i) {
          const double v = sys.inverse_sigma.empty() ? 1.0 : sys.inverse_sigma[i];
          y2 += sys.y[i] * sys.y[i] * v * v;
        }
        auto* cost = new ceres::DynamicAutoDiffCostFunction<SumToOneResidual, 4>(
            new SumToOneResidual{1e4 * std::sqrt(y2 / std::max<std::size_t>(1, sys.rows.size())), K});
        cost->AddParameterBlock(static_cast<int>(K));
        cost->SetNumResiduals(1);
        problem.AddResidualBlock(cost, nullptr, a.data());
      }
      for (std::size_t k = 0; k < K; ++k) {
        problem.SetParameterLowerBound(a.data(), static_cast<int>(k), 0.0);
        problem.SetParameterUpperBound(a.data(), static_cast<int>(k), 1e3);
      }
      problem.SetParameterLowerBound(&s, 0, 0.0);
      problem.SetParameterUpperBound(&s, 0, 100.0);
      ceres::Solver::Options options;
      options.linear_solver_type = ceres::DENSE_QR;
      options.max_num_iterations = 200;
      options.function_tolerance = 1e-12;
      options.parameter_tolerance = 1e-12;
      options.num_threads = 1;
      // Multi-start over s (the only nonlinear unknown); weights start from the NNLS solution.
      const std::vector<double> a_start = a;
      std::vector<double> best_a;
      double best_s = 0.0, best_cost = std::numeric_limits<double>::infinity();
      ceres::Solver::Summary best_summary;
      for (double s_start : {0.0, 0.1, 0.3, 1.0, 3.0}) {
        a = a_start;
        s = s_start;
        ceres::Solver::Summary summary;
        ceres::Solve(options, &problem, &summary);
        if (summary.IsSolutionUsable() && summary.final_cost < best_cost) {
          best_cost = summary.final_cost;
          best_a = a;
          best_s = s;
          best_summary = summary;
        }
      }
      if (best_a.empty()) throw InputError("method 'shadowed': the fit failed from every start");
      a = best_a;
      s = best_s;
      if (best_summary.termination_type != ceres::CONVERGENCE) {
        r.notes.push_back("shadowed fit did not converge: " + best_summary.message);
      }
      r.weights = a;
      r.settings["shadowing"] = s;
      r.settings["sigma_weighted"] = sys.inverse_sigma.empty() ? 0.0 : 1.0;
      r.settings["sum_to_one"] = settings.sum_to_one ? 1.0 : 0.0;
      r.mixture = make_mixture(MixtureKind::kShadowed, inputs, members, coarse);
      r.model = std::make_shared<const SpectralModel>(
          build_table(r.mixture, inputs, members, grid, [&](std::size_t, double* row) {
            std::copy(a.begin(), a.end(), row);
            row[K] = s;
          }));
    }
    weight_distance(r);
  }
  for (std::size_t e : members) {
    r.end_members.push_back(inputs.end_members[e].name);
    r.end_member_fits.push_back(inputs.end_members[e].fit_path);
  }
  return r;
}

Comparison compare_method(const MixInputs& inputs, Method method, const MixSettings& settings,
                          const SpectralDataset& data, int folds, unsigned seed, const SpectralModel* reference) {
  const std::size_t N = data.geometry_count();
  const std::size_t M = data.wavelength_count();
  if (folds < 2) throw InputError("--folds must be at least 2");
  if (N < static_cast<std::size_t>(folds)) {
    throw InputError("the measured mixture has " + std::to_string(N) + " geometries, fewer than --folds " +
                     std::to_string(folds));
  }
  Comparison c;
  c.method = method;
  c.folds = folds;
  c.result = mix(inputs, method, settings, &data);
  // Errors of predictions (N_rows x M, rows = geometry indices) against the data.
  auto errors = [&](const std::vector<double>& predicted, const std::vector<std::size_t>& rows, double& sse,
                    double& sum_abs) {
    for (std::size_t r = 0; r < rows.size(); ++r) {
      for (std::size_t m = 0; m < M; ++m) {
        const double y = data.value(rows[r], m);
        const double d = predicted[r * M + m] - y;
        sse += d * d;
        sum_abs += std::fabs(y);
      }
    }
  };
  std::vector<std::size_t> all(N);
  std::iota(all.begin(), all.end(), 0);
  const std::vector<double> in_sample = evaluate_spectral(*c.result.model, data.geometries, data.wavelengths);
  {
    double sse = 0.0, sum_abs = 0.0;
    errors(in_sample, all, sse, sum_abs);
    c.rmse_in_sample = std::sqrt(sse / (N * M));
    c.relative_rmse_in_sample = c.rmse_in_sample / (sum_abs / (N * M));
  }
  c.fold_of_geometry.assign(N, 0);
  if (!method_needs_data(method)) {
    c.predicted = in_sample;
  } else {
    c.predicted.assign(N * M, std::numeric_limits<double>::quiet_NaN());
    std::vector<std::size_t> order = all;
    std::mt19937 rng(seed);
    std::shuffle(order.begin(), order.end(), rng);
    for (int fold = 0; fold < folds; ++fold) {
      std::vector<std::size_t> train, test;
      for (std::size_t i = 0; i < N; ++i) (static_cast<int>(i % folds) == fold ? test : train).push_back(order[i]);
      const MixResult part = mix(inputs, method, settings, &data, &train);
      std::vector<Geometry> geometries;
      for (std::size_t n : test) geometries.push_back(data.geometries[n]);
      const std::vector<double> predicted = evaluate_spectral(*part.model, geometries, data.wavelengths);
      for (std::size_t t = 0; t < test.size(); ++t) {
        std::copy(predicted.begin() + t * M, predicted.begin() + (t + 1) * M, c.predicted.begin() + test[t] * M);
        c.fold_of_geometry[test[t]] = fold + 1;
      }
    }
  }
  {
    double sse = 0.0, sum_abs = 0.0;
    errors(c.predicted, all, sse, sum_abs);
    c.rmse = std::sqrt(sse / (N * M));
    c.relative_rmse = c.rmse / (sum_abs / (N * M));
  }
  if (data.has_sigma()) {
    if (data.sigma.size() != N * M) throw InputError("the measured mixture's sigma table has the wrong size");
    double chi2 = 0.0;
    bool valid = true;
    for (std::size_t i = 0; i < N * M && valid; ++i) {
      const double sigma = data.sigma[i];
      if (!(sigma > 0.0) || !std::isfinite(sigma)) {
        // Keep the comparison, say why chi^2 is missing.
        std::ostringstream msg;
        msg << "held-out chi^2 not computed: the measured mixture's uncertainty at geometry " << i / M + 1
            << ", wavelength " << data.wavelengths[i % M] << " nm is " << sigma << " (must be > 0)";
        c.result.notes.push_back(msg.str());
        valid = false;
        break;
      }
      const double z = (c.predicted[i] - data.brdf[i]) / sigma;
      chi2 += z * z;
    }
    if (valid) c.chi2_reduced = chi2 / (N * M);
  }
  // Albedo summary on at most kAlbedoWavelengths wavelengths evenly spaced in index (the quadrature
  // costs ~14k model evaluations per wavelength).
  std::vector<double> albedo_wavelengths;
  const std::size_t n_albedo = std::min<std::size_t>(M, kAlbedoWavelengths);
  for (std::size_t i = 0; i < n_albedo; ++i) {
    const std::size_t index = n_albedo == 1 ? 0 : (i * (M - 1) + (n_albedo - 1) / 2) / (n_albedo - 1);
    if (albedo_wavelengths.empty() || albedo_wavelengths.back() != data.wavelengths[index]) {
      albedo_wavelengths.push_back(data.wavelengths[index]);
    }
  }
  const std::vector<double> albedo = mixture_white_sky_albedo(inputs, c.result, albedo_wavelengths);
  c.albedo = std::accumulate(albedo.begin(), albedo.end(), 0.0) / albedo.size();
  if (reference) {
    const std::vector<double> ref = spectral_white_sky_albedo(*reference, albedo_wavelengths);
    c.albedo_reference = std::accumulate(ref.begin(), ref.end(), 0.0) / ref.size();
    c.albedo_difference = c.albedo - c.albedo_reference;
  }
  return c;
}

}  // namespace roadbrdf::mixing
