#include "roadbrdf/mixing/method_support.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <set>
#include <sstream>

#include "roadbrdf/core/error.h"
#include "roadbrdf/mixing/nnls.h"

namespace roadbrdf::mixing::detail {

namespace {

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

}  // namespace

// The output wavelength grid of a method over the given end-members.
std::vector<double> output_grid(const MixInputs& inputs, const std::vector<std::size_t>& members,
                                const MixSettings& settings, const SpectralDataset* data) {
  std::vector<const SpectralModel*> models;
  models.reserve(members.size());
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
                                                 const std::vector<bool>& coarse) {
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
    const double a =
        in_binder_phase(c)
            ? coverage * volume(c) / binder_volume
            : (1.0 - coverage) * (c.mass_percent / (c.density * effective_diameter_mm(f, c))) / granular_area;
    weights[member_position(members, member_of_component(inputs, i))] += a;
  }
  return weights;
}

// Mastic method: end-members (the mastic, then the coarse classes' fits) and their area weights.
std::vector<double> mastic_weights(const MixInputs& inputs, const MixSettings& settings,
                                   std::vector<std::size_t>& members, std::map<std::string, double>& info,
                                   std::vector<std::string>& notes) {
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

LinearSystem linear_system(const MixInputs& inputs, const std::vector<std::size_t>& members,
                           const SpectralDataset& data, const std::vector<std::size_t>* training,
                           const std::vector<double>& grid, bool use_sigma) {
  if (grid != data.wavelengths)
    throw InputError("fitted mixing uses the data's wavelengths (leave the settings' wavelengths empty)");
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
    const std::vector<double> v =
        evaluate_spectral(*inputs.end_members[members[k]].model, geometries, data.wavelengths);
    for (std::size_t r = 0; r < s.rows.size(); ++r) {
      for (std::size_t m = 0; m < s.M; ++m) s.F[(r * s.K + k) * s.M + m] = v[r * s.M + m];
    }
  }
  s.y.resize(s.rows.size() * s.M);
  bool any_missing = false;
  for (std::size_t r = 0; r < s.rows.size(); ++r) {
    for (std::size_t m = 0; m < s.M; ++m) {
      const double y = data.value(s.rows[r], m);
      if (std::isnan(y)) {
        any_missing = true;  // a measurement not made: multiplier 0 below
        s.y[r * s.M + m] = 0.0;
        continue;
      }
      if (!std::isfinite(y)) {
        std::ostringstream msg;
        msg << "the measured mixture's value at geometry " << s.rows[r] + 1 << ", wavelength " << data.wavelengths[m]
            << " nm is " << y << " (not a finite number)";
        throw InputError(msg.str());
      }
      s.y[r * s.M + m] = y;
      ++s.measured;
    }
  }
  s.sigma_weighted = use_sigma && data.has_sigma();
  if (s.sigma_weighted) {
    if (data.sigma.size() != data.brdf.size())
      throw InputError("the measured mixture's sigma table has the wrong size");
    s.inverse_sigma.resize(s.rows.size() * s.M);
    for (std::size_t r = 0; r < s.rows.size(); ++r) {
      for (std::size_t m = 0; m < s.M; ++m) {
        const double sigma = data.sigma[s.rows[r] * s.M + m];
        if (std::isnan(data.value(s.rows[r], m))) {
          s.inverse_sigma[r * s.M + m] = 0.0;
          continue;
        }
        if (!(sigma > 0.0) || !std::isfinite(sigma)) {
          std::ostringstream msg;
          msg << "the measured mixture's uncertainty at geometry " << s.rows[r] + 1 << ", wavelength "
              << data.wavelengths[m] << " nm is " << sigma
              << " (must be > 0 for 1/sigma^2 weighting; or fit unweighted: `use_sigma`)";
          throw InputError(msg.str());
        }
        s.inverse_sigma[r * s.M + m] = 1.0 / sigma;
      }
    }
  } else if (any_missing) {
    // Unweighted, but the missing values get a zero multiplier (masked out of the fit).
    s.inverse_sigma.assign(s.rows.size() * s.M, 1.0);
    for (std::size_t r = 0; r < s.rows.size(); ++r) {
      for (std::size_t m = 0; m < s.M; ++m) {
        if (std::isnan(data.value(s.rows[r], m))) s.inverse_sigma[r * s.M + m] = 0.0;
      }
    }
  }
  return s;
}

LinearSystem fitted_system(const MethodCall& call, const std::vector<std::size_t>& members, std::vector<double>& grid) {
  grid = output_grid(call.inputs, members, call.settings, call.data);
  LinearSystem sys = linear_system(call.inputs, members, *call.data, call.training, grid, call.settings.use_sigma);
  const std::size_t K = members.size();
  std::size_t fewest = sys.measured;  // measured values per solve
  if (call.settings.per_wavelength) {
    for (std::size_t m = 0; m < sys.M; ++m) {
      std::size_t count = 0;
      for (std::size_t r = 0; r < sys.rows.size(); ++r) count += sys.multiplier(r, m) != 0.0 ? 1 : 0;
      fewest = std::min(fewest, count);
    }
  }
  if (fewest < K) {
    throw InputError("too few measured values to fit " + std::to_string(K) + " weights");
  }
  return sys;
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

}  // namespace roadbrdf::mixing::detail
